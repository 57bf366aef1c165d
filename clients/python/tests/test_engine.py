#!/usr/bin/python3
"""The in-process `pfem` module (pybind11): the same numbers as `pfem run`, validation errors as
field paths, Ctrl-C (SIGINT to the Python process) stopping a run, and the README's tutorial.

Run by ctest (python_engine_test) with PYTHONPATH=build/python:clients/python,
PFEM_CLI=build/bin/pfem and PFEM_SOURCE_DIR=the source tree."""
import io
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import textwrap
import threading
import unittest
from contextlib import redirect_stdout

import numpy as np

import pfem
from pfem_client import read_result_dir

SOURCE = os.environ["PFEM_SOURCE_DIR"]
SLOSHING = os.path.join(SOURCE, "examples", "sloshing-beam.json")


class EngineModuleTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="pfem_engine_test_")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_run_is_bit_identical_to_pfem_run(self):
        """The sloshing example with DDM of E and rho_f, in-process and by the command."""
        t_end, params = 0.15, ["E", "rho_f"]  # the water reaches the beam by then
        result = pfem.run(SLOSHING, sensitivity="ddm", params=params, t_end=t_end)
        out = os.path.join(self.tmp, "sloshing")
        subprocess.run([os.environ["PFEM_CLI"], "run", SLOSHING, "--out", out, "--t-end",
                        str(t_end), "--sensitivity", "ddm", "--params", ",".join(params)],
                       check=True, stdout=subprocess.DEVNULL)
        cli = read_result_dir(out)
        self.assertEqual(result.status, "completed")
        self.assertEqual(result.parameters, params)
        np.testing.assert_array_equal(result.time, cli.time)
        self.assertEqual(sorted(result.responses), sorted(cli.responses))
        for name, values in cli.responses.items():
            np.testing.assert_array_equal(result.responses[name], values, err_msg=name)
        self.assertEqual(sorted(result.sensitivities), sorted(cli.sensitivities))
        for name, values in cli.sensitivities.items():
            np.testing.assert_array_equal(result.sensitivities[name], values, err_msg=name)
        self.assertGreater(np.max(np.abs(result.sensitivity("tip_ux", "E"))), 0.0)
        for key in ("steps", "newton_iterations", "particles", "max_elements", "fluid_area_final"):
            self.assertEqual(result.summary[key], cli.summary[key], key)

    def test_validation_lists_every_error_by_field_path(self):
        model = pfem.load_model(SLOSHING)
        self.assertEqual(pfem.validate(model), [])
        model.data["fluid"]["rho"] = -1.0
        model.data["fluid"]["mu"] = -0.5
        model.data["mesh"]["h"] = 0.0
        errors = dict(pfem.validate(model))
        self.assertEqual(errors["fluid.rho"], "must be > 0")
        self.assertIn("fluid.mu", errors)
        self.assertIn("mesh.h", errors)
        with self.assertRaises(pfem.ModelError) as e:
            pfem.run(model)
        self.assertIn(("fluid.rho", "must be > 0"), e.exception.errors)
        with self.assertRaises(pfem.ModelError) as e:
            pfem.run(SLOSHING, sensitivity="ddm", params=["nope"])
        self.assertEqual(e.exception.errors, [("params", "unknown parameter 'nope'")])

    def test_sigint_stops_the_run_with_the_steps_done(self):
        script = textwrap.dedent(f"""
            import json, os, signal, sys
            import pfem
            def progress(p):
                if p["step"] == 3:  # Ctrl-C from outside, as a terminal would send it
                    os.kill(os.getppid(), signal.SIGUSR1)
            try:
                pfem.run({SLOSHING!r}, t_end=5.0, progress=progress)
                print("completed")
            except pfem.RunInterrupted as e:
                print(json.dumps({{"steps": e.result.summary["steps"], "status": e.result.status,
                                  "rows": len(e.result.time)}}))
            """)
        child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
        signal.signal(signal.SIGUSR1, lambda *_: child.send_signal(signal.SIGINT))
        try:
            out, _ = child.communicate(timeout=120)
        finally:
            signal.signal(signal.SIGUSR1, signal.SIG_DFL)
        self.assertEqual(child.returncode, 0, out)
        answer = json.loads(out)
        self.assertEqual(answer["status"], "cancelled")
        self.assertGreaterEqual(answer["steps"], 3)
        self.assertLess(answer["steps"], 100)
        self.assertEqual(answer["rows"], answer["steps"] + 1)  # record_every 1: t = 0 and each step

    def test_two_runs_go_side_by_side(self):
        """The GIL is released while the engine runs: two threads' runs report their steps
        interleaved. Python's own thread switching is turned off here, so that only a released
        GIL lets the second run go while the first one computes (held, one run would end before
        the other started)."""
        hydrostatic = os.path.join(SOURCE, "examples", "hydrostatic.json")
        calls = []

        def go(tag):
            pfem.run(hydrostatic, t_end=0.25, progress=lambda p: calls.append(tag))

        interval = sys.getswitchinterval()
        sys.setswitchinterval(1000.0)
        try:
            threads = [threading.Thread(target=go, args=(tag,)) for tag in ("a", "b")]
            for t in threads:
                t.start()
            for t in threads:
                t.join()
        finally:
            sys.setswitchinterval(interval)
        self.assertEqual((calls.count("a"), calls.count("b")), (125, 125))
        switches = sum(x != y for x, y in zip(calls, calls[1:]))
        self.assertGreater(switches, 1, "one run ended before the other started")

    def test_checkpoint_continued_in_process_and_by_pfem_run(self):
        """A checkpoint written by pfem.run after step 30 of 50 is continued by pfem.run and by
        `pfem run --restart` (one file format): both the same arrays as a run never stopped."""
        model = pfem.load_model(os.path.join(SOURCE, "examples", "dam-break.json"))
        model.data["mesh"]["h"] = 0.01
        options = dict(sensitivity="ddm", params=["mu"], t_end=0.05)
        whole = pfem.run(model, **options)
        checkpoint = os.path.join(self.tmp, "checkpoint.pfem")
        pfem.run(model, checkpoint_every=30, checkpoint_file=checkpoint, **options)
        steps = []
        restarted = pfem.run(model, restart_from=checkpoint, progress=lambda p: steps.append(p["step"]),
                             **options)
        self.assertEqual(steps[0], 31)
        out = os.path.join(self.tmp, "restarted-by-cli")
        subprocess.run([os.environ["PFEM_CLI"], "run", "--restart", checkpoint, "--out", out], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        for other in (restarted, read_result_dir(out)):
            for name, values in whole.responses.items():
                np.testing.assert_array_equal(other.responses[name], values, err_msg=name)
            for name, values in whole.sensitivities.items():
                np.testing.assert_array_equal(other.sensitivities[name], values, err_msg=name)
        with self.assertRaisesRegex(pfem.CheckpointError, "restart: sensitivity is none here but ddm"):
            pfem.run(model, restart_from=checkpoint, t_end=0.05)

    def test_progress_callback_exception_stops_the_run(self):
        def stop(p):
            raise RuntimeError(f"stop at {p['step']}")
        with self.assertRaisesRegex(RuntimeError, "stop at 1"):
            pfem.run(SLOSHING, t_end=1.0, progress=stop)

    def test_readme_tutorial_runs(self):
        with open(os.path.join(SOURCE, "README.md"), encoding="utf-8") as f:
            readme = f.read()
        match = re.search(r"<!-- tutorial -->\s*```python\n(.*?)```", readme, re.S)
        self.assertIsNotNone(match, "the README has no tutorial block")
        cwd = os.getcwd()
        os.chdir(self.tmp)
        try:
            printed = io.StringIO()
            with redirect_stdout(printed):
                exec(compile(match.group(1), "README tutorial", "exec"), {})
        finally:
            os.chdir(cwd)
        self.assertIn("DDM and FDM agree: True", printed.getvalue())
        self.assertGreater(os.path.getsize(os.path.join(self.tmp, "tutorial", "sensitivities.png")), 1000)


if __name__ == "__main__":
    unittest.main()
