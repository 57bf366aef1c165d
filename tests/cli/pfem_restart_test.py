#!/usr/bin/python3
"""`pfem run --checkpoint-every N` stopped by SIGTERM and continued by `pfem run --restart DIR`:
every output (responses.csv, sensitivities.csv, the VTK files and their .pvd, the summary's
counts) is byte for byte that of a run never stopped. A restart that would change the run is
refused.

Run by ctest (pfem_restart_test) with PFEM_CLI=build/bin/pfem, PFEM_SOURCE_DIR=the source."""
import filecmp
import json
import os
import shutil
import signal
import subprocess
import tempfile
import unittest

PFEM = os.environ["PFEM_CLI"]
MODEL = os.path.join(os.environ["PFEM_SOURCE_DIR"], "examples", "dam-break.json")
TIMINGS = {"wall_seconds", "response_seconds", "sensitivity_seconds", "remesh_seconds",
           "assemble_seconds", "factorize_seconds", "solve_seconds"}


def read(path):
    with open(path, "rb") as f:
        return f.read()


def counts(out):
    with open(os.path.join(out, "summary.json")) as f:
        return {k: v for k, v in json.load(f).items() if k not in TIMINGS}


class RestartTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="pfem_restart_")
        with open(MODEL) as f:
            model = json.load(f)
        model["mesh"]["h"] = 0.01
        model["analysis"]["t_end"] = 0.5
        cls.model = os.path.join(cls.tmp, "model.json")
        with open(cls.model, "w") as f:
            json.dump(model, f)
        run_options = ["--sensitivity", "ddm", "--params", "rho_f,mu", "--vtk-every", "25"]
        cls.ref = os.path.join(cls.tmp, "ref")
        subprocess.run([PFEM, "run", cls.model, "--out", cls.ref] + run_options, check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

        # Stopped by SIGTERM about a second in, then continued.
        cls.out = os.path.join(cls.tmp, "out")
        proc = subprocess.Popen([PFEM, "run", cls.model, "--out", cls.out, "--progress",
                                 "--checkpoint-every", "40"] + run_options,
                                stderr=subprocess.PIPE, text=True)
        lines = []
        for line in proc.stderr:  # --progress on a pipe: one line a second
            lines.append(line)
            if sum(x.startswith("step ") for x in lines) == 2:
                break
        proc.send_signal(signal.SIGTERM)
        cls.stopped_stderr = "".join(lines) + proc.stderr.read()
        proc.stderr.close()
        cls.stopped_code = proc.wait(timeout=60)
        cls.stopped = counts(cls.out)
        cls.restart = subprocess.run([PFEM, "run", "--restart", cls.out, "--progress"],
                                     capture_output=True, text=True)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_stopped_mid_run_with_a_checkpoint(self):
        self.assertEqual(self.stopped_code, 1, self.stopped_stderr)
        self.assertEqual(self.stopped["status"], "cancelled")
        self.assertGreater(self.stopped["steps"], 1)
        self.assertLess(self.stopped["steps"], 500)
        self.assertIn(f"continue with: pfem run --restart {self.out}\n", self.stopped_stderr)

    def test_the_restart_continues_where_it_stopped(self):
        self.assertEqual(self.restart.returncode, 0, self.restart.stderr)
        first = self.restart.stderr.splitlines()[0]
        self.assertTrue(first.startswith(f"step {self.stopped['steps'] + 1}/500 "), first)

    def test_every_output_byte_for_byte(self):
        self.assertEqual(self.restart.returncode, 0, self.restart.stderr)
        for name in ["responses.csv", "sensitivities.csv"]:
            self.assertEqual(read(os.path.join(self.out, name)), read(os.path.join(self.ref, name)), name)
        self.assertEqual(counts(self.out), counts(self.ref))
        vtk, ref_vtk = os.path.join(self.out, "vtk"), os.path.join(self.ref, "vtk")
        names = sorted(os.listdir(ref_vtk))
        self.assertEqual(sorted(os.listdir(vtk)), names)
        self.assertIn("pfem_000020.vtu", names)  # t = 0 and every 25th of 500 steps
        match, mismatch, errors = filecmp.cmpfiles(vtk, ref_vtk, names, shallow=False)
        self.assertEqual((mismatch, errors), ([], []))

    def test_a_restart_that_would_change_the_run_is_refused(self):
        r = subprocess.run([PFEM, "run", "--restart", self.out, "--out", os.path.join(self.tmp, "x"),
                            "--dt", "0.002"], capture_output=True, text=True)
        self.assertEqual(r.returncode, 2)
        self.assertIn("--dt: a restart continues with the checkpointed run's options", r.stderr)
        with open(self.model) as f:
            model = json.load(f)
        model["fluid"]["mu"] = 0.002
        other = os.path.join(self.tmp, "other.json")
        with open(other, "w") as f:
            json.dump(model, f)
        r = subprocess.run([PFEM, "run", other, "--restart", self.out, "--out", os.path.join(self.tmp, "x")],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 2)
        self.assertEqual(r.stderr, "pfem: restart: the model is not the checkpointed run's "
                                   "(modified: fluid.mu: 0.001 -> 0.002)\n")


if __name__ == "__main__":
    unittest.main()
