#!/usr/bin/python3
"""pfem_client against a real pfem-server started here on 127.0.0.1 with an ephemeral port.

Run by ctest (python_client_test) with PYTHONPATH=build/python:clients/python and
PFEM_SERVER=build/bin/pfem-server."""
import importlib.util
import io
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import unittest
from contextlib import redirect_stdout

import grpc
import numpy as np

from pfem_client import Client, ServiceError, plot_histories

# Still water in a small closed box: 5 x 4 particles, 5 steps of 2 ms.
with open(os.path.join(os.environ["PFEM_SOURCE_DIR"], "tests", "data", "tiny.json"),
          encoding="utf-8") as f:
    TINY = json.load(f)
TOKEN = "python-test-token"
# The sloshing example is run to this time: the collapsing column reaches the beam by then.
SLOSHING_T_END = 0.15


class ClientTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="pfem_python_test_")
        cls.token_file = os.path.join(cls.tmp, "tokens")
        with open(cls.token_file, "w") as f:
            f.write(TOKEN + "\n")
        cls.server = subprocess.Popen(
            [os.environ["PFEM_SERVER"], "--listen", "127.0.0.1:0", "--data-dir",
             os.path.join(cls.tmp, "data"), "--workers", "2", "--token-file", cls.token_file],
            stdout=subprocess.PIPE, text=True)
        timer = threading.Timer(30, cls.server.kill)  # bounded wait for the first line
        timer.start()
        line = cls.server.stdout.readline()
        timer.cancel()
        if "listening on" not in line:
            raise RuntimeError(f"pfem-server did not start: {line!r}")
        cls.address = line.split()[-1]
        cls.client = Client(cls.address, token=TOKEN)

    @classmethod
    def tearDownClass(cls):
        cls.client.close()
        cls.server.send_signal(signal.SIGTERM)
        try:
            cls.server.wait(timeout=30)
        except subprocess.TimeoutExpired:
            cls.server.kill()
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_missing_or_wrong_token_is_unauthenticated(self):
        for token in (None, "wrong"):
            with Client(self.address, token=token) as c:
                with self.assertRaises(ServiceError) as e:
                    c.validate(TINY)
                self.assertEqual(e.exception.code, grpc.StatusCode.UNAUTHENTICATED)

    def test_invalid_model_names_the_field(self):
        bad = dict(TINY, fluid={"rho": -1.0, "mu": 0.001, "kappa": 2.15e9})
        answer = self.client.validate(bad)
        self.assertFalse(answer.valid)
        self.assertEqual(answer.errors[0].path, "fluid.rho")
        with self.assertRaises(ServiceError) as e:
            self.client.submit(bad)
        self.assertEqual(e.exception.code, grpc.StatusCode.INVALID_ARGUMENT)
        self.assertIn("fluid.rho: must be > 0", e.exception.details)
        self.assertEqual(self.client.validate(TINY).estimated_particles, 20)

    def test_submit_watch_result_evaluate_and_plot(self):
        job_id = self.client.submit(TINY, sensitivity="fdm", param_values={"rho_f": 1005.0})
        updates = []
        job = self.client.watch(job_id, callback=updates.append)
        self.assertGreaterEqual(len(updates), 1)
        self.assertEqual(job.state, "SUCCEEDED", job.error.message)
        self.assertEqual([j.id for j in self.client.list_jobs("succeeded")].count(job_id), 1)
        self.assertNotIn(job_id, [j.id for j in self.client.list_jobs("RUNNING")])
        with self.assertRaises(ValueError):
            self.client.list_jobs("DONE")
        self.assertEqual(job.progress.step, 5)

        result = self.client.result(job_id)
        self.assertEqual(result.time.shape, (6,))
        self.assertEqual(sorted(result.responses), ["bottom_p", "fluid_area", "front_x"])
        self.assertEqual(len(result.sensitivities), 6)
        self.assertEqual(result.parameters, ["rho_f", "kappa"])
        self.assertEqual(result.summary["parameters"]["rho_f"], 1005.0)
        self.assertEqual(result.status, "completed")
        self.assertEqual(result.summary["steps"], 5)
        p = result.responses["bottom_p"]
        self.assertTrue(np.all(np.isfinite(p)))

        # Evaluate on the same model and settings: the same numbers, bit for bit.
        ev = self.client.evaluate(TINY, ["bottom_p:max", "fluid_area:final", "bottom_p:at:0.004"],
                                  param_values={"rho_f": 1005.0}, sensitivity="fdm")
        i = int(np.argmax(p))
        self.assertEqual(ev.values[0], p[i])
        self.assertEqual(ev.times[0], result.time[i])
        self.assertEqual(ev.gradients[0, 0], result.sensitivity("bottom_p", "rho_f")[i])
        self.assertEqual(ev.gradients[0, 1], result.sensitivity("bottom_p", "kappa")[i])
        self.assertEqual(ev.values[1], result.responses["fluid_area"][-1])
        self.assertEqual(ev.values[2], p[2])  # t = 0.004 is the third sample
        self.assertEqual(ev.parameters, ["rho_f", "kappa"])
        self.assertEqual(ev.gradients.shape, (3, 2))
        self.assertFalse(ev.cached)
        again = self.client.evaluate(TINY, ["bottom_p:max"], param_values={"rho_f": 1005.0},
                                     sensitivity="fdm")
        self.assertTrue(again.cached)
        self.assertEqual(again["bottom_p:max"][0], ev.values[0])

        paths = plot_histories(result, os.path.join(self.tmp, "plots"))
        self.assertEqual([os.path.basename(x) for x in paths],
                         ["responses.png", "sensitivities.png"])
        for path in paths:
            with open(path, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")

    def test_fig34_script_on_the_sloshing_example_with_ddm(self):
        """The Fig. 3/4 script on a short run of the sloshing example: DDM through the service
        (FDM overlaid), the PNGs written, and the sensitivities the service returned equal to
        those of `pfem run` on the same model and options (same engine, one thread)."""
        here = os.path.dirname(os.path.abspath(__file__))
        spec = importlib.util.spec_from_file_location(
            "fig34", os.path.join(here, "..", "examples", "fig34_sensitivities.py"))
        fig34 = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(fig34)
        model = os.path.join(os.environ["PFEM_SOURCE_DIR"], "examples", "sloshing-beam.json")
        t_end = SLOSHING_T_END
        out = os.path.join(self.tmp, "fig34")
        printed = io.StringIO()
        with redirect_stdout(printed):
            rc = fig34.main([model, "--server", self.address, "--token-file", self.token_file,
                             "--t-end", str(t_end), "--params", "E,rho_f", "--fdm",
                             "--out", out])
        self.assertEqual(rc, 0)
        text = printed.getvalue()
        for name in ("fig3_responses.png", "fig4_sensitivities.png", "responses.png",
                     "sensitivities.png"):
            path = os.path.join(out, name)
            with open(path, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n", name)
            self.assertGreater(os.path.getsize(path), 1000, name)
            self.assertIn(path, text)
        ids = {line.split()[0]: line.split()[2] for line in text.splitlines()
               if line.split()[1:2] == ["job"]}
        self.assertEqual(sorted(ids), ["ddm", "fdm"], text)

        served = self.client.result(ids["ddm"])
        self.assertEqual(served.method, "ddm")
        self.assertEqual(served.parameters, ["E", "rho_f"])
        local = os.path.join(self.tmp, "sloshing-cli")
        subprocess.run([os.environ["PFEM_CLI"], "run", model, "--out", local, "--t-end",
                        str(t_end), "--sensitivity", "ddm", "--params", "E,rho_f"],
                       check=True, stdout=subprocess.DEVNULL)
        cli = fig34.read_result_dir(local)
        self.assertEqual(cli.method, "ddm")
        np.testing.assert_array_equal(served.time, cli.time)
        np.testing.assert_array_equal(served.sensitivity_time, cli.sensitivity_time)
        self.assertEqual(sorted(served.sensitivities), sorted(cli.sensitivities))
        for name, values in cli.sensitivities.items():
            peak = np.max(np.abs(values))
            self.assertGreater(peak, 0.0, name)  # the water has reached the beam
            # bit for bit: the same engine with one thread, and the CSV's %.17g round-trips
            np.testing.assert_array_equal(served.sensitivities[name], values, err_msg=name)
        for name, values in cli.responses.items():
            np.testing.assert_array_equal(served.responses[name], values, err_msg=name)
        # DDM and FDM (the overlay) agree closely.
        fdm = self.client.result(ids["fdm"])
        for name, values in served.sensitivities.items():
            peak = np.max(np.abs(values))
            np.testing.assert_allclose(fdm.sensitivities[name], values, rtol=0,
                                       atol=1e-3 * peak, err_msg=name)

        # The same figures from the result directory (no server).
        offline = os.path.join(self.tmp, "fig34-offline")
        with redirect_stdout(io.StringIO()):
            self.assertEqual(fig34.main(["--result-dir", local, "--out", offline]), 0)
        for name in ("fig3_responses.png", "fig4_sensitivities.png"):
            self.assertGreater(os.path.getsize(os.path.join(offline, name)), 1000, name)
    def test_evaluate_many_over_two_replicas_and_a_dead_one(self):
        """An ipv4: target of this server and a second one: evaluate_many spreads the points,
        gives the numbers one server gives, and survives the second replica's SIGKILL."""
        second = subprocess.Popen(
            [os.environ["PFEM_SERVER"], "--listen", "127.0.0.1:0", "--data-dir",
             os.path.join(self.tmp, "data2"), "--workers", "1", "--token-file", self.token_file],
            stdout=subprocess.PIPE, text=True)
        try:
            address = second.stdout.readline().split()[-1]
            points = [{"rho_f": 990.0 + 2.5 * k} for k in range(8)]
            functionals = ["bottom_p:max", "front_x:final"]
            one = [self.client.evaluate(TINY, functionals, param_values=p, no_cache=True)
                   for p in points]
            with Client(f"ipv4:{self.address},{address}", token=TOKEN) as both:
                many = both.evaluate_many(TINY, functionals, points, concurrency=2, no_cache=True)
                for a, b in zip(one, many):
                    np.testing.assert_array_equal(a.values, b.values)
                    np.testing.assert_array_equal(a.gradients, b.gradients)
                second.kill()
                second.wait()
                again = both.evaluate_many(TINY, functionals, points, concurrency=2, no_cache=True)
                for a, b in zip(one, again):
                    np.testing.assert_array_equal(a.values, b.values)
            with self.assertRaises(ValueError):
                self.client.evaluate_many(TINY, functionals, points, concurrency=0)
        finally:
            if second.poll() is None:
                second.kill()
                second.wait()
            second.stdout.close()


if __name__ == "__main__":
    unittest.main()
