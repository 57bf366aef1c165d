#!/usr/bin/python3
"""`pfem run` stopped by SIGINT and by SIGTERM: it ends the step in progress, writes every output
with status "cancelled", and the histories it wrote are those of an uninterrupted run to the
same step, bit for bit. Also the --progress line on a pipe.

Run by ctest (pfem_run_signals_test) with PFEM_CLI=build/bin/pfem, PFEM_SOURCE_DIR=the source."""
import csv
import json
import os
import pty
import shutil
import signal
import subprocess
import tempfile
import unittest

PFEM = os.environ["PFEM_CLI"]
MODEL = os.path.join(os.environ["PFEM_SOURCE_DIR"], "examples", "dam-break.json")
DT = 0.001  # the example's analysis.dt


def rows(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


class RunSignalsTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="pfem_signals_")
        self.addCleanup(shutil.rmtree, self.tmp, ignore_errors=True)
        with open(MODEL) as f:
            model = json.load(f)
        model["mesh"]["h"] = 0.01
        model["analysis"]["t_end"] = 5.0  # far more than the test waits for
        self.model = os.path.join(self.tmp, "model.json")
        with open(self.model, "w") as f:
            json.dump(model, f)

    def interrupted(self, sig, sensitivity):
        out = os.path.join(self.tmp, f"{sig.name}-{sensitivity}")
        proc = subprocess.Popen([PFEM, "run", self.model, "--out", out, "--progress",
                                 "--sensitivity", sensitivity], stderr=subprocess.PIPE, text=True)
        lines = []
        for line in proc.stderr:  # --progress on a pipe: one line a second
            lines.append(line)
            if sum(x.startswith("step ") for x in lines) == 2:  # a second into the run
                break
        proc.send_signal(sig)
        rest = proc.stderr.read()
        proc.stderr.close()
        self.assertEqual(proc.wait(timeout=60), 1, rest)
        self.assertRegex(lines[-1], r"^step \d+/5000  t = [0-9.]+ s  newton \d+  [0-9.]+ s elapsed, "
                                    r"[0-9.]+ s left$")
        self.assertIn("cancelled", rest)
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        self.assertEqual(summary["status"], "cancelled")
        steps = summary["steps"]
        self.assertGreater(steps, 1)
        self.assertLess(steps, 5000)
        responses = rows(os.path.join(out, "responses.csv"))
        self.assertEqual(len(responses), steps + 2)  # header, t = 0 and one row per step
        self.assertAlmostEqual(float(responses[-1][0]), steps * DT, places=12)

        # The same run to the step it reached, uninterrupted: the same histories, bit for bit.
        ref = os.path.join(self.tmp, f"ref-{sig.name}-{sensitivity}")
        subprocess.run([PFEM, "run", self.model, "--out", ref, "--t-end", repr(steps * DT),
                        "--sensitivity", sensitivity], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        self.assertEqual(responses, rows(os.path.join(ref, "responses.csv")))
        if sensitivity != "none":
            self.assertEqual(rows(os.path.join(out, "sensitivities.csv")),
                             rows(os.path.join(ref, "sensitivities.csv")))

    def test_progress_on_a_terminal_without_the_flag(self):
        """stderr a terminal (a pseudo-terminal here): the line is rewritten in place (\\r)."""
        master, slave = pty.openpty()
        out = os.path.join(self.tmp, "tty")
        proc = subprocess.Popen([PFEM, "run", self.model, "--out", out, "--t-end", "0.02"],
                                stdout=subprocess.DEVNULL, stderr=slave)
        os.close(slave)
        seen = b""
        while True:
            try:
                chunk = os.read(master, 4096)
            except OSError:  # the child closed the terminal
                break
            if not chunk:
                break
            seen += chunk
        os.close(master)
        self.assertEqual(proc.wait(timeout=60), 0)
        text = seen.decode()
        self.assertIn("\rstep 1/20  t = 0.0010 s  newton ", text)
        self.assertIn("\rstep 20/20  t = 0.0200 s  newton ", text)

    def test_sigint(self):
        self.interrupted(signal.SIGINT, "none")

    def test_sigterm_with_ddm(self):
        self.interrupted(signal.SIGTERM, "ddm")


if __name__ == "__main__":
    unittest.main()
