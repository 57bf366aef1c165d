#!/usr/bin/python3
"""UM-Bridge 1.0 protocol conformance of pfem-server, from a second client: Python's standard
library (urllib, json) against the real binary on 127.0.0.1. Each check is one rule of the
protocol's specification: the keys and types of every answer, the sizes that tie them
together, and the error answers (type, HTTP 400) for an unknown model, wrong input sizes,
wrong outWrt / inWrt and an unsupported call. (The reference `umbridge` package and its
conformance suite are on PyPI, which this project cannot reach; these checks follow the same
rules.)

Run by ctest (umbridge_protocol_test) with PFEM_SERVER=build/bin/pfem-server and
PFEM_SOURCE_DIR."""
import json
import os
import shutil
import subprocess
import tempfile
import threading
import unittest
import urllib.error
import urllib.request

TOKEN = "umbridge-protocol-token"
INPUT = [1000.0, 2.15e9]  # rho_f, kappa of the tiny model


def tiny_model():
    """The tiny still-water model of the C++ service tests (tests/integration/service_test_support.h)."""
    with open(os.path.join(os.environ["PFEM_SOURCE_DIR"], "tests/integration/service_test_support.h")) as f:
        text = f.read()
    start = text.index('kTinyModelJson = R"(') + len('kTinyModelJson = R"(')
    return text[start:text.index(')";', start)]


class ProtocolTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="pfem_umbridge_protocol_")
        model_file = os.path.join(cls.tmp, "tiny.json")
        with open(model_file, "w") as f:
            f.write(tiny_model())
        token_file = os.path.join(cls.tmp, "tokens")
        with open(token_file, "w") as f:
            f.write(TOKEN + "\n")
        cls.server = subprocess.Popen(
            [os.environ["PFEM_SERVER"], "--listen", "127.0.0.1:0", "--data-dir",
             os.path.join(cls.tmp, "data"), "--workers", "2", "--token-file", token_file,
             "--umbridge-listen", "127.0.0.1:0", "--umbridge-model", "tiny=" + model_file],
            stdout=subprocess.PIPE, text=True)
        timer = threading.Timer(30, cls.server.kill)  # bounded wait for the first line
        timer.start()
        line = cls.server.stdout.readline()
        timer.cancel()
        if "UM-Bridge on http://" not in line:
            raise RuntimeError(f"pfem-server did not start its UM-Bridge endpoint: {line!r}")
        cls.url = line.split()[-1]

    @classmethod
    def tearDownClass(cls):
        cls.server.terminate()
        cls.server.wait(timeout=60)
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def call(self, path, body=None):
        """(HTTP status, decoded JSON answer) of GET path (body None) or POST path body."""
        data = None if body is None else json.dumps(body).encode()
        request = urllib.request.Request(self.url + path, data=data,
                                         headers={"Authorization": "Bearer " + TOKEN})
        try:
            with urllib.request.urlopen(request, timeout=120) as reply:
                return reply.status, json.load(reply)
        except urllib.error.HTTPError as e:
            return e.code, json.load(e)

    def ok(self, path, body=None):
        status, answer = self.call(path, body)
        self.assertEqual(status, 200, answer)
        return answer

    def assert_error(self, path, body, error_type):
        status, answer = self.call(path, body)
        self.assertEqual(status, 400, answer)
        self.assertEqual(set(answer), {"error"})
        self.assertEqual(set(answer["error"]), {"type", "message"})
        self.assertEqual(answer["error"]["type"], error_type)
        self.assertIsInstance(answer["error"]["message"], str)

    def assert_numbers(self, values, size):
        self.assertIsInstance(values, list)
        self.assertEqual(len(values), size)
        for v in values:
            self.assertIsInstance(v, (int, float))
            self.assertNotIsInstance(v, bool)

    def name(self):
        return self.ok("/Info")["models"][0]

    def sizes(self):
        body = {"name": self.name()}
        return self.ok("/InputSizes", body)["inputSizes"], self.ok("/OutputSizes", body)["outputSizes"]

    def test_info(self):
        info = self.ok("/Info")
        self.assertEqual(set(info), {"protocolVersion", "models"})
        self.assertEqual(info["protocolVersion"], 1.0)
        self.assertTrue(all(isinstance(m, str) for m in info["models"]))
        self.assertEqual(info["models"], ["tiny"])

    def test_model_info(self):
        info = self.ok("/ModelInfo", {"name": self.name()})
        self.assertEqual(set(info), {"support"})
        self.assertEqual(info["support"], {"Evaluate": True, "Gradient": True,
                                           "ApplyJacobian": True, "ApplyHessian": False})

    def test_sizes(self):
        for path, key in (("/InputSizes", "inputSizes"), ("/OutputSizes", "outputSizes")):
            answer = self.ok(path, {"name": self.name()})
            self.assertEqual(set(answer), {key})
            self.assertGreaterEqual(len(answer[key]), 1)
            self.assertTrue(all(isinstance(n, int) for n in answer[key]))
        self.assertEqual(self.sizes(), ([2], [3]))

    def test_evaluate(self):
        inputs, outputs = self.sizes()
        answer = self.ok("/Evaluate", {"name": self.name(), "input": [INPUT], "config": {}})
        self.assertEqual(set(answer), {"output"})
        self.assertEqual(len(answer["output"]), len(outputs))
        for vector, size in zip(answer["output"], outputs):
            self.assert_numbers(vector, size)

    def test_gradient(self):
        inputs, outputs = self.sizes()
        answer = self.ok("/Gradient", {"name": self.name(), "input": [INPUT], "config": {},
                                       "outWrt": 0, "inWrt": 0, "sens": [0.0] * outputs[0]})
        self.assertEqual(set(answer), {"output"})
        self.assert_numbers(answer["output"], inputs[0])

    def test_apply_jacobian(self):
        inputs, outputs = self.sizes()
        answer = self.ok("/ApplyJacobian", {"name": self.name(), "input": [INPUT], "config": {},
                                            "outWrt": 0, "inWrt": 0, "vec": [1.0] * inputs[0]})
        self.assertEqual(set(answer), {"output"})
        self.assert_numbers(answer["output"], outputs[0])

    def test_apply_hessian_is_unsupported(self):
        self.assert_error("/ApplyHessian", {"name": self.name()}, "UnsupportedFeature")

    def test_unknown_model(self):
        for path in ("/Evaluate", "/ModelInfo", "/InputSizes", "/Gradient"):
            self.assert_error(path, {"name": "wrong_model_name"}, "ModelNotFound")

    def test_wrong_input_sizes(self):
        inputs, outputs = self.sizes()
        longer = [INPUT + [1.0]]
        name = self.name()
        self.assert_error("/Evaluate", {"name": name, "input": longer, "config": {}}, "InvalidInput")
        self.assert_error("/Gradient", {"name": name, "input": longer, "config": {}, "outWrt": 0,
                                        "inWrt": 0, "sens": [0.0] * outputs[0]}, "InvalidInput")
        self.assert_error("/ApplyJacobian", {"name": name, "input": longer, "config": {}, "outWrt": 0,
                                             "inWrt": 0, "vec": [1.0] * inputs[0]}, "InvalidInput")

    def test_wrong_out_and_in_wrt(self):
        inputs, outputs = self.sizes()
        base = {"name": self.name(), "input": [INPUT], "config": {}, "sens": [0.0] * outputs[0]}
        self.assert_error("/Gradient", {**base, "outWrt": len(outputs), "inWrt": 0}, "InvalidInput")
        self.assert_error("/Gradient", {**base, "outWrt": 0, "inWrt": len(inputs)}, "InvalidInput")


if __name__ == "__main__":
    unittest.main()
