#!/usr/bin/env python3
"""tall_box_resolution.py - the scene of
NormalisedPull.TwiceTheParticlesGiveTheSameIouCurveWithTheDerivedCount
(tests/test_normalised_pull.cpp) as scene files, at any particle count, and
the fluid's particle layers in an exported frame (docs/PERFORMANCE.md, "Why
the first climb differs between resolutions").

  write FOLDER SIDE ...
      writes FOLDER/tallbox_SIDE.json: a SIDE^3 block of fluid filling the
      same 0.063 m cube on the floor of a 0.2 x 0.25 x 0.2 m container
      (the particle mass and smoothing radius scaled with the spacing), a
      1 x 2 x 1 box target of its volume, on the default preset with
      control.auto_count 465 (the 12^3 block's count), as the test makes it.

  layers FRAME.ply [--half W]
      prints the fluid's particle layers (clusters of y separated by more
      than 1.2 mm) within W (default 0.015 m) of the block's vertical axis
      in a binary PLY frame of `flowform run --export DIR --format ply`, and
      the gaps between them in rest spacings.

Usage (the commands of docs/PERFORMANCE.md):
  python3 bench/tall_box_resolution.py write build/tb 12 15
  ./build/flowform run build/tb/tallbox_12.json --backend cpu --threads 2 --seconds 1.5 --metrics build/tb/tallbox_12.csv
  python3 bench/resolution_scale.py compare build/tb/tallbox_12.csv build/tb/tallbox_15.csv --until 1.5
"""
import json
import math
import os
import struct
import sys

SPACING = (0.0002 / 800.0) ** (1.0 / 3.0)  # the water preset's rest spacing (resolution_scale.py)
MASS, H = 1000.0 * SPACING ** 3, 2.0 * SPACING
REF = 10  # the test's reference block: 10^3 particles at the preset's spacing


def scene(side):
    scale = REF / side
    extent = side * SPACING * scale
    return {
        "name": "tallbox_%d" % side,
        "preset": "default",
        "duration": 1.5,
        "container": {"min": [0.0, 0.0, 0.0], "max": [0.2, 0.25, 0.2]},
        "fluid": [{"origin": [0.1 - 0.5 * extent, 0.0, 0.1 - 0.5 * extent], "dims": [side, side, side]}],
        "params": {
            "fluid": {"particle_mass": MASS * scale ** 3, "smoothing_radius": H * scale},
            "control": {"normalise": 1, "auto_count": int(math.ceil(1728.0 / 1.55 ** 3))},
        },
        "target": {"shape": "box", "size": [1, 2, 1]},
    }


def write(folder, sides):
    os.makedirs(folder, exist_ok=True)
    for s in sides:
        path = os.path.join(folder, "tallbox_%d.json" % s)
        with open(path, "w") as f:
            json.dump(scene(s), f, indent=1)
        print("%s: %d fluid particles" % (path, s ** 3))


def read_ply(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").split("\n")
    n, props = 0, []
    for line in header:
        w = line.split()
        if w[:2] == ["element", "vertex"]:
            n = int(w[2])
        elif w[:1] == ["property"]:
            props.append((w[1], w[2]))
    fmt = "<" + "".join({"float": "f", "float32": "f", "int": "i", "int32": "i", "uint": "I"}[t] for t, _ in props)
    size = struct.calcsize(fmt)
    names = [p for _, p in props]
    return [dict(zip(names, struct.unpack_from(fmt, data, end + i * size))) for i in range(n)]


def layers(path, half):
    pts = read_ply(path)
    xs = [p["x"] for p in pts]
    zs = [p["z"] for p in pts]
    cx, cz = 0.5 * (min(xs) + max(xs)), 0.5 * (min(zs) + max(zs))
    ys = sorted(p["y"] for p in pts if abs(p["x"] - cx) < half and abs(p["z"] - cz) < half)
    groups = [[ys[0]]]
    for y in ys[1:]:
        if y - groups[-1][-1] <= 0.0012:
            groups[-1].append(y)
        else:
            groups.append([y])
    means = [sum(g) / len(g) for g in groups]
    # rest spacing of this frame's particles: the cube's side over the particles across it
    side = round(len(pts) ** (1.0 / 3.0))
    s = 0.063 / side
    print("%d particles (%d^3), spacing %.2f mm; layers (mm, particles):" % (len(pts), side, 1000 * s))
    print(" ".join("%.1f(%d)" % (1000 * m, len(g)) for m, g in zip(means, groups)))
    print("gaps / spacing: " + " ".join("%.2f" % ((b - a) / s) for a, b in zip(means, means[1:])))


def main(argv):
    if len(argv) >= 3 and argv[0] == "write":
        write(argv[1], [int(a) for a in argv[2:]])
    elif len(argv) >= 2 and argv[0] == "layers":
        half = float(argv[argv.index("--half") + 1]) if "--half" in argv else 0.015
        layers(argv[1], half)
    else:
        print(__doc__)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
