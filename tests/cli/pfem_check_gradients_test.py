#!/usr/bin/python3
"""`pfem check-gradients` end to end (README, "Exact gradients"): its table marks the columns it
cannot compare and its verdict counts the others; exit 0 when every compared column is within the
tolerance, 1 otherwise.

The yielding obstacle to 0.03 s, before the water reaches it: its sway and base pressure stay 0
in every run ("unmoved"), its base moment is round-off, so its finite difference w.r.t. E is
noise ("FDM not a slope", with the run's warning), and its base fiber stress (self-weight) and
the water's front are compared.

Run by ctest (pfem_check_gradients_test) with PFEM_CLI=build/bin/pfem, PFEM_SOURCE_DIR=the source."""
import os
import re
import subprocess
import unittest

PFEM = os.environ["PFEM_CLI"]
MODEL = os.path.join(os.environ["PFEM_SOURCE_DIR"], "examples", "dam-break-obstacle.json")


def check(*extra):
    return subprocess.run([PFEM, "check-gradients", MODEL, "--params", "E,rho_f", "--t-end", "0.03", *extra],
                          capture_output=True, text=True, timeout=300)


def rows(stdout):
    """{(recorder, parameter): (DDM figure, mark)} from the table."""
    table = {}
    for line in stdout.splitlines():
        m = re.match(r"^(\S+)\s+(\S+)\s+\S+e[+-]\d+\s+(\S+)\s+\S+\s*(.*)$", line)
        if m:
            table[(m.group(1), m.group(2))] = (float(m.group(3)), m.group(4).strip())
    return table


class CheckGradientsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.default = check()

    def test_columns_without_a_slope_are_marked_and_left_out(self):
        r = self.default
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        table = rows(r.stdout)
        self.assertEqual(len(table), 12, r.stdout)
        for p in ("E", "rho_f"):
            for recorder in ("tip_ux", "base_p"):
                mark = table[(recorder, p)][1]
                self.assertTrue(mark.startswith("unmoved, max |DDM| "), mark)
                self.assertLess(float(mark.split()[-1]), 1e-20, mark)  # round-off
        self.assertEqual(table[("base_moment", "E")][1], "FDM not a slope")
        self.assertIn("dbase_moment/dE: the two one-sided differences", r.stderr)
        compared = [k for k, (ddm, mark) in table.items() if not mark]
        self.assertIn(("base_fiber_stress", "E"), compared)
        self.assertIn(("front_x", "rho_f"), compared)
        for k in compared:
            self.assertLess(table[k][0], 1e-3, k)
        verdict = f"DDM within 0.001 of FDM: yes, {len(compared)} of 12 columns (not compared: "
        self.assertIn(verdict, r.stdout)
        self.assertIn("4 unmoved: the response and its FDM 0 throughout", r.stdout)

    def test_a_compared_column_beyond_the_tolerance_fails_the_check(self):
        r = check("--tolerance", "1e-12")
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertRegex(r.stdout, r"DDM within 1e-12 of FDM: NO, \d+ of 12 columns")


if __name__ == "__main__":
    unittest.main()
