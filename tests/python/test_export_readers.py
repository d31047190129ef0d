#!/usr/bin/python3
"""Reads `flowform run --export` output with readers flowform did not write.

- VTK: meshio (Debian's python3-meshio) reads every .vtu (points, velocity,
  id, density, pressure; rest_position and s for the control particles) and
  Python's xml.etree reads the .pvd collections' times.
- BGEO: a parser of Houdini's classic binary geometry layout (version 5, as
  Houdini documents it for .geo/.bgeo and as partio reads it), written here from
  the layout, not from flowform's writer. No BGEO reader is packaged in Debian 12
  and CI installs nothing from PyPI, so the test carries its own.
- PLY: meshio again.

Checks against independent values: a block falling freely (no target, no
contact yet) has mean vertical velocity -g*t exactly (SPH pair forces cancel),
at the time each file states; ids are a permutation of 0..n-1; the three
formats agree particle by particle (matched by id); the frames fall at the
frame rate.

Usage: test_export_readers.py FLOWFORM_EXE
"""
import os
import struct
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET

import meshio
import numpy as np

EXE = None
G = 9.81
FPS = 30.0


def read_bgeo(path):
    """Houdini classic .bgeo (big-endian): header, point attribute
    definitions, points (P as x y z w, then the attributes), no primitives,
    detail attributes (definitions, then values), and the 0x00 0xff end."""
    with open(path, "rb") as f:
        data = f.read()
    pos = 0

    def take(fmt):
        nonlocal pos
        vals = struct.unpack_from(">" + fmt, data, pos)
        pos += struct.calcsize(">" + fmt)
        return vals

    assert data[:5] == b"BgeoV", data[:5]
    pos = 5
    (version,) = take("i")
    assert version == 5
    n_points, n_prims, n_point_groups, n_prim_groups = take("4i")
    n_point_attrib, n_vertex_attrib, n_prim_attrib, n_detail_attrib = take("4i")
    assert (n_prims, n_point_groups, n_prim_groups, n_vertex_attrib, n_prim_attrib) == (0, 0, 0, 0, 0)

    def definitions(count):
        out = []
        for _ in range(count):
            (name_len,) = take("H")
            name = data[pos : pos + name_len].decode()
            take(f"{name_len}x")
            size, htype = take("Hi")
            assert htype in (0, 1, 5), htype  # float, int, vector
            take(f"{size}i")  # defaults
            out.append((name, size, "i" if htype == 1 else "f"))
        return out

    attrs = definitions(n_point_attrib)
    # Each point: P (4 floats) then the attributes' 32-bit values (ints are
    # unpacked as ints, exact in the float64 table below up to 2**53).
    fmt = ">4f" + "".join(t * size for _, size, t in attrs)
    rec = struct.calcsize(fmt)
    rows = [struct.unpack_from(fmt, data, pos + i * rec) for i in range(n_points)]
    pos += n_points * rec
    table = np.array(rows, dtype=np.float64).reshape(n_points, -1)
    out = {"P": table[:, 0:3], "Pw": table[:, 3]}
    col = 4
    for name, size, t in attrs:
        block = table[:, col : col + size]
        out[name] = (block.astype(np.int64) if t == "i" else block).reshape(n_points, size)
        col += size
    detail = {}
    for name, size, t in definitions(n_detail_attrib):
        detail[name] = take(f"{size}{t}")
    assert data[pos:] == b"\x00\xff", data[pos:]
    return out, detail, attrs


def pvd_times(path):
    root = ET.parse(path).getroot()
    assert root.get("type") == "Collection"
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]


