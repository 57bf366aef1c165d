#!/usr/bin/python3
"""Soak: 32 clients mixing Evaluate, SubmitJob, WatchJob, CancelJob and GetResult against the
pfem-server binary (127.0.0.1, 2 workers) for PFEM_SOAK_SECONDS (600), with two kill -9
restarts on the same port and data dir. It ends with every completed result intact (identical
jobs give the identical result, re-run or not), no job lost or duplicated, every acknowledged
cancel ending CANCELLED, the idle RSS within 20 % of the idle RSS after the warm-up, and no
error but the expected ones (UNAVAILABLE while the server is down or restarting;
FAILED_PRECONDITION for a cancel that came after the job's end).

Run by ctest (service_soak_test, label slow) with PYTHONPATH=build/python:clients/python,
PFEM_SERVER=build/bin/pfem-server and PFEM_SOURCE_DIR."""
import collections
import hashlib
import json
import os
import random
import shutil
import signal
import socket
import subprocess
import tempfile
import threading
import time
import unittest

import grpc

from pfem_client import Client, ServiceError

SECONDS = float(os.environ.get("PFEM_SOAK_SECONDS", "600"))
CLIENTS = 32
WARM_UP = min(60.0, SECONDS / 10)

# The Python client test's still water in a small box (5 x 4 particles, steps of 2 ms).
with open(os.path.join(os.environ["PFEM_SOURCE_DIR"], "tests", "data", "tiny.json"),
          encoding="utf-8") as f:
    TINY = json.load(f)
# The jobs, by model name: (t_end, sensitivity). "long" (1 000 steps) is the one cancelled.
JOBS = {"soak-short": (0.02, "none"), "soak-ddm": (0.04, "ddm"), "soak-long": (2.0, "none")}
RHO_VALUES = [980.0, 990.0, 1000.0, 1010.0, 1020.0]
EXPECTED = {grpc.StatusCode.UNAVAILABLE, grpc.StatusCode.FAILED_PRECONDITION}


def model(name):
    return dict(TINY, name=name)


def fingerprint(result):
    h = hashlib.sha256()
    for arrays in (result.responses, result.sensitivities):
        for name in sorted(arrays):
            h.update(name.encode())
            h.update(arrays[name].tobytes())
    h.update(result.time.tobytes())
    return h.hexdigest()


