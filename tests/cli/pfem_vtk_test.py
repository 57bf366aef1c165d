#!/usr/bin/python3
"""`pfem run --vtk` on the yielding obstacle with DDM: the .pvd collections, the zero-padded
.vtu files (read here as XML), no removed particle, the legend, and every field at the
recorders' nodes and element equal to responses.csv and sensitivities.csv at the same times.

Run by ctest (pfem_vtk_test) with PFEM_CLI=build/bin/pfem, PFEM_SOURCE_DIR=the source."""
import csv
import json
import os
import shutil
import subprocess
import tempfile
import unittest
import xml.etree.ElementTree as ET

import numpy as np

PFEM = os.environ["PFEM_CLI"]
MODEL = os.path.join(os.environ["PFEM_SOURCE_DIR"], "examples", "dam-break-obstacle.json")
T_END, EVERY, PARAMS = 0.3, 50, ["E", "rho_f"]  # the water reaches the obstacle at about 0.2 s


def read_vtu(path):
    """(points (n, 3), point fields, cell fields, cell types, connectivity, the raw text)."""
    with open(path) as f:
        text = f.read()
    piece = ET.fromstring(text).find("UnstructuredGrid/Piece")

    def arrays(node):
        out = {}
        for a in node.findall("DataArray"):
            values = np.array(a.text.split(), dtype=np.float64)
            n = int(a.get("NumberOfComponents", "1"))
            out[a.get("Name")] = values.reshape(-1, n) if n > 1 else values
        return out

    cells = arrays(piece.find("Cells"))
    return (arrays(piece.find("Points"))["position"], arrays(piece.find("PointData")),
            arrays(piece.find("CellData")) if piece.find("CellData") is not None else {},
            cells["types"], cells["connectivity"], text)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    data = np.array(rows[1:], dtype=np.float64)
    return data[:, 0], {name: data[:, j] for j, name in enumerate(rows[0]) if j > 0}


def collection(path):
    return [(float(d.get("timestep")), d.get("file"))
            for d in ET.parse(path).getroot().iter("DataSet")]


class VtkOutputTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="pfem_vtk_")
        cls.out = os.path.join(cls.tmp, "obstacle")
        subprocess.run([PFEM, "run", MODEL, "--out", cls.out, "--t-end", str(T_END), "--vtk-every",
                        str(EVERY), "--sensitivity", "ddm", "--params", ",".join(PARAMS)],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        cls.time, cls.responses = read_csv(os.path.join(cls.out, "responses.csv"))
        _, cls.sensitivities = read_csv(os.path.join(cls.out, "sensitivities.csv"))
        with open(os.path.join(cls.out, "summary.json")) as f:
            cls.summary = json.load(f)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def row(self, t):
        i = int(np.argmin(np.abs(self.time - t)))
        self.assertAlmostEqual(self.time[i], t, places=12)
        return i

    def assert_close(self, actual, expected, what):
        # the .vtu files carry 15 significant digits, the CSV files 17
        self.assertLessEqual(abs(actual - expected), 1e-13 * abs(expected), f"{what}: {actual!r} vs {expected!r}")

    def test_collections_and_names(self):
        vtk = os.path.join(self.out, "vtk")
        steps = round(T_END / 0.001)
        expected_times = [k * EVERY * 0.001 for k in range(steps // EVERY + 1)]
        for stem in ("pfem", "beams"):
            files = collection(os.path.join(vtk, f"{stem}.pvd"))
            np.testing.assert_allclose([t for t, _ in files], expected_times, rtol=0, atol=1e-12)
            self.assertEqual([f for _, f in files],
                             [f"{stem}_{k:06d}.vtu" for k in range(len(expected_times))])

    def test_fluid_files(self):
        vtk = os.path.join(self.out, "vtk")
        files = collection(os.path.join(vtk, "pfem.pvd"))
        for t, name in files:
            points, fields, _, types, connectivity, text = read_vtu(os.path.join(vtk, name))
            self.assertIn("kind: 0 fluid particle, 1 wall node, 2 structure node", text)
            self.assertEqual(sorted(set(fields["kind"])), [0, 1, 2], name)  # no 3: removed left out
            for f in ("velocity", "pressure", "displacement", "free_surface",
                      *(f"d_{q}/d{p}" for q in ("velocity", "pressure", "displacement") for p in PARAMS)):
                self.assertEqual(len(fields[f]), len(points), f)
            self.assertEqual(int(np.sum(types == 1)), int(np.sum(fields["kind"] == 0)))
            self.assertLess(int(connectivity.max()), len(points))
        # the last file: every particle there is, after insertions and removals
        _, fields, *_ = read_vtu(os.path.join(vtk, files[-1][1]))
        s = self.summary
        self.assertGreater(s["removed_particles"] + s["inserted_particles"], 0)
        self.assertEqual(int(np.sum(fields["kind"] == 0)),
                         s["particles"] + s["inserted_particles"] - s["removed_particles"] - s["left_domain"])

    def test_beam_fields_equal_the_recorders(self):
        vtk = os.path.join(self.out, "vtk")
        files = collection(os.path.join(vtk, "beams.pvd"))
        checked = 0
        for t, name in files:
            points, fields, cell_fields, types, connectivity, text = read_vtu(os.path.join(vtk, name))
            self.assertIn("axial_force (tension > 0)", text)
            self.assertEqual(list(types), [3] * 16)  # 16 elements as VTK_LINE
            self.assertEqual(list(cell_fields["element"]), list(range(16)))
            initial_y = points[:, 1] - fields["displacement"][:, 1]
            order = np.argsort(initial_y)
            tip, base1 = order[-1], order[1]  # "tip" at the top; "obstacle/1" just above the base
            self.assertEqual(list(connectivity[:2]), [order[0], base1])  # element obstacle/1
            i = self.row(t)
            r, d = self.responses, self.sensitivities
            self.assert_close(fields["displacement"][tip, 0], r["tip_ux"][i], f"tip_ux at {t}")
            self.assert_close(fields["pressure"][base1], r["base_p"][i], f"base_p at {t}")
            self.assert_close(cell_fields["moment_i"][0], r["base_moment"][i], f"base_moment at {t}")
            for p in PARAMS:
                self.assert_close(fields[f"d_displacement/d{p}"][tip, 0], d[f"dtip_ux/d{p}"][i], p)
                self.assert_close(fields[f"d_pressure/d{p}"][base1], d[f"dbase_p/d{p}"][i], p)
                self.assert_close(cell_fields[f"d_moment_i/d{p}"][0], d[f"dbase_moment/d{p}"][i], p)
                for q in ("rotation", "velocity"):
                    self.assertIn(f"d_{q}/d{p}", fields)
                for q in ("axial_force", "moment_j"):
                    self.assertEqual(len(cell_fields[f"d_{q}/d{p}"]), 16)
            checked += abs(r["tip_ux"][i]) > 0 and abs(d["dtip_ux/dE"][i]) > 0
        self.assertGreaterEqual(checked, 2)  # the water has pushed the obstacle by then


if __name__ == "__main__":
    unittest.main()
