#!/usr/bin/env python3
"""unseen_shapes.py - a generated set of target shapes of the four kinds issue
10 says users pick, none of which the project was tuned on (docs/RESULTS.md,
"The unseen set"):

  letters   extruded block letters (A, H, K, L, X, Y, S and O; A and O with a
            hole), strokes rasterised as thick segments and arcs, with varied
            stroke width and depth, standing upright or lying on their face
  discs     thin discs (surfaces of revolution) 10 to 22 times as wide as
            thick (22: about 2 control spacings thick at 12,000 particles),
            standing on the rim, lying flat or tilted
  dumbbells two balls of unequal radii joined by a thin, long bar, lying,
            tilted or one lump above the other, and two boxes and a bar
  figures   thin-limbed figures rasterised from capsule skeletons: arms
            spread, raised or one up, legs apart, limbs 1/10 to 1/18 of the
            height thick, and a tall thin tower and a tree

Each shape is one closed, consistently oriented triangle mesh, NAME.obj, with
a water-preset scene NAME.json (12,000 fluid particles in a 20 x 30 x 20
block, no control_count) whose container is sized from the shape's extent at
the fluid's volume. The proportions come from the rules below, not from runs.

  python3 bench/unseen_shapes.py DIR              write the meshes and scenes
  python3 bench/unseen_shapes.py --run DIR [NAME...]
        also run each scene for 3 s (water, OpenMP, 2 threads, one after
        another) into DIR/NAME.csv, then print the table
  python3 bench/unseen_shapes.py --table DIR      print the table of DIR/*.csv

The table is iou / filled / stray / filled_thin at 3 s, the most velocity
clamps of any step and where the shape stands at 3 s (base_height: its
lowest point above the floor; tilt), as docs/RESULTS.md shows it.
"""
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from thin_shapes import blocks, dumbbell_profile, revolve, write  # noqa: E402

SPACING = (0.00025 / 1000.0) ** (1.0 / 3.0)  # the water preset's rest spacing
FLUID = (20, 30, 20)


# ---------------------------------------------------------------- rasterising
def seg_dist(p, a, b):
    """The distance from point p to the segment a-b (any dimension)."""
    ab = [bb - aa for aa, bb in zip(a, b)]
    ap = [pp - aa for aa, pp in zip(a, p)]
    den = sum(c * c for c in ab)
    t = 0.0 if den == 0.0 else max(0.0, min(1.0, sum(x * y for x, y in zip(ab, ap)) / den))
    return math.sqrt(sum((pp - (aa + t * c)) ** 2 for pp, aa, c in zip(p, a, ab)))


def raster(inside, lo, hi):
    """The cells (i, j, k) of the integer box [lo, hi) whose centres are inside."""
    cells = set()
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                if inside((i + 0.5, j + 0.5, k + 0.5)):
                    cells.add((i, j, k))
    return cells


def keep_largest(cells):
    """The largest face-connected part of `cells` (a rasterised shape is one body)."""
    left, best = set(cells), set()
    while left:
        seed = left.pop()
        part, todo = {seed}, [seed]
        while todo:
            i, j, k = todo.pop()
            for n in ((i + 1, j, k), (i - 1, j, k), (i, j + 1, k), (i, j - 1, k), (i, j, k + 1), (i, j, k - 1)):
                if n in left:
                    left.remove(n)
                    part.add(n)
                    todo.append(n)
        if len(part) > len(best):
            best = part
    return best


# ---------------------------------------------------------------- letters
# Each letter as strokes in a unit box (x in [0, w], y in [0, 1]): segments
# ("s", x0, y0, x1, y1) and arcs ("a", cx, cy, rx, ry, deg0, deg1), drawn
# with a round pen of the stroke width.
LETTERS = {
    "A": (0.8, [("s", 0.0, 0.0, 0.4, 1.0), ("s", 0.4, 1.0, 0.8, 0.0), ("s", 0.16, 0.38, 0.64, 0.38)]),
    "H": (0.7, [("s", 0.0, 0.0, 0.0, 1.0), ("s", 0.7, 0.0, 0.7, 1.0), ("s", 0.0, 0.5, 0.7, 0.5)]),
    "K": (0.7, [("s", 0.0, 0.0, 0.0, 1.0), ("s", 0.0, 0.45, 0.7, 1.0), ("s", 0.2, 0.6, 0.7, 0.0)]),
    "L": (0.6, [("s", 0.0, 0.0, 0.0, 1.0), ("s", 0.0, 0.0, 0.6, 0.0)]),
    "X": (0.8, [("s", 0.0, 0.0, 0.8, 1.0), ("s", 0.0, 1.0, 0.8, 0.0)]),
    "Y": (0.8, [("s", 0.0, 1.0, 0.4, 0.5), ("s", 0.8, 1.0, 0.4, 0.5), ("s", 0.4, 0.5, 0.4, 0.0)]),
    "S": (0.7, [("a", 0.35, 0.75, 0.35, 0.25, 0, 270), ("a", 0.35, 0.25, 0.35, 0.25, 90, -180)]),
    "O": (0.8, [("a", 0.4, 0.5, 0.4, 0.5, 0, 360)]),
}


