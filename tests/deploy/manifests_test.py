#!/usr/bin/python3
"""The deploy/ files checked without a cluster or a container engine: every Kubernetes object's
kind, selectors that match the pod labels, probes on a port the container has and that the
server serves health on, one PersistentVolumeClaim per pod for the data dir, a grace period
longer than the server's drain; the Containerfile's runtime stage and the compose file.

Run by ctest (deploy_manifests_test) as /usr/bin/python3 tests/deploy/manifests_test.py."""
import os
import re
import shutil
import subprocess
import unittest

import yaml

ROOT = os.environ.get("PFEM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
K8S = os.path.join(ROOT, "deploy", "k8s")


def load(path):
    with open(path, encoding="utf-8") as f:
        return [d for d in yaml.safe_load_all(f) if d is not None]


def flag(args, name):
    """The value of --name=VALUE in a list of arguments (None when absent)."""
    for a in args:
        if a.startswith(f"--{name}="):
            return a.split("=", 1)[1]
    return None


def port_of(address):
    return int(address.rsplit(":", 1)[1])


class KustomizeBase(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        kustomization = load(os.path.join(K8S, "kustomization.yaml"))[0]
        cls.kustomization = kustomization
        cls.objects = []
        for resource in kustomization["resources"]:
            cls.objects += load(os.path.join(K8S, resource))
        cls.by_kind = {}
        for o in cls.objects:
            cls.by_kind.setdefault(o["kind"], []).append(o)
        cls.sts = cls.by_kind["StatefulSet"][0]
        cls.pod = cls.sts["spec"]["template"]
        cls.container = cls.pod["spec"]["containers"][0]
        cls.args = cls.container["args"]

    def test_kinds_and_api_versions(self):
        kinds = sorted((o["apiVersion"], o["kind"]) for o in self.objects)
        self.assertEqual(kinds, [("apps/v1", "StatefulSet"), ("policy/v1", "PodDisruptionBudget"),
                                 ("v1", "Secret"), ("v1", "Service")])
        for o in self.objects:
            self.assertTrue(o["metadata"]["name"], o["kind"])
        # every file of the folder is in the base
        files = sorted(f for f in os.listdir(K8S) if f.endswith(".yaml") and f != "kustomization.yaml")
        self.assertEqual(files, sorted(self.kustomization["resources"]))

    def test_selectors_match_the_pod_labels(self):
        labels = self.pod["metadata"]["labels"]
        selectors = {
            "StatefulSet": self.sts["spec"]["selector"]["matchLabels"],
            "Service": self.by_kind["Service"][0]["spec"]["selector"],
            "PodDisruptionBudget": self.by_kind["PodDisruptionBudget"][0]["spec"]["selector"]["matchLabels"],
        }
        for kind, selector in selectors.items():
            self.assertTrue(selector, kind)
            for k, v in selector.items():
                self.assertEqual(labels.get(k), v, f"{kind} selector {k}={v}")

    def test_headless_service_on_the_grpc_port(self):
        service = self.by_kind["Service"][0]
        self.assertEqual(self.sts["spec"]["serviceName"], service["metadata"]["name"])
        self.assertEqual(service["spec"]["clusterIP"], "None")  # headless: client-side balancing
        ports = {p["name"]: p["containerPort"] for p in self.container["ports"]}
        target = service["spec"]["ports"][0]["targetPort"]
        self.assertIn(target, ports)
        self.assertEqual(ports[target], port_of(flag(self.args, "listen")))

    def test_native_grpc_probes_on_the_health_port(self):
        container_ports = {p["containerPort"] for p in self.container["ports"]}
        health = port_of(flag(self.args, "health-listen"))
        self.assertNotEqual(health, port_of(flag(self.args, "listen")))
        with open(os.path.join(ROOT, "server", "server.h"), encoding="utf-8") as f:
            liveness = re.search(r'kLivenessService = "([^"]+)"', f.read()).group(1)
        for probe, service in (("readinessProbe", None), ("livenessProbe", liveness)):
            grpc = self.container[probe]["grpc"]
            self.assertIn(grpc["port"], container_ports, probe)
            self.assertEqual(grpc["port"], health, probe)
            self.assertEqual(grpc.get("service"), service, probe)

    def test_a_volume_claim_per_pod_for_the_data_dir(self):
        claims = {c["metadata"]["name"]: c for c in self.sts["spec"]["volumeClaimTemplates"]}
        volumes = {v["name"]: v for v in self.pod["spec"]["volumes"]}
        mounts = {m["mountPath"]: m["name"] for m in self.container["volumeMounts"]}
        for m in self.container["volumeMounts"]:
            self.assertTrue(m["name"] in claims or m["name"] in volumes, m["name"])
        data = mounts[flag(self.args, "data-dir")]
        self.assertIn(data, claims)  # not a pod volume shared through a network file system
        self.assertNotIn(data, volumes)
        self.assertEqual(claims[data]["spec"]["accessModes"], ["ReadWriteOnce"])

    def test_token_secret_mounted_where_the_server_reads_it(self):
        token_file = flag(self.args, "token-file")
        secret = self.by_kind["Secret"][0]
        mounts = {m["name"]: m["mountPath"] for m in self.container["volumeMounts"]}
        volumes = {v["name"]: v for v in self.pod["spec"]["volumes"]}
        name = next(n for n, v in volumes.items()
                    if v.get("secret", {}).get("secretName") == secret["metadata"]["name"])
        directory, key = os.path.split(token_file)
        self.assertEqual(mounts[name], directory)
        self.assertIn(key, secret["stringData"])

    def test_grace_period_covers_the_drain(self):
        grace = float(flag(self.args, "grace-seconds"))
        self.assertGreater(self.pod["spec"]["terminationGracePeriodSeconds"], grace)
        self.assertGreater(float(flag(self.args, "max-connection-age")), 0)

    def test_resources_and_a_non_root_user(self):
        resources = self.container["resources"]
        for part in ("requests", "limits"):
            self.assertIn("cpu", resources[part])
            self.assertIn("memory", resources[part])
        workers = int(flag(self.args, "workers"))
        self.assertLessEqual(workers, int(resources["limits"]["cpu"]))
        self.assertTrue(self.pod["spec"]["securityContext"]["runAsNonRoot"])
        self.assertNotEqual(self.pod["spec"]["securityContext"]["runAsUser"], 0)

    @unittest.skipUnless(shutil.which("kubectl"), "kubectl not installed: no kustomize rendering")
    def test_kustomize_renders_the_same_objects(self):
        out = subprocess.run(["kubectl", "kustomize", K8S], check=True, capture_output=True,
                             text=True).stdout
        rendered = [d for d in yaml.safe_load_all(out) if d]
        self.assertEqual(sorted(o["kind"] for o in rendered), sorted(o["kind"] for o in self.objects))
        for o in rendered:
            self.assertEqual(o["metadata"]["labels"]["app.kubernetes.io/part-of"], "pfem")


class ContainerAndCompose(unittest.TestCase):
    def test_containerfile_runtime_stage(self):
        with open(os.path.join(ROOT, "deploy", "container", "Containerfile"), encoding="utf-8") as f:
            text = f.read()
        stages = re.split(r"^FROM ", text, flags=re.M)[1:]
        self.assertEqual(len(stages), 2)  # build, runtime
        self.assertIn("scripts/install-deps", stages[0])
        self.assertIn("scripts/build", stages[0])
        runtime = stages[1]
        installed = re.findall(r"\b(lib[a-z0-9.+-]+)", runtime.split("rm -rf")[0])
        self.assertTrue(installed)
        self.assertFalse([p for p in installed if p.endswith("-dev")], "no -dev in the runtime")
        user = re.search(r"^USER (\S+)", runtime, flags=re.M).group(1)
        self.assertNotIn(user.split(":")[0], ("0", "root"))
        self.assertRegex(runtime, r'ENTRYPOINT \["/usr/local/bin/pfem-server"\]')
        volume = re.search(r"^VOLUME (\S+)", runtime, flags=re.M).group(1)
        cmd = re.search(r"^CMD (\[.*\])", runtime, flags=re.M).group(1)
        self.assertIn(f'"--data-dir", "{volume}"', cmd)

    def test_compose_replicas_share_a_token_not_a_store(self):
        compose = load(os.path.join(ROOT, "deploy", "compose.yaml"))[0]
        service = compose["services"]["pfem"]
        self.assertGreaterEqual(service["deploy"]["replicas"], 2)
        secret = service["secrets"][0]
        self.assertIn(secret, compose["secrets"])
        self.assertEqual(flag(service["command"], "token-file"), f"/run/secrets/{secret}")
        # each replica keeps the image's anonymous data volume: no named volume shared by all
        self.assertNotIn("volumes", service)
        grace = float(flag(service["command"], "grace-seconds"))
        self.assertGreater(float(service["stop_grace_period"].rstrip("s")), grace)


if __name__ == "__main__":
    unittest.main()
