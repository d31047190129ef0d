#!/usr/bin/env python3
"""thin_shapes.py - writes thin target meshes of the kinds issue 10 names, that
the project was not tuned on (docs/RESULTS.md, "Thin features"):

  thin_disc.obj      a disc 10 times as wide as it is thick (a surface of revolution)
  dumbbell.obj       two balls joined by a bar a quarter of their radius thick
  letter_t.obj       an extruded letter T, strokes a fifth of its height wide
  stick_figure.obj   a tall figure with thin limbs: legs, arms spread sideways
                     and a head, limbs a fourteenth of its height thick

Each is one closed, consistently oriented triangle mesh (the voxeliser counts
ray crossings). With each mesh it writes a water-preset scene,
FOLDER/NAME.json (12,000 fluid particles, the target and no control_count:
the count follows from the default voxel size), whose mesh resolves relative
to the scene's folder. Usage: python3 bench/thin_shapes.py FOLDER
"""
import math
import os
import sys


def revolve(profile, segments=48):
    """A closed surface of revolution about the x axis: profile is a list of
    (x, r) from one pole (r = 0) to the other (r = 0)."""
    verts, faces = [], []
    rings = []
    for x, r in profile:
        if r == 0.0:
            verts.append((x, 0.0, 0.0))
            rings.append([len(verts) - 1])
            continue
        ring = []
        for s in range(segments):
            a = 2.0 * math.pi * s / segments
            verts.append((x, r * math.cos(a), r * math.sin(a)))
            ring.append(len(verts) - 1)
        rings.append(ring)
    for a, b in zip(rings, rings[1:]):
        if len(a) == 1:
            for s in range(segments):
                faces.append((a[0], b[(s + 1) % segments], b[s]))
        elif len(b) == 1:
            for s in range(segments):
                faces.append((a[s], a[(s + 1) % segments], b[0]))
        else:
            for s in range(segments):
                t = (s + 1) % segments
                faces.append((a[s], a[t], b[t]))
                faces.append((a[s], b[t], b[s]))
    return verts, faces


def disc():
    r, half = 1.0, 0.05  # 2.0 wide, 0.1 thick
    return revolve([(-half, 0.0), (-half, r), (half, r), (half, 0.0)], 96)


def dumbbell_profile(r1, r2, bar, gap, n=24):
    """Balls of radii r1 (at -x) and r2 joined by a bar of radius `bar`, the
    balls' surfaces `gap` apart, about the x axis (n segments per half circle)."""
    c1, c2 = -(r1 + gap / 2.0), r2 + gap / 2.0
    prof = []
    # the left ball from its far pole to where it meets the bar, then the right
    m1 = math.sqrt(r1 * r1 - bar * bar)
    for i in range(n + 1):
        a = math.pi * i / n
        x, r = c1 - r1 * math.cos(a), r1 * math.sin(a)
        if x > c1 + m1:
            break
        prof.append((x, r))
    prof.append((c1 + m1, bar))
    m2 = math.sqrt(r2 * r2 - bar * bar)
    prof.append((c2 - m2, bar))
    for i in range(n + 1):
        a = math.pi * i / n
        x, r = c2 - r2 * math.cos(a), r2 * math.sin(a)
        if x < c2 - m2:
            continue
        prof.append((x, r))
    prof[0] = (prof[0][0], 0.0)
    prof[-1] = (prof[-1][0], 0.0)
    return revolve(prof)


def dumbbell():
    # balls of radius 1, centres 2 + 2 apart, bar radius 0.25
    return dumbbell_profile(1.0, 1.0, 0.25, 2.0)


def letter_t():
    # The T's outline (counter-clockwise seen from +z), extruded along z.
    w, h, s, d = 1.0, 1.0, 0.2, 0.2  # width, height, stroke, depth
    poly = [(-w / 2, h), (-w / 2, h - s), (-s / 2, h - s), (-s / 2, 0.0), (s / 2, 0.0), (s / 2, h - s),
            (w / 2, h - s), (w / 2, h)]
    n = len(poly)
    verts = [(x, y, -d / 2) for x, y in poly] + [(x, y, d / 2) for x, y in poly]
    # The caps as two convex pieces of the outline: the bar and the stem.
    pieces = [(0, 1, 2, 5, 6, 7), (2, 3, 4, 5)]
    faces = []
    for p in pieces:
        for i in range(1, len(p) - 1):
            faces.append((p[0] + n, p[i] + n, p[i + 1] + n))  # front (+z), counter-clockwise
            faces.append((p[0], p[i + 1], p[i]))  # back (-z)
    for i in range(n):
        j = (i + 1) % n
        faces.append((i, j, j + n))
        faces.append((i, j + n, i + n))
    return verts, faces