def letter(ch, stroke, depth, height=40):
    """The extruded letter `ch`, `height` cells tall, strokes `stroke` and depth
    `depth` as shares of the height."""
    w, strokes = LETTERS[ch]
    pen = 0.5 * stroke * height
    pts = []  # the strokes as short segments in cells
    for s in strokes:
        if s[0] == "s":
            pts.append(((s[1] * height, s[2] * height), (s[3] * height, s[4] * height)))
        else:
            _, cx, cy, rx, ry, a0, a1 = s
            n = 48
            prev = None
            for m in range(n + 1):
                a = math.radians(a0 + (a1 - a0) * m / n)
                q = ((cx + rx * math.cos(a)) * height, (cy + ry * math.sin(a)) * height)
                if prev is not None:
                    pts.append((prev, q))
                prev = q
    # The pen's centre stays within the unit box shrunk by the pen, so that
    # every letter is `height` tall.
    sx = (w * height - 2 * pen) / (w * height) if w > 0 else 1.0
    sy = (height - 2 * pen) / height
    segs = [((pen + a[0] * sx, pen + a[1] * sy), (pen + b[0] * sx, pen + b[1] * sy)) for a, b in pts]
    d = max(1, int(round(depth * height)))
    lo, hi = (-1, -1, 0), (int(w * height) + 2, height + 2, d)
    flat = raster(lambda p: min(seg_dist(p[:2], a, b) for a, b in segs) <= pen, (lo[0], lo[1], 0), (hi[0], hi[1], 1))
    return keep_largest({(i, j, k) for (i, j, _) in flat for k in range(d)})


# ---------------------------------------------------------------- discs, dumbbells
def disc(aspect):
    """A disc `aspect` times as wide as it is thick, about the x axis."""
    r, half = 1.0, 1.0 / aspect
    return revolve([(-half, 0.0), (-half, r), (half, r), (half, 0.0)], 96)


def dumbbell(r1, r2, bar, gap):
    """Balls of radii r1 (at -x) and r2 joined by a bar of radius `bar`, the
    balls' surfaces `gap` apart, about the x axis."""
    return dumbbell_profile(r1, r2, bar, gap, 32)


