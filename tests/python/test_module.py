#!/usr/bin/python3
"""The Python module `flowform` against the flowform program.

- A scene run from Python gives the CLI's metrics (every CSV cell, printed the
  same way) and the CLI's exported particle positions bit for bit, on the CPU
  backend with the same thread count.
- The arrays have the right shapes, types and ids (a permutation of 0..n-1).
- A bad scene raises flowform.Error naming the file and the key; target,
  region and parameter changes work at any time and bad ones raise.

Usage: test_module.py FLOWFORM_EXE MODULE_DIR
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import meshio
import numpy as np

EXE = None
SCENE = {
    "name": "py",
    "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]},
    "fluid": [{"origin": [0.06, 0.0, 0.06], "dims": [10, 10, 10]}],
    "schedule": [{"time": 0.0, "target": "sphere"}],
}
STEPS = 60


class ModuleTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="flowform_py_")
        self.scene = os.path.join(self.dir, "scene.json")
        with open(self.scene, "w") as f:
            json.dump(SCENE, f)

    def tearDown(self):
        shutil.rmtree(self.dir)

    def test_metrics_and_particles_match_the_cli_bit_for_bit(self):
        csv = os.path.join(self.dir, "m.csv")
        out = os.path.join(self.dir, "frames")
        subprocess.run([EXE, "run", self.scene, "--backend", "cpu", "--threads", "2", "--steps", str(STEPS),
                        "--metrics", csv, "--format", "ply", "--export", out, "--export-every", str(STEPS)],
                       check=True, stdout=subprocess.DEVNULL)
        sim = flowform.Simulation(self.scene, backend="cpu", threads=2)
        hist = sim.run(steps=STEPS)
        with open(csv) as f:
            rows = f.read().splitlines()
        header = rows[0].split(",")
        self.assertEqual(len(rows), STEPS + 1)
        for name in header:
            self.assertEqual(hist[name].shape, (STEPS,), name)
        for i, row in enumerate(rows[1:]):
            mine = ",".join("%.9g" % hist[name][i] for name in header)
            self.assertEqual(mine, row, "step %d" % (i + 1))
        # The CLI's last frame (step STEPS) against the module's fluid, by id.
        mesh = meshio.read(os.path.join(out, "fluid_00001.ply"))
        cli_id = np.asarray(mesh.point_data["id"]).astype(np.int64)
        cli_pos = np.asarray(mesh.points)[np.argsort(cli_id)]
        fluid = sim.fluid()
        py_pos = fluid["position"][np.argsort(fluid["id"])]
        self.assertTrue(np.array_equal(cli_pos.astype(np.float32), py_pos))
        self.assertEqual(sim.step_count, STEPS)

    def test_arrays_have_the_right_shapes_and_ids(self):
        sim = flowform.Simulation(SCENE, backend="cpu", threads=2)
        sim.run(steps=3)
        fluid = sim.fluid()
        self.assertEqual(fluid["position"].shape, (1000, 3))
        self.assertEqual(fluid["velocity"].shape, (1000, 3))
        self.assertEqual(fluid["position"].dtype, np.float32)
        self.assertEqual(fluid["id"].dtype, np.uint32)
        self.assertTrue(np.array_equal(np.sort(fluid["id"]), np.arange(1000)))
        # Every particle is inside the container.
        self.assertTrue((fluid["position"] >= 0).all() and (fluid["position"] <= 0.2).all())
        control = sim.control()
        m = int(sim.metrics["control_count"])
        self.assertGreater(m, 0)
        for key in ("position", "velocity", "rest_position"):
            self.assertEqual(control[key].shape, (m, 3), key)
        self.assertEqual(control["s"].shape, (m,))
        self.assertEqual(sim.target, "sphere")
        self.assertEqual(sim.metrics["step"], 3)

    def test_counts_are_integers(self):
        # The metrics that count (docs/METRICS.md) are Python ints and int64
        # arrays, the others floats and float64 arrays.
        counts = {"step", "control_count", "substeps", "solver_iterations", "solver_capped", "velocity_clamps"}
        sim = flowform.Simulation(SCENE, backend="cpu", threads=2)
        hist = sim.run(steps=2)
        m = sim.metrics
        self.assertTrue(counts <= set(m), sorted(m))
        for name, value in m.items():
            if name in counts:
                self.assertIs(type(value), int, name)
                self.assertEqual(hist[name].dtype, np.int64, name)
            else:
                self.assertIs(type(value), float, name)
                self.assertEqual(hist[name].dtype, np.float64, name)
        self.assertEqual(m["step"], 2)
        self.assertEqual(hist["step"].tolist(), [1, 2])
        self.assertGreater(m["control_count"], 0)

    def test_a_bad_scene_names_the_file_and_the_key(self):
        bad = os.path.join(self.dir, "bad.json")
        with open(bad, "w") as f:
            json.dump({"fluid": [{"origin": [0, 0, 0], "dims": [4, 4, 4]}],
                       "params": {"fluid": {"viscosity": -1}}}, f)
        with self.assertRaises(flowform.Error) as ctx:
            flowform.Simulation(bad)
        self.assertIn("bad.json", str(ctx.exception))
        self.assertIn("params.fluid.viscosity", str(ctx.exception))
        self.assertIsInstance(ctx.exception, RuntimeError)
        # The CLI says the same.
        cli = subprocess.run([EXE, "run", bad, "--steps", "1"], capture_output=True, text=True)
        self.assertEqual(cli.returncode, 1, cli.stderr)  # an error, not a crash
        self.assertIn(str(ctx.exception), cli.stderr)
        with self.assertRaises(flowform.Error) as ctx:
            flowform.Simulation(dict(SCENE, colour="blue"))
        self.assertIn("<dict>", str(ctx.exception))
        self.assertIn("colour", str(ctx.exception))

    def test_target_region_and_parameters_change_at_any_time(self):
        sim = flowform.Simulation(SCENE, backend="cpu", threads=2)
        sim.run(steps=2)
        sim.set_region({"box": {"min": [0, 0, 0], "max": [0.2, 0.05, 0.2]}})
        sim.set_target({"shape": "box", "size": [1, 1, 1]})
        self.assertEqual(sim.target, "box")
        sim.step()
        sim.set_params({"fluid": {"viscosity": 0.03}})
        with self.assertRaises(flowform.Error) as ctx:
            sim.set_params({"fluid": {"viscosity": -2}})
        self.assertIn("viscosity", str(ctx.exception))
        with self.assertRaises(flowform.Error):
            sim.set_target("no_such_mesh.obj")
        sim.set_target(None)
        self.assertIsNone(sim.target)
        sim.run(seconds=0.008)
        self.assertEqual(sim.step_count, 5)
        with self.assertRaises(flowform.Error):
            sim.run(steps=1, seconds=1.0)

    def test_nan_is_refused_naming_its_key_and_numpy_values_are_read(self):
        # NaN and infinity (json.dumps wrote NaN, which the reader called
        # invalid JSON): refused naming the key path; NumPy arrays and
        # scalars are read as their numbers (a TypeError before).
        sim = flowform.Simulation(SCENE, backend="cpu", threads=2)
        cases = [
            (lambda: sim.set_params({"fluid": {"viscosity": float("nan")}}),
             "<params>: params.fluid.viscosity: must be a finite number"),
            (lambda: sim.set_params({"fluid": {"gravity": np.array([0.0, -np.inf, 0.0])}}),
             "<params>: params.fluid.gravity[1]: must be a finite number"),
            (lambda: sim.set_target({"shape": "box", "size": (float("inf"), 1, 1)}),
             "<target>: target.size[0]: must be a finite number"),
            (lambda: flowform.Simulation(dict(SCENE, fluid=[{"origin": [float("nan"), 0, 0], "dims": [2, 2, 2]}])),
             "<dict>: fluid[0].origin[0]: must be a finite number"),
        ]
        for call, want in cases:
            with self.assertRaises(flowform.Error) as ctx:
                call()
            self.assertEqual(str(ctx.exception), want)
        sim.set_region({"box": {"min": np.zeros(3), "max": np.array([0.2, 0.05, 0.2], dtype=np.float32)}})
        sim.set_params({"fluid": {"viscosity": np.float32(0.5)}})
        sim.step()
        # The NumPy numbers are the ones read: a box of no height is refused as such.
        with self.assertRaises(flowform.Error) as ctx:
            sim.set_region({"box": {"min": np.zeros(3), "max": np.array([0.2, 0.0, 0.2])}})
        self.assertIn("<region>: region.box: min must be < max on every axis", str(ctx.exception))
        with self.assertRaises(flowform.Error) as ctx:
            sim.set_params({"fluid": {"viscosity": np.float64(-1.0)}})
        self.assertIn("params.fluid.viscosity: must be in [0, 10000] (got -1)", str(ctx.exception))

    def test_absurd_run_lengths_and_thread_counts_are_refused(self):
        # Once a MemoryError (steps: the metrics arrays) and a segfault (threads).
        sim = flowform.Simulation(SCENE, backend="cpu", threads=2)
        with self.assertRaises(flowform.Error) as ctx:
            sim.run(steps=10**12)
        self.assertIn("run: steps", str(ctx.exception))
        with self.assertRaises(flowform.Error) as ctx:
            sim.run(seconds=1e300)
        self.assertIn("run: seconds", str(ctx.exception))
        self.assertEqual(sim.step_count, 0)  # refused before stepping
        with self.assertRaises(flowform.Error) as ctx:
            flowform.Simulation(SCENE, backend="cpu", threads=100000)
        self.assertIn("threads: must be in [0, 1024]", str(ctx.exception))

    def test_params_given_with_the_scene_act_from_the_start(self):
        # Simulation(scene, params=...) is the scene with those params, bit for
        # bit: control.adaptive, read where a target is placed, acts.
        over = {"control": {"adaptive": 1}}
        a = flowform.Simulation(SCENE, backend="cpu", threads=2, params=over).run(steps=3)
        b = flowform.Simulation(dict(SCENE, params=over), backend="cpu", threads=2).run(steps=3)
        self.assertTrue(np.array_equal(a["iou"], b["iou"]))
        self.assertTrue(np.array_equal(a["max_speed"], b["max_speed"]))
        plain = flowform.Simulation(SCENE, backend="cpu", threads=2).run(steps=3)
        self.assertFalse(np.array_equal(a["iou"], plain["iou"]))
        # set_params places the control particles again where control.adaptive
        # changes: given before the first step, the run is the one that
        # started with it (iou and speeds bit for bit).
        late = flowform.Simulation(SCENE, backend="cpu", threads=2)
        late.set_params(over)
        c = late.run(steps=3)
        self.assertTrue(np.array_equal(a["iou"], c["iou"]))
        self.assertTrue(np.array_equal(a["max_speed"], c["max_speed"]))
        with self.assertRaises(flowform.Error) as ctx:
            flowform.Simulation(SCENE, backend="cpu", threads=2, params={"fluid": {"viscosity": -1}})
        self.assertIn("<params>: params.fluid.viscosity: must be in", str(ctx.exception))
        with self.assertRaises(flowform.Error) as ctx:
            flowform.Simulation(SCENE, backend="cpu", threads=2, params=5)
        self.assertIn("params: give a dict", str(ctx.exception))

    def test_run_until_stops_where_the_time_reaches_until(self):
        # run(until=T): no step where sim.time >= T already, else the fewest
        # steps after which sim.time >= T (less than one step past it),
        # counted from the frame clock (before: from step_count * the current
        # step, wrong once set_params changed the step).
        sim = flowform.Simulation(SCENE, backend="cpu", threads=2)
        dt = float(np.float32(0.004))  # the water preset's 4 ms frame step, a float
        self.assertEqual(len(sim.run(until=0.01)["step"]), 3)  # 0.008 < 0.01 <= 0.012
        self.assertEqual(len(sim.run(until=0.011)["step"]), 0)  # reached: nothing to run
        self.assertEqual(len(sim.run(until=0.012)["step"]), 0)
        self.assertEqual(len(sim.run(until=0.0121)["step"]), 1)
        self.assertAlmostEqual(sim.time, 4 * dt, delta=1e-12)
        sim.set_params({"fluid": {"time_step": 0.002}})
        t = sim.time
        self.assertEqual(len(sim.run(until=t + 0.004)["step"]), 2)
        self.assertAlmostEqual(sim.time, t + 2 * float(np.float32(0.002)), delta=1e-12)
        # 0.005 as a float is 0.004999999888: four steps end at 0.0199999996 s,
        # which has reached 0.02 (before: five steps, to 0.025).
        scene = dict(SCENE, params={"fluid": {"time_step": 0.005}})
        five = flowform.Simulation(scene, backend="cpu", threads=2)
        self.assertEqual(len(five.run(until=0.02)["step"]), 4)
        # Where the substeps carry over the frame (the water preset), the
        # fluid's clock sim.time runs ahead of the frames by less than a
        # substep and the lead changes from step to step: every run still
        # ends at or past `until`, and the fluid's clock led somewhere.
        lead = 0.0
        for until in np.arange(0.02, 0.4, 0.0137):
            five.run(until=until)
            self.assertGreaterEqual(five.time, until)
            self.assertLess(five.time, until + 2 * 0.005)
            lead = max(lead, five.time - five.step_count * float(np.float32(0.005)))
        self.assertGreater(lead, 0.0)

    def test_a_folder_given_as_the_checkpoint_file_is_named(self):
        sim = flowform.Simulation(SCENE, backend="cpu", threads=2)
        for path in (".", self.dir):
            with self.assertRaises(flowform.Error) as ctx:
                sim.save_checkpoint(path)
            self.assertIn(path + ": cannot write the checkpoint: this is a folder", str(ctx.exception))
            with self.assertRaises(flowform.Error) as ctx:
                flowform.resume(path, threads=2)
            self.assertIn(path + ": cannot open the checkpoint: this is a folder", str(ctx.exception))

    def test_backend_and_device_errors_name_the_keywords(self):
        # Python's keywords backend= and device=, not the CLI's --backend and --device.
        cases = [
            (dict(backend="cuda"), "backend: unknown backend 'cuda'"),
            (dict(backend="cpu", device=0), "device: only applies to the OpenCL backend (backend='opencl' or"),
            (dict(backend="opencl", device=-3), "device: must be >= 0 (got -3)"),
        ]
        ck = os.path.join(self.dir, "c.ffck")
        flowform.Simulation(SCENE, backend="cpu", threads=2).save_checkpoint(ck)
        for kwargs, want in cases:
            for make in (lambda: flowform.Simulation(SCENE, threads=2, **kwargs),
                         lambda: flowform.resume(ck, threads=2, **kwargs)):
                with self.assertRaises(flowform.Error) as ctx:
                    make()
                self.assertIn(want, str(ctx.exception))
                self.assertNotIn("--", str(ctx.exception))
        # A device number past the last: named as device= too (or, without
        # OpenCL, the backend as backend='opencl').
        with self.assertRaises(flowform.Error) as ctx:
            flowform.Simulation(SCENE, backend="opencl", device=9999, threads=2)
        msg = str(ctx.exception)
        self.assertTrue(msg.startswith("device 9999: no such OpenCL device") or
                        msg.startswith("backend='opencl': ") or msg.startswith("OpenCL"), msg)
        self.assertNotIn("--device", msg)

    def test_export_and_checkpoint(self):
        sim = flowform.Simulation(SCENE, backend="cpu", threads=2)
        out = os.path.join(self.dir, "exp")
        exporter = flowform.Exporter(out, formats="ply", every_steps=1)
        exporter.write(sim)
        sim.step()
        self.assertTrue(exporter.write_if_due(sim))
        self.assertEqual(exporter.frames, 2)
        mesh = meshio.read(os.path.join(out, "fluid_00001.ply"))
        self.assertEqual(len(mesh.points), 1000)
        # fps and every_steps exclude each other, as --fps and --export-every
        # (fps was ignored before).
        with self.assertRaises(flowform.Error) as ctx:
            flowform.Exporter(os.path.join(self.dir, "both"), fps=10, every_steps=2)
        self.assertIn("fps or every_steps, not both", str(ctx.exception))
        # A folder holding another run's frames: refused, naming Python's keyword.
        with self.assertRaises(flowform.Error) as ctx:
            flowform.Exporter(out, formats="ply", every_steps=1).write(sim)
        self.assertIn("overwrite=True", str(ctx.exception))
        self.assertNotIn("--", str(ctx.exception))
        flowform.Exporter(out, formats="ply", every_steps=1, overwrite=True).write(sim)
        self.assertFalse(os.path.exists(os.path.join(out, "fluid_00001.ply")))
        ck = os.path.join(self.dir, "c.ffck")
        sim.save_checkpoint(ck)
        a = sim.run(steps=3)
        b = flowform.resume(ck, threads=2).run(steps=3)
        self.assertTrue(np.array_equal(a["iou"], b["iou"]))
        self.assertTrue(np.array_equal(a["max_speed"], b["max_speed"]))
        # The OpenCL backend (where there is one) cannot write or resume
        # checkpoints: refused naming Python's backend='cpu', not --backend.
        try:
            cl = flowform.Simulation(SCENE, backend="opencl", threads=2)
        except flowform.Error:
            return  # built without OpenCL, or no device
        for refused in (lambda: cl.save_checkpoint(os.path.join(self.dir, "cl.ffck")),
                        lambda: flowform.resume(ck, backend="opencl", threads=2)):
            with self.assertRaises(flowform.Error) as ctx:
                refused()
            self.assertIn("backend='cpu'", str(ctx.exception))
            self.assertNotIn("--", str(ctx.exception))
        self.assertFalse(os.path.exists(os.path.join(self.dir, "cl.ffck")))


if __name__ == "__main__":
    EXE = sys.argv[1]
    sys.path.insert(0, sys.argv[2])
    import flowform  # noqa: E402
    unittest.main(argv=sys.argv[:1], verbosity=2)
