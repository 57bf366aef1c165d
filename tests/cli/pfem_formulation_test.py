#!/usr/bin/python3
"""`pfem run --formulation` and analysis.formulation end to end (docs/model-reference.md,
"analysis"): the incompressible formulation's DDM is labelled "ddm-approximate" in summary.json,
the quasi-incompressible one "ddm"; the incompressible run says that the model's fluid.kappa is
ignored; an unknown formulation is a usage error (exit 2) on the command line and a field error
in the model file.

Run by ctest (pfem_formulation_test) with PFEM_CLI=build/bin/pfem, PFEM_SOURCE_DIR=the source."""
import json
import os
import shutil
import subprocess
import tempfile
import unittest

PFEM = os.environ["PFEM_CLI"]
MODEL = os.path.join(os.environ["PFEM_SOURCE_DIR"], "examples", "sloshing-beam.json")


class FormulationTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="pfem_formulation_")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp)

    def run_pfem(self, *args):
        return subprocess.run([PFEM, *args], capture_output=True, text=True, timeout=120)

    def summary(self, formulation):
        out = os.path.join(self.tmp, formulation)
        r = self.run_pfem("run", MODEL, "--out", out, "--t-end", "0.01", "--sensitivity", "ddm", "--params", "E",
                          "--formulation", formulation)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(out, "summary.json")) as f:
            return json.load(f)

    def test_the_incompressible_ddm_is_labelled_approximate(self):
        s = self.summary("incompressible")
        self.assertEqual(s["status"], "completed")
        self.assertEqual(s["sensitivity_method"], "ddm-approximate")
        self.assertTrue(any(w.startswith("fluid.kappa: is ignored") for w in s["warnings"]), s["warnings"])

    def test_the_quasi_incompressible_ddm_is_exact(self):
        s = self.summary("quasi-incompressible")
        self.assertEqual(s["sensitivity_method"], "ddm")
        self.assertFalse(any(w.startswith("fluid.kappa") for w in s["warnings"]), s["warnings"])

    def test_an_unknown_formulation_flag_is_a_usage_error(self):
        r = self.run_pfem("run", MODEL, "--out", os.path.join(self.tmp, "bad"), "--formulation", "compressible")
        self.assertEqual(r.returncode, 2)
        self.assertIn("--formulation must be quasi-incompressible or incompressible", r.stderr)

    def test_an_unknown_formulation_in_the_model_is_a_field_error(self):
        with open(MODEL) as f:
            model = json.load(f)
        model["analysis"]["formulation"] = "compressible"
        path = os.path.join(self.tmp, "compressible.json")
        with open(path, "w") as f:
            json.dump(model, f)
        r = self.run_pfem("validate", path)
        self.assertEqual(r.returncode, 2)
        self.assertIn("analysis.formulation: must be quasi-incompressible or incompressible (got 'compressible')",
                      r.stdout + r.stderr)


if __name__ == "__main__":
    unittest.main()
