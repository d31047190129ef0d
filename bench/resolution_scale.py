#!/usr/bin/env python3
"""resolution_scale.py - the same scene at another particle count or another
size, as a user would make it (issue 10: "the same scene at 2x and 4x the
particle count, and scaled 0.5x and 2x, gives iou curves within 0.05 of each
other"; docs/RESULTS.md, "Resolution and scale").

  write BASE FOLDER [--set GROUP.KEY=VALUE ...] [--scale-radius]
      writes FOLDER/res1.json (BASE as it is), res2.json and res4.json (2x
      and 4x the fluid particles in the same volume: the spacing divided by
      the cube root of 2 or 4, the particle mass, smoothing radius and
      particle radius with it, each block's dims rounded to fill its
      extent), scale0.5.json and scale2.json (the container, every block's
      origin and spacing, the mass, smoothing radius and particle radius
      scaled by 0.5 or 2, the same particle count; a mesh target is sized to
      the fluid's volume, so it scales with it). Gravity, time steps and the
      control's constants are left alone: they are what is being tested.
      --set adds a parameter override to every variant (e.g.
      --set control.normalise=1); --scale-radius also scales control.radius
      with the scene. The mesh path of a mesh target is resolved by
      FLOWFORM_MESH_PATH as for BASE.

  compare REF.csv OTHER.csv[@C] ... [--until T] [--every DT] [--from T0]
      prints each metrics CSV's iou at every DT seconds up to T, and the
      largest |iou - iou_ref| over those times from T0 on; then the largest
      difference over every row of REF from T0 to T (the whole curve, each
      step). OTHER.csv@C reads a scene scaled by C on the clock of its fall
      under gravity: its time t is compared at t / sqrt(C) (sqrt(L / g),
      the Froude-scaled clock).

Usage (the commands of docs/RESULTS.md):
  python3 bench/resolution_scale.py write scenes/water/bunny.json build/res
  FLOWFORM_MESH_PATH=../shared/meshes ./build/flowform run build/res/res2.json \
      --backend cpu --threads 2 --seconds 3 --metrics build/res/res2.csv
  python3 bench/resolution_scale.py compare build/res/res1.csv build/res/res2.csv
"""
import csv
import json
import math
import os
import sys

# The paper preset's fluid (params.h); the water preset keeps its particle
# spacing at rho0 = 1000 (src/core/params.cpp, waterParams).
PRESET_FLUID = {
    "paper": {"particle_mass": 0.0002, "particle_radius": 0.0059, "smoothing_radius": 0.012, "rest_density": 800.0},
}
_spacing = (0.0002 / 800.0) ** (1.0 / 3.0)
PRESET_FLUID["water"] = {"particle_mass": 1000.0 * _spacing ** 3, "particle_radius": 0.0059,
                         "smoothing_radius": 2.0 * _spacing, "rest_density": 1000.0}
PRESET_FLUID["default"] = PRESET_FLUID["water"]


def fluid_of(scene):
    base = dict(PRESET_FLUID[scene.get("preset", "default")])
    base.update(scene.get("params", {}).get("fluid", {}))
    return base


def set_fluid(scene, fluid, factor):
    """Scales the fluid's lengths by `factor` (mass by factor^3)."""
    params = scene.setdefault("params", {})
    f = params.setdefault("fluid", {})
    f["particle_mass"] = fluid["particle_mass"] * factor ** 3
    f["smoothing_radius"] = fluid["smoothing_radius"] * factor
    f["particle_radius"] = fluid["particle_radius"] * factor


def spacing_of(block, fluid):
    return block.get("spacing", (fluid["particle_mass"] / fluid["rest_density"]) ** (1.0 / 3.0))


def resolution(scene, count_factor):
    s = json.loads(json.dumps(scene))
    fluid = fluid_of(scene)
    factor = count_factor ** (-1.0 / 3.0)
    set_fluid(s, fluid, factor)
    for block, old in zip(s["fluid"], scene["fluid"]):
        sp = spacing_of(old, fluid)
        new_sp = sp * factor
        block["dims"] = [max(1, int(round(d * sp / new_sp))) for d in old["dims"]]
        if "spacing" in old:
            block["spacing"] = new_sp
    s["name"] = "%s_res%g" % (scene.get("name", "scene"), count_factor)
    return s


def scaled(scene, c, scale_radius):
    s = json.loads(json.dumps(scene))
    fluid = fluid_of(scene)
    set_fluid(s, fluid, c)
    if "container" in s:
        for k in ("min", "max"):
            s["container"][k] = [v * c for v in s["container"][k]]
    else:
        s["container"] = {"min": [0.0, 0.0, 0.0], "max": [0.3 * c] * 3}
    for block in s["fluid"]:
        block["origin"] = [v * c for v in block["origin"]]
        if "spacing" in block:
            block["spacing"] *= c
    region = s.get("region", "all")
    if isinstance(region, dict):
        if "box" in region:
            for k in ("min", "max"):
                region["box"][k] = [v * c for v in region["box"][k]]
        if "sphere" in region:
            region["sphere"]["center"] = [v * c for v in region["sphere"]["center"]]
            region["sphere"]["radius"] *= c
    if scale_radius:
        control = s["params"].setdefault("control", {})
        control["radius"] = control.get("radius", 0.03) * c
    s["name"] = "%s_scale%g" % (scene.get("name", "scene"), c)
    return s