def box_dumbbell(a, b, bar, gap):
    """Two cubes of edge a and b cells joined by a square bar `bar` cells thick."""
    cells = set()
    h = max(a, b)
    for i in range(a):
        for j in range(a):
            for k in range(a):
                cells.add((i, j + (h - a) // 2, k + (h - a) // 2))
    for i in range(a, a + gap):
        for j in range(bar):
            for k in range(bar):
                cells.add((i, j + (h - bar) // 2, k + (h - bar) // 2))
    for i in range(b):
        for j in range(b):
            for k in range(b):
                cells.add((i + a + gap, j + (h - b) // 2, k + (h - b) // 2))
    return blocks(cells)


# ---------------------------------------------------------------- figures
def figure(bones, height=56):
    """A figure from capsules (x0, y0, z0, x1, y1, z1, radius) given in shares
    of the height (y up)."""
    caps = [((b[0] * height, b[1] * height, b[2] * height), (b[3] * height, b[4] * height, b[5] * height),
             b[6] * height) for b in bones]
    lo = [int(math.floor(min(min(a[c], b[c]) - r for a, b, r in caps))) - 1 for c in range(3)]
    hi = [int(math.ceil(max(max(a[c], b[c]) + r for a, b, r in caps))) + 1 for c in range(3)]
    cells = raster(lambda p: any(seg_dist(p, a, b) <= r for a, b, r in caps), lo, hi)
    return blocks(keep_largest(cells))


def humanoid(t, arms, legs_apart=0.0):
    """A figure 1 tall with limbs t thick: arms 'spread', 'raised' (a Y) or
    'one_up' (one raised, one spread down)."""
    r = t / 2.0
    hip, sh = 0.48, 0.80
    bones = [(-0.06 - legs_apart, r, 0, -0.05, hip, 0, r), (0.06 + legs_apart, r, 0, 0.05, hip, 0, r),
             (0, hip, 0, 0, sh, 0, 1.6 * r), (0, sh, 0, 0, 0.88, 0, r * 0.8), (0, 0.93, 0, 0, 0.93, 0, 0.07)]
    if arms == "spread":
        bones += [(0, sh - 0.02, 0, -0.36, sh - 0.02, 0, r), (0, sh - 0.02, 0, 0.36, sh - 0.02, 0, r)]
    elif arms == "raised":
        bones += [(0, sh - 0.02, 0, -0.22, sh + 0.2, 0, r), (0, sh - 0.02, 0, 0.22, sh + 0.2, 0, r)]
    else:
        bones += [(0, sh - 0.02, 0, -0.2, sh + 0.22, 0, r), (0, sh - 0.02, 0, 0.25, sh - 0.22, 0, r)]
    return figure(bones)


def tower(aspect):
    """A square column `aspect` times as tall as it is wide."""
    w = 6
    return blocks({(i, j, k) for i in range(w) for j in range(int(aspect * w)) for k in range(w)})


def tree(t):
    """A trunk with branches t thick and a ball crown at the top."""
    r = t / 2.0
    bones = [(0, r, 0, 0, 0.75, 0, r * 1.3), (0, 0.45, 0, -0.25, 0.7, 0, r), (0, 0.55, 0, 0.22, 0.8, 0.0, r),
             (0, 0.35, 0, 0.0, 0.55, 0.2, r), (0, 0.86, 0, 0, 0.86, 0, 0.14)]
    return figure(bones)


# ---------------------------------------------------------------- the set
def shapes():
    """(name, kind, mesh, rotation) for every shape of the set."""
    out = []
    for ch, stroke, depth, lying in (("A", 0.16, 0.2, False), ("H", 0.2, 0.25, False), ("K", 0.14, 0.15, False),
                                     ("L", 0.2, 0.3, False), ("X", 0.16, 0.2, False), ("Y", 0.18, 0.2, False),
                                     ("S", 0.16, 0.2, False), ("O", 0.16, 0.25, False), ("H", 0.16, 0.15, True),
                                     ("A", 0.2, 0.2, True), ("X", 0.14, 0.12, True), ("O", 0.2, 0.2, True)):
        name = "letter_%s_%s%d" % (ch.lower(), "lying" if lying else "up", int(round(100 * stroke)))
        out.append((name, "letter", blocks(letter(ch, stroke, depth)), [90, 0, 0] if lying else None))
    for aspect, rot, tag in ((10, None, "edge"), (16, None, "edge"), (22, None, "edge"), (10, [0, 0, 90], "flat"),
                             (22, [0, 0, 90], "flat"), (14, [0, 0, 45], "tilt"), (22, [0, 30, 60], "tilt")):
        out.append(("disc_%s%d" % (tag, aspect), "disc", disc(aspect), rot))
    for r2, bar, gap, rot, tag in ((1.0, 0.15, 4.0, None, "long"), (0.6, 0.2, 3.0, None, "unequal"),
                                   (0.5, 0.12, 3.5, None, "thin"), (0.7, 0.3, 1.5, None, "short"),
                                   (0.7, 0.2, 3.0, [0, 0, 90], "upright"), (0.8, 0.2, 3.0, [0, 0, 30], "tilt")):
        out.append(("dumbbell_%s" % tag, "dumbbell", dumbbell(1.0, r2, bar, gap), rot))
    out.append(("dumbbell_boxes", "dumbbell", box_dumbbell(10, 7, 2, 14), None))
    for t, arms, apart, tag in ((1 / 14.0, "spread", 0.0, "spread14"), (1 / 18.0, "spread", 0.0, "spread18"),
                                (1 / 10.0, "raised", 0.0, "raised10"), (1 / 14.0, "raised", 0.06, "raised14"),
                                (1 / 16.0, "one_up", 0.1, "oneup16")):
        out.append(("figure_%s" % tag, "figure", humanoid(t, arms, apart), None))
    out.append(("figure_tower6", "figure", tower(6), None))
    out.append(("figure_tower10", "figure", tower(10), None))
    out.append(("figure_tree", "figure", tree(1 / 12.0), None))
    return out


def volume(mesh):
    verts, faces = mesh
    v = 0.0
    for a, b, c in faces:
        p, q, r = verts[a], verts[b], verts[c]
        v += (p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) +
              p[2] * (q[0] * r[1] - q[1] * r[0])) / 6.0
    return v


def rotate(v, deg):
    """Rotation about x, then y, then z (scenes/README.md, `rotation`)."""
    x, y, z = v
    ax, ay, az = (math.radians(d) for d in deg)
    y, z = y * math.cos(ax) - z * math.sin(ax), y * math.sin(ax) + z * math.cos(ax)
    x, z = x * math.cos(ay) + z * math.sin(ay), -x * math.sin(ay) + z * math.cos(ay)
    x, y = x * math.cos(az) - y * math.sin(az), x * math.sin(az) + y * math.cos(az)
    return (x, y, z)


def write_mesh(path, mesh):
    write(path, mesh, "bench/unseen_shapes.py")


def write_scene(path, name, mesh, rot):
    vol = volume(mesh)
    if vol <= 0.0:
        sys.exit("%s: mesh volume %g is not positive (faces wound inwards)" % (name, vol))
    fluid_volume = FLUID[0] * FLUID[1] * FLUID[2] * SPACING ** 3
    s = (fluid_volume / vol) ** (1.0 / 3.0)
    pts = [rotate(v, rot) if rot else v for v in mesh[0]]
    ext = [s * (max(p[c] for p in pts) - min(p[c] for p in pts)) for c in range(3)]
    block = [n * SPACING for n in FLUID]
    # Room for the shape and the fluid block, with a margin, in whole cm.
    top = [math.ceil(100.0 * max(ext[c] * 1.15 + 0.06, block[c] + 0.12, 0.3)) / 100.0 for c in range(3)]
    top[1] = math.ceil(100.0 * max(ext[1] * 1.1 + 0.05, 0.3)) / 100.0
    origin = [round((top[0] - block[0]) / 2.0, 4), 0.0, round((top[2] - block[2]) / 2.0, 4)]
    target = '{"shape": "mesh", "mesh": "%s.obj"' % name
    if rot:
        target += ', "rotation": [%g, %g, %g]' % tuple(rot)
    target += "}"
    with open(path, "w") as f:
        f.write('{\n  "name": "%s",\n  "preset": "water",\n  "duration": 3.0,\n' % name)
        f.write('  "container": {"min": [0.0, 0.0, 0.0], "max": [%g, %g, %g]},\n' % tuple(top))
        f.write('  "fluid": [{"origin": [%g, %g, %g], "dims": [%d, %d, %d]}],\n' % (tuple(origin) + FLUID))
        f.write('  "region": "all",\n  "target": %s\n}\n' % target)
    return ext


def generate(out):
    os.makedirs(out, exist_ok=True)
    names = []
    for name, kind, mesh, rot in shapes():
        write_mesh(os.path.join(out, name + ".obj"), mesh)
        ext = write_scene(os.path.join(out, name + ".json"), name, mesh, rot)
        names.append(name)
        print("%-22s %-8s %6d triangles, %.2f x %.2f x %.2f m" % ((name, kind, len(mesh[1])) + tuple(ext)))
    return names


def row_at(csv_path, t):
    with open(csv_path) as f:
        head = f.readline().strip().split(",")
        rows = [dict(zip(head, line.strip().split(","))) for line in f if line.strip()]
    best = min(rows, key=lambda r: abs(float(r["time"]) - t))
    clamps = max(int(float(r["velocity_clamps"])) for r in rows)
    return best, clamps, rows


def table(out, names=None):
    if names is None:
        names = sorted(n[:-4] for n in os.listdir(out) if n.endswith(".csv"))
    print("| shape | control particles | iou 1 s | iou 2 s | iou / filled / stray / filled_thin at 3 s | "
          "most clamps in a step | base_height / tilt at 3 s |")
    print("|---|---:|---|---|---|---:|---|")
    for n in names:
        path = os.path.join(out, n + ".csv")
        if not os.path.exists(path):
            continue
        r3, clamps, rows = row_at(path, 3.0)
        r1, r2 = row_at(path, 1.0)[0], row_at(path, 2.0)[0]
        print("| %s | %s | %.3f | %.3f | %.3f / %.3f / %.3f / %.3f | %d | %.1f cm / %.1f deg |" %
              (n, r3["control_count"], float(r1["iou"]), float(r2["iou"]), float(r3["iou"]), float(r3["filled"]),
               float(r3["stray"]), float(r3["filled_thin"]), clamps, 100.0 * float(r3["base_height"]) + 0.0 if abs(float(r3["base_height"])) >= 5e-4 else 0.0,
               float(r3["tilt"])))


def main():
    args = sys.argv[1:]
    if len(args) >= 2 and args[0] == "--run":
        out, only = args[1], args[2:]
        names = generate(out)
        if only:
            names = [n for n in names if n in only]
        root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
        exe = os.path.join(root, "build", "flowform")
        env = dict(os.environ, OMP_NUM_THREADS="2", POCL_MAX_PTHREAD_COUNT="2")
        for n in names:
            rc = subprocess.run([exe, "run", os.path.join(out, n + ".json"),
                                 "--backend", "cpu", "--threads", "2", "--seconds", "3", "--metrics",
                                 os.path.join(out, n + ".csv")], env=env, stdout=subprocess.DEVNULL).returncode
            print(n, "done" if rc == 0 else "FAILED (exit %d)" % rc, file=sys.stderr)
        table(out, names)
    elif len(args) == 2 and args[0] == "--table":
        table(args[1])
    elif len(args) == 1 and not args[0].startswith("--"):
        generate(args[0])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
