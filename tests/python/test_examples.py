#!/usr/bin/python3
"""Runs examples/wedge.py or examples/keyframes.py small and cheap (the
default scene, a few steps) in a temporary folder and checks their output.

Usage: test_examples.py wedge|keyframes SOURCE_DIR MODULE_DIR
"""
import csv
import os
import shutil
import subprocess
import sys
import tempfile


def run(script, args, tmp, module_dir):
    env = dict(os.environ, PYTHONPATH=module_dir)
    r = subprocess.run([sys.executable, script] + args, cwd=tmp, env=env, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("%s failed (%d):\n%s%s" % (script, r.returncode, r.stdout, r.stderr))
    return r.stdout


def refused(script, args, tmp, module_dir, needle):
    """A bad argument: exit status 1 and one line naming it, no traceback."""
    env = dict(os.environ, PYTHONPATH=module_dir)
    r = subprocess.run([sys.executable, script] + args, cwd=tmp, env=env, capture_output=True, text=True)
    check(r.returncode == 1 and needle in r.stderr and "Traceback" not in r.stderr,
          "%s %s: expected exit 1 naming '%s', got %d:\n%s%s" % (script, args, needle, r.returncode, r.stdout,
                                                                   r.stderr))


def check(cond, what):
    if not cond:
        sys.exit("FAILED: " + what)


def wedge(src, module_dir, tmp):
    run(os.path.join(src, "examples", "wedge.py"),
        ["--param", "control.attraction_g", "--values", "4.35,17.4", "--steps", "4", "--threads", "2",
         "--out", "w.csv"], tmp, module_dir)
    rows = list(csv.reader(open(os.path.join(tmp, "w.csv"))))
    check(rows[0][:3] == ["control.attraction_g", "final_iou", "final_coverage"], "header %s" % rows[0])
    check(len(rows) == 3, "one row per value, got %d" % (len(rows) - 1))
    check([float(r[0]) for r in rows[1:]] == [4.35, 17.4], "values column %s" % rows[1:])
    for r in rows[1:]:
        check(0.0 <= float(r[1]) <= 1.0, "iou in [0, 1]: %s" % r)
        check(abs(float(r[-1]) - 4 * 0.004) < 1e-6, "4 steps of 0.004 s: %s" % r)
    # Different attraction (the default preset pulls normalised: attraction_g), different run: the wedge really changed the parameter.
    check(rows[1][1:-1] != rows[2][1:-1], "both runs gave the same metrics")
    # A parameter read only where the first target is placed (control.adaptive:
    # each control particle's radius from the target's thickness) acts too:
    # the wedge gives it from the start (before, set_params after the
    # placement left both runs the same).
    run(os.path.join(src, "examples", "wedge.py"),
        ["--param", "control.adaptive", "--values", "0,1", "--steps", "3", "--threads", "2", "--out", "a.csv"],
        tmp, module_dir)
    rows = list(csv.reader(open(os.path.join(tmp, "a.csv"))))
    check(len(rows) == 3 and rows[1][1:-1] != rows[2][1:-1], "adaptive 0 and 1 gave the same metrics: %s" % rows)
    # Bad arguments (a traceback, or a silent run of the default length, before).
    script = os.path.join(src, "examples", "wedge.py")
    refused(script, ["--values", "abc", "--steps", "1"], tmp, module_dir, "--values: 'abc' is not a number")
    refused(script, ["--steps", "-2"], tmp, module_dir, "--steps: must be > 0")
    refused(script, ["--seconds", "-1"], tmp, module_dir, "--seconds: must be > 0")
    refused(script, ["--steps", "1", "--out", os.path.join(tmp, "no", "w.csv")], tmp, module_dir,
            os.path.join(tmp, "no", "w.csv") + ": No such file or directory")


def keyframes(src, module_dir, tmp):
    out = run(os.path.join(src, "examples", "keyframes.py"),
              ["--keys", "0:sphere,0.02:box", "--seconds", "0.04", "--threads", "2", "--metrics", "k.csv",
               "--export", "frames"], tmp, module_dir)
    check("target box" in out, "the box keyframe was applied:\n" + out)
    rows = list(csv.DictReader(open(os.path.join(tmp, "k.csv"))))
    check(len(rows) == 10, "10 steps of 0.004 s, got %d" % len(rows))
    check([int(float(r["step"])) for r in rows] == list(range(1, 11)), "steps 1..10")
    # The control set changed with the target at 0.02 s (step 5 -> 6).
    before, after = float(rows[4]["control_count"]), float(rows[5]["control_count"])
    check(before > 0 and after > 0 and before != after, "control count %g -> %g" % (before, after))
    check(os.path.exists(os.path.join(tmp, "frames", "fluid_00000.ply")), "exported frames")
    # Bad arguments (a traceback, or a silent run of no steps, before).
    script = os.path.join(src, "examples", "keyframes.py")
    refused(script, ["--seconds", "-1"], tmp, module_dir, "--seconds: must be > 0")
    refused(script, ["--keys", "soon:box"], tmp, module_dir, "--keys: 'soon:box': the time must be")
    refused(script, ["--seconds", "0.004", "--metrics", os.path.join(tmp, "no", "k.csv")], tmp, module_dir,
            os.path.join(tmp, "no", "k.csv") + ": No such file or directory")


if __name__ == "__main__":
    which, src, module_dir = sys.argv[1], os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3])
    tmp = tempfile.mkdtemp(prefix="flowform_example_")
    try:
        {"wedge": wedge, "keyframes": keyframes}[which](src, module_dir, tmp)
    finally:
        shutil.rmtree(tmp)
    print("OK")