def parse_value(text):
    try:
        return json.loads(text)
    except ValueError:
        return text


def write(argv):
    base_path, folder = argv[0], argv[1]
    sets, scale_radius = [], False
    rest = argv[2:]
    while rest:
        if rest[0] == "--set" and len(rest) > 1:
            sets.append(rest[1])
            rest = rest[2:]
        elif rest[0] == "--scale-radius":
            scale_radius = True
            rest = rest[1:]
        else:
            sys.exit("resolution_scale.py: unknown option %s" % rest[0])
    with open(base_path) as f:
        base = json.load(f)
    for item in sets:
        key, _, value = item.partition("=")
        group, _, name = key.partition(".")
        if not group or not name or not value:
            sys.exit("resolution_scale.py: --set wants GROUP.KEY=VALUE (got %s)" % item)
        base.setdefault("params", {}).setdefault(group, {})[name] = parse_value(value)
    os.makedirs(folder, exist_ok=True)
    variants = {"res1": json.loads(json.dumps(base)), "res2": resolution(base, 2.0),
                "res4": resolution(base, 4.0), "scale0.5": scaled(base, 0.5, scale_radius),
                "scale2": scaled(base, 2.0, scale_radius)}
    for name, scene in variants.items():
        path = os.path.join(folder, name + ".json")
        with open(path, "w") as f:
            json.dump(scene, f, indent=1)
        count = sum(math.prod(b["dims"]) for b in scene["fluid"])
        print("%s: %d fluid particles" % (path, count))


def iou_curve(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [(float(r["time"]), float(r["iou"])) for r in rows]


def interp(curve, t):
    """iou at time t, linear between rows; None outside the curve."""
    for (t0, v0), (t1, v1) in zip(curve, curve[1:]):
        if t0 <= t <= t1:
            return v0 if t1 == t0 else v0 + (v1 - v0) * (t - t0) / (t1 - t0)
    return None


def compare(argv):
    until, every, start, paths, clocks = 3.0, 0.25, 0.0, [], []
    while argv:
        if argv[0] == "--until":
            until, argv = float(argv[1]), argv[2:]
        elif argv[0] == "--every":
            every, argv = float(argv[1]), argv[2:]
        elif argv[0] == "--from":
            start, argv = float(argv[1]), argv[2:]
        else:
            path, _, c = argv[0].partition("@")
            paths, clocks, argv = paths + [path], clocks + [math.sqrt(float(c)) if c else 1.0], argv[1:]
    # Each curve on the reference's clock: t_ref = t / sqrt(C).
    curves = [[(t / k, v) for t, v in iou_curve(p)] for p, k in zip(paths, clocks)]
    names = [os.path.basename(p) + ("@%g" % (k * k) if k != 1.0 else "") for p, k in zip(paths, clocks)]
    times = [every * (k + 1) for k in range(int(round(until / every)))]
    print("time " + " ".join(names))
    worst = [0.0] * len(paths)
    for t in times:
        vals = [interp(c, t) for c in curves]
        ref = vals[0]
        print("%.2f " % t + " ".join("-" if v is None else "%.3f" % v for v in vals))
        for k, v in enumerate(vals):
            if v is not None and ref is not None and t >= start - 1e-9:
                worst[k] = max(worst[k], abs(v - ref))
    print("max |iou - %s| at those times from %g s: " % (names[0], start) +
          " ".join("%s %.3f" % (n, w) for n, w in zip(names[1:], worst[1:])))
    # Every row of the reference from `start` to `until`.
    line = []
    for name, c in zip(names[1:], curves[1:]):
        w, wt = 0.0, None
        for t, ref in curves[0]:
            if t < start - 1e-9 or t > until + 1e-9:
                continue
            v = interp(c, t)
            if v is not None and abs(v - ref) >= w:
                w, wt = abs(v - ref), t
        line.append("%s %.3f (at %.3f s)" % (name, w, wt) if wt is not None else "%s -" % name)
    print("max |iou - %s| over every step from %g s: " % (names[0], start) + " ".join(line))


def main():
    if len(sys.argv) < 2 or sys.argv[1] not in ("write", "compare"):
        sys.exit(__doc__)
    if sys.argv[1] == "write":
        if len(sys.argv) < 4:
            sys.exit(__doc__)
        write(sys.argv[2:])
    else:
        compare(sys.argv[2:])


if __name__ == "__main__":
    main()