def run(args):
    r = subprocess.run([EXE] + args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return r.returncode, r.stdout


SCENE_FALL = """{
  "name": "falling block",
  "container": {"min": [0, 0, 0], "max": [0.3, 0.6, 0.3]},
  "fluid": [{"origin": [0.1, 0.35, 0.1], "dims": [8, 8, 8]}],
  "params": {"fluid": {"gravity": [0, -9.81, 0]}}
}"""

SCENE_TARGET = """{
  "name": "block into a sphere",
  "container": {"min": [0, 0, 0], "max": [0.3, 0.3, 0.3]},
  "fluid": [{"origin": [0.1, 0.0, 0.1], "dims": [8, 8, 8]}],
  "region": "all",
  "schedule": [{"time": 0.0, "target": "sphere"}]
}"""


class ExportReaders(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="flowform_export_")
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def export(self, scene_text, seconds, formats, out="out", extra=()):
        scene = os.path.join(self.dir, "scene.json")
        with open(scene, "w") as f:
            f.write(scene_text)
        out = os.path.join(self.dir, out)
        code, text = run(["run", scene, "--backend", "cpu", "--threads", "2", "--seconds", str(seconds),
                          "--export", out, "--format", formats, *extra])
        self.assertEqual(code, 0, text)
        return out, text

    def test_falling_block_in_all_formats(self):
        out, _ = self.export(SCENE_FALL, 0.1, "vtk,bgeo,ply")
        n = 8 * 8 * 8
        times = pvd_times(os.path.join(out, "fluid.pvd"))
        # Frames at 30 fps over 0.1 s: 0, 1/30, 2/30, 3/30, each at the first
        # step (4 ms) at or after its frame time.
        self.assertEqual([f for _, f in times], [f"fluid_{k:05d}.vtu" for k in range(4)])
        for k, (t, _) in enumerate(times):
            self.assertGreaterEqual(t, k / FPS - 1e-6)
            self.assertLess(t, k / FPS + 0.004 + 1e-6)
        self.assertEqual([t for t, _ in pvd_times(os.path.join(out, "control.pvd"))], [t for t, _ in times])
        for k, (t, name) in enumerate(times):
            m = meshio.read(os.path.join(out, name))
            self.assertEqual(m.points.shape, (n, 3))
            self.assertEqual(len(m.cells), 1)
            self.assertEqual(m.cells[0].type, "vertex")
            self.assertEqual(len(m.cells[0].data), n)
            self.assertAlmostEqual(float(np.ravel(m.field_data["TimeValue"])[0]), t, places=7)
            vel = m.point_data["velocity"]
            ids = m.point_data["id"].astype(np.int64).ravel()
            self.assertEqual(vel.shape, (n, 3))
            self.assertTrue(np.issubdtype(m.point_data["id"].dtype, np.integer))
            self.assertEqual(sorted(ids.tolist()), list(range(n)))
            self.assertTrue(np.all(np.isfinite(m.point_data["density"])))
            self.assertTrue(np.all(np.isfinite(m.point_data["pressure"])))
            # Free fall: the mean velocity is (0, -g t, 0) at the file's time.
            mean = vel.mean(axis=0)
            self.assertAlmostEqual(mean[1], -G * t, delta=1e-3 + 1e-3 * G * t)
            self.assertAlmostEqual(mean[0], 0.0, delta=1e-3)
            self.assertAlmostEqual(mean[2], 0.0, delta=1e-3)
            order = np.argsort(ids)

            # BGEO: same particles, same velocities, same time.
            geo, detail, attrs = read_bgeo(os.path.join(out, f"fluid_{k:05d}.bgeo"))
            self.assertEqual([a[0] for a in attrs], ["v", "id", "density", "pressure"])
            self.assertAlmostEqual(detail["time"][0], t, places=6)
            bids = geo["id"].ravel()
            border = np.argsort(bids)
            self.assertEqual(sorted(bids.tolist()), list(range(n)))
            np.testing.assert_array_equal(geo["Pw"], 1.0)
            np.testing.assert_allclose(geo["P"][border], m.points[order], rtol=0, atol=0)
            np.testing.assert_allclose(geo["v"][border], vel[order], rtol=0, atol=0)
            np.testing.assert_allclose(geo["density"][border].ravel(), m.point_data["density"].ravel()[order], atol=0)

            # PLY: meshio again; the time in a comment.
            ply_path = os.path.join(out, f"fluid_{k:05d}.ply")
            p = meshio.read(ply_path)
            pids = p.point_data["id"].astype(np.int64)
            self.assertEqual(p.point_data["id"].dtype, np.int32)
            porder = np.argsort(pids)
            pv = np.stack([p.point_data[c] for c in ("vx", "vy", "vz")], axis=1)
            np.testing.assert_allclose(pv[porder], vel[order], atol=0)
            with open(ply_path, "rb") as f:
                head = f.read(300).split(b"end_header")[0].decode()
            self.assertIn(f"comment time {t:.9g}", head)

    def test_control_particles_and_frame_rate(self):
        out, _ = self.export(SCENE_TARGET, 0.2, "vtk,bgeo", extra=["--fps", "10"])
        times = pvd_times(os.path.join(out, "control.pvd"))
        self.assertEqual(len(times), 3)  # 0, 0.1, 0.2
        t, name = times[-1]
        self.assertAlmostEqual(t, 0.2, delta=1e-6)
        m = meshio.read(os.path.join(out, name))
        count = len(m.points)
        self.assertGreater(count, 0)
        self.assertEqual(m.point_data["rest_position"].shape, (count, 3))
        self.assertEqual(m.point_data["velocity"].shape, (count, 3))
        s = m.point_data["s"]
        self.assertTrue(np.all(np.isfinite(s)))
        self.assertEqual(sorted(m.point_data["id"].astype(np.int64).ravel().tolist()), list(range(count)))
        # The rest positions fill a ball: its outermost point is 2**(1/3) = 1.26
        # times the median distance from the centre (voxelised: loosely).
        rest = m.point_data["rest_position"]
        radius = np.linalg.norm(rest - rest.mean(axis=0), axis=1)
        self.assertGreater(radius.max(), 1.1 * np.median(radius))
        self.assertLess(radius.max(), 1.45 * np.median(radius))
        geo, detail, attrs = read_bgeo(os.path.join(out, "control_00002.bgeo"))
        self.assertEqual([a[0] for a in attrs], ["v", "id", "rest", "s"])
        self.assertEqual(len(geo["P"]), count)
        np.testing.assert_allclose(np.sort(geo["rest"][:, 1]), np.sort(rest[:, 1]), atol=0)

    def test_folder_with_another_runs_frames_is_refused_or_cleaned(self):
        out, _ = self.export(SCENE_FALL, 0.04, "vtk")
        mine = os.path.join(out, "notes.txt")
        similar = os.path.join(out, "fluid_notes.vtu")
        for p in (mine, similar):
            with open(p, "w") as f:
                f.write("the user's")
        scene = os.path.join(self.dir, "scene.json")
        code, text = run(["run", scene, "--backend", "cpu", "--steps", "2", "--export", out, "--format", "ply"])
        self.assertEqual(code, 1, text)  # an error, not a crash (a signal gives a negative code)
        self.assertIn(out, text)
        self.assertIn("--overwrite", text)
        self.assertEqual(len(text.strip().splitlines()), 1, text)
        self.assertTrue(os.path.exists(os.path.join(out, "fluid_00000.vtu")))  # nothing removed
        code, text = run(["run", scene, "--backend", "cpu", "--steps", "2", "--export", out, "--format", "ply",
                          "--overwrite", "--export-every", "1"])
        self.assertEqual(code, 0, text)
        left = sorted(os.listdir(out))
        self.assertEqual(left, ["control_00000.ply", "control_00001.ply", "control_00002.ply", "fluid_00000.ply",
                                "fluid_00001.ply", "fluid_00002.ply", "fluid_notes.vtu", "notes.txt"])

    def test_bad_format_is_a_one_line_error(self):
        code, text = run(["run", "--steps", "1", "--export", os.path.join(self.dir, "x"), "--format", "vtk,obj"])
        self.assertEqual(code, 1, text)  # an error, not a crash (a signal gives a negative code)
        self.assertIn("--format", text)
        self.assertIn("obj", text)


if __name__ == "__main__":
    EXE = sys.argv.pop(1)
    unittest.main()
