#!/usr/bin/python3
"""The surface meshes of `flowform run --export DIR --surface`, read with
meshio (Debian's python3-meshio), checked against independent values:

- a resting block (the rest lattice at time 0) gives a watertight mesh (every
  edge in exactly two triangles, each directed edge once: consistently wound)
  whose enclosed volume, by the divergence theorem computed here, is within
  10% of the fluid's rest volume N * m / rho0, and whose bounds are the block's;
- the mesh stays watertight once the block has started to spread;
- OBJ and PLY carry the same mesh; the level set is written as an OpenVDB file.

Usage: test_surface_mesh.py FLOWFORM_EXE
"""
import collections
import os
import struct
import subprocess
import sys
import tempfile
import unittest

import meshio
import numpy as np

EXE = None
MASS, RHO0 = 0.0002, 800.0  # the paper preset's particle mass and rest density
SPACING = (MASS / RHO0) ** (1.0 / 3.0)
DIMS = (12, 10, 14)
SCENE = """{
  "name": "resting block",
  "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]},
  "fluid": [{"origin": [0.05, 0, 0.04], "dims": [12, 10, 14]}]
}"""


def triangles(mesh):
    return np.concatenate([c.data for c in mesh.cells if c.type == "triangle"]).astype(np.int64)


def volume(points, tris):
    a, b, c = (points[tris[:, k]].astype(np.float64) for k in range(3))
    return np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0


def edge_counts(tris):
    directed = collections.Counter()
    for t in tris.tolist():
        for k in range(3):
            directed[(t[k], t[(k + 1) % 3])] += 1
    undirected = collections.Counter()
    for (u, v), n in directed.items():
        undirected[(min(u, v), max(u, v))] += n
    return directed, undirected


class SurfaceMesh(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="flowform_surface_")
        scene = os.path.join(cls.tmp.name, "block.json")
        with open(scene, "w") as f:
            f.write(SCENE)
        cls.out = {}
        for fmt in ("obj", "ply"):
            out = os.path.join(cls.tmp.name, fmt)
            r = subprocess.run([EXE, "run", scene, "--backend", "cpu", "--seconds", "0.4", "--fps", "5",
                                "--export", out, "--surface", "--surface-format", fmt, "--surface-vdb"],
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            assert r.returncode == 0, r.stdout
            cls.out[fmt] = out

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def check_watertight(self, tris):
        directed, undirected = edge_counts(tris)
        self.assertTrue(all(n == 2 for n in undirected.values()),
                        f"{sum(1 for n in undirected.values() if n != 2)} edges not in exactly two triangles")
        self.assertTrue(all(n == 1 for n in directed.values()), "inconsistent winding")

    def test_resting_block_is_watertight_with_its_rest_volume(self):
        m = meshio.read(os.path.join(self.out["obj"], "surface_00000.obj"))
        tris = triangles(m)
        self.assertGreater(len(tris), 100)
        self.check_watertight(tris)
        rest = np.prod(DIMS) * MASS / RHO0
        v = volume(m.points, tris)
        self.assertGreater(v, 0.0)  # wound outwards
        self.assertLess(abs(v / rest - 1.0), 0.10, f"volume {v} vs rest volume {rest}")
        lo = np.array([0.05, 0.0, 0.04])
        hi = lo + np.array(DIMS) * SPACING
        np.testing.assert_allclose(m.points.min(axis=0), lo, atol=0.25 * SPACING)
        np.testing.assert_allclose(m.points.max(axis=0), hi, atol=0.25 * SPACING)
        with open(os.path.join(self.out["obj"], "surface_00000.obj")) as f:
            self.assertIn("# time 0", f.read(200))

    def test_spreading_block_stays_watertight(self):
        for k in (1, 2):
            m = meshio.read(os.path.join(self.out["obj"], f"surface_{k:05d}.obj"))
            self.check_watertight(triangles(m))

    def test_ply_holds_the_same_mesh_and_the_level_set_is_a_vdb(self):
        a = meshio.read(os.path.join(self.out["obj"], "surface_00001.obj"))
        b = meshio.read(os.path.join(self.out["ply"], "surface_00001.ply"))
        np.testing.assert_array_equal(triangles(a), triangles(b))
        # OBJ holds the shortest text of each float: read back as float32, it is exact.
        np.testing.assert_array_equal(a.points.astype(np.float32), b.points.astype(np.float32))
        with open(os.path.join(self.out["ply"], "surface_00001.ply"), "rb") as f:
            self.assertIn(b"comment time 0.2", f.read(200))
        for out in self.out.values():
            with open(os.path.join(out, "surface_00001.vdb"), "rb") as f:
                magic = struct.unpack("<q", f.read(8))[0]
            self.assertEqual(magic, 0x56444220)  # OpenVDB's file magic, " BDV"


if __name__ == "__main__":
    EXE = sys.argv.pop(1)
    unittest.main()