def blocks(cells):
    """The closed surface of a union of unit cubes (a set of (i, j, k)): every
    face between a cube of the set and one outside it, wound outwards."""
    verts, faces, index = [], [], {}

    def vert(v):
        if v not in index:
            index[v] = len(verts)
            verts.append(tuple(float(c) for c in v))
        return index[v]

    for (i, j, k) in cells:
        for axis in range(3):
            for side in (0, 1):
                n = [i, j, k]
                n[axis] += 1 if side else -1
                if tuple(n) in cells:
                    continue
                # The face's corners, counter-clockwise seen from outside.
                u, w = (axis + 1) % 3, (axis + 2) % 3
                corner = []
                for du, dw in ((0, 0), (1, 0), (1, 1), (0, 1)):
                    c = [i, j, k]
                    c[axis] += side
                    c[u] += du
                    c[w] += dw
                    corner.append(vert(tuple(c)))
                if not side:
                    corner.reverse()
                faces.append((corner[0], corner[1], corner[2]))
                faces.append((corner[0], corner[2], corner[3]))
    return verts, faces


def stick_figure():
    # In cells of a quarter of a limb: y up, 28 cells tall, limbs 2 x 2 cells.
    cells = set()

    def box(x0, x1, y0, y1, z0, z1):
        for i in range(x0, x1):
            for j in range(y0, y1):
                for k in range(z0, z1):
                    cells.add((i, j, k))

    box(-3, -1, 0, 14, -1, 1)  # legs
    box(1, 3, 0, 14, -1, 1)
    box(-3, 3, 14, 23, -1, 1)  # torso
    box(-10, -3, 20, 22, -1, 1)  # arms, straight out
    box(3, 10, 20, 22, -1, 1)
    box(-1, 1, 23, 24, -1, 1)  # neck
    box(-2, 2, 24, 28, -2, 2)  # head
    return blocks(cells)


SCENES = {
    # name: (container max, fluid block origin)
    "thin_disc": ([0.5, 0.5, 0.5], [0.187, 0.0, 0.187]),
    "dumbbell": ([0.6, 0.4, 0.4], [0.237, 0.0, 0.137]),
    "letter_t": ([0.5, 0.5, 0.4], [0.187, 0.0, 0.137]),
    "stick_figure": ([0.6, 0.8, 0.4], [0.237, 0.0, 0.137]),
}


def write_scene(path, name):
    top, origin = SCENES[name]
    with open(path, "w") as f:
        f.write('{\n  "name": "%s_water",\n  "preset": "water",\n  "duration": 4.0,\n' % name)
        f.write('  "container": {"min": [0.0, 0.0, 0.0], "max": [%g, %g, %g]},\n' % tuple(top))
        f.write('  "fluid": [{"origin": [%g, %g, %g], "dims": [20, 30, 20]}],\n' % tuple(origin))
        f.write('  "region": "all",\n')
        f.write('  "target": {"shape": "mesh", "mesh": "%s.obj"}\n}\n' % name)


def write(path, mesh, script="bench/thin_shapes.py"):
    verts, faces = mesh
    with open(path, "w") as f:
        f.write("# " + os.path.basename(path) + " (" + script + ")\n")
        for v in verts:
            f.write("v %.6f %.6f %.6f\n" % v)
        for a, b, c in faces:
            f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: python3 bench/thin_shapes.py FOLDER")
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for name, mesh in (("thin_disc", disc()), ("dumbbell", dumbbell()), ("letter_t", letter_t()),
                       ("stick_figure", stick_figure())):
        write(os.path.join(out, name + ".obj"), mesh)
        write_scene(os.path.join(out, name + ".json"), name)
        print(os.path.join(out, name + ".obj"), len(mesh[0]), "vertices", len(mesh[1]), "triangles")


if __name__ == "__main__":
    main()