def rss_mb(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    raise RuntimeError(f"no VmRSS for {pid}")


class Server:
    """pfem-server on a fixed port of 127.0.0.1, restartable on the same port and data dir."""

    def __init__(self, data_dir):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            self.port = s.getsockname()[1]
        self.data_dir = data_dir
        self.address = f"127.0.0.1:{self.port}"
        self.process = None
        self.start()

    def start(self):
        self.process = subprocess.Popen(
            [os.environ["PFEM_SERVER"], "--listen", self.address, "--data-dir", self.data_dir,
             "--workers", "2"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        timer = threading.Timer(30, self.process.kill)
        timer.start()
        line = self.process.stdout.readline()
        timer.cancel()
        if "listening on" not in line:
            raise RuntimeError(f"pfem-server did not start: {line!r}")

    def kill9(self):
        self.process.send_signal(signal.SIGKILL)
        self.process.wait()
        self.process.stdout.close()

    def stop(self):
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            self.process.wait(timeout=60)
        self.process.stdout.close()


class Ledger:
    """What the clients saw, under one lock."""

    def __init__(self):
        self.lock = threading.Lock()
        self.ops = collections.Counter()
        self.expected = collections.Counter()
        self.errors = []
        self.acknowledged = {}         # job id SubmitJob answered -> when (time.monotonic())
        self.unacknowledged = 0        # submits that failed UNAVAILABLE (the job may exist)
        self.cancelled = set()         # job ids whose cancel was acknowledged
        self.references = {}           # model name -> result fingerprint
        self.evaluations = {}          # rho -> (values, gradients)
        self.results_checked = 0

    def error(self, what):
        with self.lock:
            self.errors.append(what)

    def check_result(self, name, fp, job_id):
        with self.lock:
            self.results_checked += 1
            reference = self.references.setdefault(name, fp)
        if fp != reference:
            self.error(f"job {job_id} ({name}): result differs from the first {name} result")


def client_loop(index, server, ledger, stop):
    rng = random.Random(index)
    client = Client(server.address, max_attempts=1)
    while not stop.is_set():
        op = rng.choices(["evaluate", "job", "cancel", "fire"], weights=[35, 35, 15, 15])[0]
        try:
            if op == "evaluate":
                rho = rng.choice(RHO_VALUES)
                e = client.evaluate(model("soak-evaluate"), ["bottom_p:max", "fluid_area:final"],
                                    param_values={"rho_f": rho}, t_end=0.02, timeout=60)
                got = (e.values.tobytes(), e.gradients.tobytes())
                with ledger.lock:
                    reference = ledger.evaluations.setdefault(rho, got)
                if got != reference:
                    ledger.error(f"Evaluate at rho_f = {rho}: values differ from the first")
            else:
                name = "soak-long" if op == "cancel" else rng.choice(["soak-short", "soak-ddm"])
                t_end, method = JOBS[name]
                try:
                    job_id = client.submit(model(name), t_end=t_end, sensitivity=method)
                except ServiceError as e:
                    if e.code == grpc.StatusCode.UNAVAILABLE:
                        with ledger.lock:
                            ledger.unacknowledged += 1
                    raise
                with ledger.lock:
                    ledger.acknowledged[job_id] = time.monotonic()
                if op == "cancel":
                    time.sleep(rng.uniform(0.0, 0.3))
                    client.cancel(job_id)
                    with ledger.lock:
                        ledger.cancelled.add(job_id)
                elif op == "job":
                    job = client.watch(job_id, timeout=120)
                    if job is None or job.state != "SUCCEEDED":
                        # A watch cut by a kill ends UNAVAILABLE, not here.
                        ledger.error(f"job {job_id}: watch ended {job and job.state}")
                    else:
                        ledger.check_result(name, fingerprint(client.result(job_id)), job_id)
            with ledger.lock:
                ledger.ops[op] += 1
        except ServiceError as e:
            with ledger.lock:
                if e.code in EXPECTED:
                    ledger.expected[e.code.name] += 1
                else:
                    ledger.errors.append(f"{op}: {e}")
            if e.code == grpc.StatusCode.UNAVAILABLE:
                time.sleep(0.2)
    client.close()


class SoakTest(unittest.TestCase):
    def test_soak(self):
        tmp = tempfile.mkdtemp(prefix="pfem_soak_")
        self.addCleanup(shutil.rmtree, tmp, ignore_errors=True)
        server = Server(os.path.join(tmp, "data"))
        self.addCleanup(server.stop)
        ledger = Ledger()
        stop = threading.Event()
        started = time.monotonic()

        def run_clients():
            stop.clear()
            threads = [threading.Thread(target=client_loop, args=(i, server, ledger, stop))
                       for i in range(CLIENTS)]
            for t in threads:
                t.start()
            return threads

        def halt(threads):
            stop.set()
            for t in threads:
                t.join(timeout=180)
                self.assertFalse(t.is_alive(), "a client did not stop")

        def wait_idle():
            with Client(server.address) as c:
                deadline = time.monotonic() + 300
                while time.monotonic() < deadline:
                    busy = c.list_jobs("QUEUED", 1) + c.list_jobs("RUNNING", 1)
                    if not busy:
                        return
                    time.sleep(0.5)
            self.fail("jobs still queued or running 300 s after the load stopped")

        # Warm-up, then the idle memory it leaves.
        threads = run_clients()
        time.sleep(WARM_UP)
        halt(threads)
        wait_idle()
        time.sleep(2)
        start_rss = rss_mb(server.process.pid)

        threads = run_clients()
        kills = [started + SECONDS / 3, started + 2 * SECONDS / 3]
        restart_seconds = []
        for at in kills:
            time.sleep(max(0.0, at - time.monotonic()))
            server.kill9()
            t0 = time.monotonic()
            server.start()
            restart_seconds.append(time.monotonic() - t0)
        time.sleep(max(0.0, started + SECONDS - time.monotonic()))
        halt(threads)
        wait_idle()
        time.sleep(2)
        end_rss = rss_mb(server.process.pid)

        # Every job once, each acknowledged one there, results intact, cancels durable.
        with Client(server.address) as c:
            jobs = c.list_jobs(limit=1_000_000)
            ids = [j.id for j in jobs]
            states = collections.Counter(j.state for j in jobs)
            for j in jobs:
                if j.state == "SUCCEEDED" and j.model_name in JOBS:
                    ledger.check_result(j.model_name, fingerprint(c.result(j.id)), j.id)
        by_id = {j.id: j for j in jobs}
        duplicates = len(ids) - len(set(ids))
        lost = set(ledger.acknowledged) - set(ids)
        extra = set(ids) - set(ledger.acknowledged)
        not_cancelled = [i for i in ledger.cancelled if by_id.get(i) and by_id[i].state != "CANCELLED"]
        failed = [i for i in ids if by_id[i].state == "FAILED"]
        reruns = sum(1 for j in jobs if j.attempts > 1)

        print(f"soak: {SECONDS:.0f} s, {CLIENTS} clients, 2 kill -9 restarts "
              f"({', '.join(f'{s:.2f}' for s in restart_seconds)} s to listen again)")
        print(f"calls completed: {dict(ledger.ops)}; expected errors: {dict(ledger.expected)}")
        print(f"jobs: {len(ids)} ({dict(states)}), {reruns} run again after a kill, "
              f"{len(ledger.cancelled)} cancels acknowledged, {len(extra)} stored of "
              f"{ledger.unacknowledged} unacknowledged submits")
        print(f"results checked against their first: {ledger.results_checked}; "
              f"Evaluate points: {len(ledger.evaluations)}")
        print(f"idle RSS after the warm-up {start_rss:.1f} MB, at the end {end_rss:.1f} MB "
              f"({100 * (end_rss / start_rss - 1):+.1f} %)")
        print(f"unexpected errors: {len(ledger.errors)}")
        for e in ledger.errors[:20]:
            print("  " + e)
        with Client(server.address) as c:
            for i in sorted(lost)[:20]:
                try:
                    answer = c.get_job(i).state
                except ServiceError as e:
                    answer = e.code.name
                print(f"  lost {i}: acknowledged {ledger.acknowledged[i] - started:.2f} s in "
                      f"(kills at {', '.join(f'{k - started:.2f}' for k in kills)} s), "
                      f"GetJob: {answer}")

        self.assertEqual(ledger.errors, [])
        self.assertEqual(duplicates, 0)
        self.assertEqual(lost, set())
        self.assertLessEqual(len(extra), ledger.unacknowledged)
        self.assertEqual(not_cancelled, [])
        self.assertEqual(failed, [])
        self.assertEqual(states["QUEUED"] + states["RUNNING"], 0)
        self.assertGreater(ledger.ops["job"], 100)
        self.assertGreater(ledger.ops["evaluate"], 100)
        self.assertLess(end_rss, 1.2 * start_rss)


if __name__ == "__main__":
    unittest.main()
