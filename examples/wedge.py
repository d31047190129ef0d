#!/usr/bin/python3
"""A parameter wedge: the same scene run once per value of one parameter,
with a table of the metrics each run reached.

    PYTHONPATH=build/python /usr/bin/python3 examples/wedge.py \
        --param control.attraction_g --values 4.35,8.7,17.4 --seconds 2 --out wedge.csv

Each row: the value, then the final iou and coverage, the mean iou over the
last quarter of the run, the highest max_speed and the mean density_error.
"""
import argparse
import csv
import sys

import flowform


def params_overlay(path, value):
    """'control.attraction', 0.1 -> {'control': {'attraction': 0.1}}"""
    keys = path.split(".")
    out = value
    for k in reversed(keys):
        out = {k: out}
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default=None, help="scene file (default: the built-in default scene)")
    ap.add_argument("--param", default="control.attraction_g", help="a key of the scene's params, e.g. fluid.viscosity")
    ap.add_argument("--values", default="4.35,8.7,17.4", help="comma-separated values")
    ap.add_argument("--seconds", type=float, default=2.0, help="simulated seconds per run")
    ap.add_argument("--steps", type=int, default=0, help="steps per run instead of --seconds")
    ap.add_argument("--backend", default="cpu")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--out", default="wedge.csv", help="the metrics table (CSV)")
    a = ap.parse_args()
    values = []
    for v in a.values.split(","):
        if v.strip():
            try:
                values.append(float(v))
            except ValueError:
                sys.exit("wedge.py: --values: '%s' is not a number" % v.strip())
    if not values:
        sys.exit("wedge.py: --values: give at least one number")
    if a.steps < 0:
        sys.exit("wedge.py: --steps: must be > 0 (got %d)" % a.steps)
    if a.steps == 0 and not a.seconds > 0.0:
        sys.exit("wedge.py: --seconds: must be > 0 (got %g)" % a.seconds)
    open(a.out, "a").close()  # fail now on a file it cannot write, not after the runs
    rows = []
    for v in values:
        # From the start, as in a scene file: set_params after the first
        # target is placed would leave what only the first placement reads
        # (shape_matching.blend_first, the fluid's spacing) at the scene's value.
        sim = flowform.Simulation(a.scene, backend=a.backend, threads=a.threads, params=params_overlay(a.param, v))
        m = sim.run(steps=a.steps) if a.steps > 0 else sim.run(seconds=a.seconds)
        n = len(m["iou"])
        tail = m["iou"][n - max(1, n // 4):]
        rows.append([v, m["iou"][-1], m["coverage"][-1], tail.mean(), m["max_speed"].max(),
                     m["density_error"].mean(), sim.time])
        print("%s = %-10g iou %.4f  coverage %.4f  (t = %.3f s)" % (a.param, v, rows[-1][1], rows[-1][2], sim.time))
    with open(a.out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow([a.param, "final_iou", "final_coverage", "mean_iou_last_quarter", "peak_max_speed",
                    "mean_density_error", "time"])
        for r in rows:
            w.writerow(["%.9g" % x for x in r])
    print("wrote", a.out)


if __name__ == "__main__":
    try:
        main()
    except flowform.Error as e:
        sys.exit("wedge.py: %s" % e)
    except OSError as e:
        sys.exit("wedge.py: %s: %s" % (e.filename, e.strerror))
