#!/usr/bin/python3
"""Targets changed from a script: keyframes of (time, target) applied while
the fluid runs, with the metrics of every step written to a CSV and,
optionally, frames exported.

    PYTHONPATH=build/python /usr/bin/python3 examples/keyframes.py \
        --keys "0:sphere,2:box,4:torus" --seconds 6 --metrics keyframes.csv --export frames

A target is any target in scene syntax: sphere, box, torus, capsule or a mesh
file (bunny.obj, found next to the scene or along FLOWFORM_MESH_PATH).
"""
import argparse
import sys

import numpy as np

import flowform


def parse_keys(text):
    keys = []
    for item in text.split(","):
        t, _, target = item.partition(":")
        if not target:
            sys.exit("keyframes.py: --keys: '%s' is not TIME:TARGET" % item)
        try:
            time = float(t)
        except ValueError:
            time = float("nan")
        if not time >= 0.0:
            sys.exit("keyframes.py: --keys: '%s': the time must be a number of seconds >= 0" % item)
        keys.append((time, target.strip()))
    return sorted(keys)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default=None, help="scene file (default: the built-in default scene)")
    ap.add_argument("--keys", default="0:sphere,2:box,4:torus", help="TIME:TARGET,... in simulated seconds")
    ap.add_argument("--seconds", type=float, default=6.0, help="simulated seconds in all")
    ap.add_argument("--backend", default="cpu")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--metrics", default="keyframes.csv", help="per-step metrics (CSV)")
    ap.add_argument("--export", default=None, help="folder for PLY frames (10 per simulated second)")
    a = ap.parse_args()
    if not a.seconds > 0.0:
        sys.exit("keyframes.py: --seconds: must be > 0 (got %g)" % a.seconds)
    keys = parse_keys(a.keys)
    open(a.metrics, "a").close()  # fail now on a file it cannot write, not after the run
    sim = flowform.Simulation(a.scene, backend=a.backend, threads=a.threads)
    exporter = flowform.Exporter(a.export, formats="ply", fps=10.0) if a.export else None
    if exporter:
        exporter.write(sim)
    parts = []
    for t, target in keys:
        if t > a.seconds:
            break
        if t > sim.time + 1e-9:
            parts.append(run_to(sim, t, exporter))
        sim.set_target(target)
        print("t = %.3f s: target %s (%d control particles)" % (sim.time, sim.target, len(sim.control()["s"])))
    if a.seconds > sim.time + 1e-9:
        parts.append(run_to(sim, a.seconds, exporter))
    names = list(parts[0].keys()) if parts else []
    with open(a.metrics, "w") as f:
        f.write(",".join(names) + "\n")
        for p in parts:
            for row in zip(*(p[n] for n in names)):
                f.write(",".join("%.9g" % x for x in row) + "\n")
    m = sim.metrics
    print("t = %.3f s: iou %.4f coverage %.4f; metrics in %s" % (sim.time, m["iou"], m["coverage"], a.metrics))


def run_to(sim, t, exporter):
    """Runs to simulated time t, exporting when a frame is due."""
    if exporter is None:
        return sim.run(until=t)
    chunks = []
    while sim.time < t - 1e-9:
        chunks.append(sim.run(steps=1))
        exporter.write_if_due(sim)
    return {k: np.concatenate([c[k] for c in chunks]) for k in chunks[0]}


if __name__ == "__main__":
    try:
        main()
    except flowform.Error as e:
        sys.exit("keyframes.py: %s" % e)
    except OSError as e:
        sys.exit("keyframes.py: %s: %s" % (e.filename, e.strerror))
