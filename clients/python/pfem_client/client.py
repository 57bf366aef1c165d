"""Client, Result and Evaluation: pfem.v1.GradientService with numpy results."""
from __future__ import annotations

import concurrent.futures
import json
import os
import time
from dataclasses import dataclass, field
from typing import Callable, Iterable, List, Mapping, Optional, Sequence, Union

import grpc
import numpy as np
from google.protobuf import json_format

from pfem.v1 import model_pb2, service_pb2, service_pb2_grpc

from .results import Result

ModelLike = Union[str, os.PathLike, Mapping, model_pb2.Model]

_METHODS = {
    None: service_pb2.SENSITIVITY_METHOD_UNSPECIFIED,
    "none": service_pb2.SENSITIVITY_METHOD_NONE,
    "ddm": service_pb2.SENSITIVITY_METHOD_DDM,
    "fdm": service_pb2.SENSITIVITY_METHOD_FDM,
}
_KINDS = {
    "at": service_pb2.Functional.KIND_VALUE_AT,
    "value_at": service_pb2.Functional.KIND_VALUE_AT,
    "max": service_pb2.Functional.KIND_MAX,
    "min": service_pb2.Functional.KIND_MIN,
    "max_abs": service_pb2.Functional.KIND_MAX_ABS,
    "absmax": service_pb2.Functional.KIND_MAX_ABS,
    "final": service_pb2.Functional.KIND_FINAL,
}


class ServiceError(RuntimeError):
    """A failed call: `code` is the grpc.StatusCode, `details` the server's message."""

    def __init__(self, code: grpc.StatusCode, details: str):
        super().__init__(f"{code.name}: {details}")
        self.code = code
        self.details = details


def load_model(model: ModelLike) -> model_pb2.Model:
    """A pfem.v1.Model from a message, a dict, a JSON string or a JSON file path.

    Unknown fields are errors, as for `pfem validate`."""
    if isinstance(model, model_pb2.Model):
        return model
    if isinstance(model, Mapping):
        return json_format.ParseDict(model, model_pb2.Model())
    text = str(model)
    if not text.lstrip().startswith("{"):
        with open(text, encoding="utf-8") as f:
            text = f.read()
    return json_format.Parse(text, model_pb2.Model())


@dataclass
class Evaluation:
    """Evaluate's answer: values[i] and gradients[i, k] = d values[i] / d parameters[k]."""

    names: List[str]
    values: np.ndarray
    times: np.ndarray
    gradients: np.ndarray
    parameters: List[str]
    parameter_values: np.ndarray
    cached: bool
    wall_seconds: float
    summary: service_pb2.Summary = field(repr=False)

    def __getitem__(self, name: str):
        """(value, gradient) of the functional called `name`."""
        i = self.names.index(name)
        return self.values[i], self.gradients[i]


_STATE_PREFIX = "JOB_STATE_"


class Job:
    """A job as the server reports it. `state` is a name: "QUEUED", "RUNNING", "SUCCEEDED",
    "FAILED" or "CANCELLED"; every other field is the pfem.v1.Job message's (`job.progress.step`,
    `job.error.message`, ...), and `message` is that message."""

    def __init__(self, message: service_pb2.Job):
        self.message = message

    @property
    def state(self) -> str:
        return service_pb2.JobState.Name(self.message.state)[len(_STATE_PREFIX):]

    @property
    def finished(self) -> bool:
        return self.message.state >= service_pb2.JOB_STATE_SUCCEEDED

    def __getattr__(self, name):
        return getattr(self.message, name)

    def __repr__(self):
        return f"Job(id={self.message.id!r}, state={self.state}, step={self.message.progress.step})"


def _state_number(state: Union[str, int, None]) -> int:
    """A JobState from its name ("RUNNING", case-insensitive) or number; None = every state."""
    if state is None or isinstance(state, int):
        return state or 0
    try:
        return service_pb2.JobState.Value(_STATE_PREFIX + state.upper())
    except ValueError:
        names = [n[len(_STATE_PREFIX):] for n in service_pb2.JobState.keys()][1:]
        raise ValueError(f"job state {state!r}: expected one of {', '.join(names)}") from None


def _functional(spec) -> service_pb2.Functional:
    """'recorder:kind[:time]', a (recorder, kind[, time]) tuple, a dict or a message."""
    if isinstance(spec, service_pb2.Functional):
        return spec
    if isinstance(spec, Mapping):
        return json_format.ParseDict(spec, service_pb2.Functional())
    parts = spec.split(":") if isinstance(spec, str) else [str(p) for p in spec]
    if len(parts) not in (2, 3) or parts[1] not in _KINDS:
        raise ValueError(f"functional {spec!r}: expected RECORDER:KIND[:TIME], KIND one of "
                         + ", ".join(sorted(_KINDS)))
    f = service_pb2.Functional(recorder=parts[0], kind=_KINDS[parts[1]],
                               name=spec if isinstance(spec, str) else ":".join(parts))
    if len(parts) == 3:
        f.time = float(parts[2])
    return f


def _param_values(values: Optional[Mapping[str, float]]):
    return [service_pb2.ParameterValue(name=k, value=float(v)) for k, v in (values or {}).items()]


class Client:
    """A connection to pfem-server. Every call raises ServiceError on a non-OK status.

    `address` is any gRPC target: HOST:PORT, dns:///NAME:PORT (every address of the name, e.g.
    a Kubernetes headless Service) or ipv4:A:P,B:P; calls are spread over the replicas by the
    round_robin policy. Evaluate, which gives the same answer on every replica, is retried up
    to `max_attempts` times in all when a replica is UNAVAILABLE (it died or is draining)."""

    def __init__(self, address: str, *, token: Optional[str] = None,
                 token_file: Optional[str] = None, tls_ca: Optional[str] = None,
                 max_message_mb: int = 256, max_attempts: int = 5):
        if token_file:
            with open(token_file, encoding="utf-8") as f:
                token = next(line.strip() for line in f
                             if line.strip() and not line.strip().startswith("#"))
        options = [("grpc.max_receive_message_length", max_message_mb * 1024 * 1024),
                   ("grpc.lb_policy_name", "round_robin")]
        self._max_attempts = max_attempts
        if tls_ca:
            with open(tls_ca, "rb") as f:
                credentials = grpc.ssl_channel_credentials(root_certificates=f.read())
            self._channel = grpc.secure_channel(address, credentials, options=options)
        else:
            self._channel = grpc.insecure_channel(address, options=options)
        self._metadata = (("authorization", f"Bearer {token}"),) if token else ()
        self._stub = service_pb2_grpc.GradientServiceStub(self._channel)

    def close(self):
        self._channel.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _call(self, method, request, timeout=None, attempts=1):
        wait = 0.1
        for attempt in range(1, attempts + 1):
            try:
                return method(request, metadata=self._metadata, timeout=timeout)
            except grpc.RpcError as e:
                if e.code() != grpc.StatusCode.UNAVAILABLE or attempt == attempts:
                    raise ServiceError(e.code(), e.details()) from None
            time.sleep(wait)
            wait = min(2 * wait, 2.0)

    def validate(self, model: ModelLike) -> service_pb2.ValidateModelResponse:
        return self._call(self._stub.ValidateModel,
                          service_pb2.ValidateModelRequest(model=load_model(model)))

    def submit(self, model: ModelLike, *, t_end: Optional[float] = None,
               dt: Optional[float] = None, sensitivity: Optional[str] = "none",
               params: Sequence[str] = (), fdm_eps: Optional[float] = None,
               param_values: Optional[Mapping[str, float]] = None,
               timeout_seconds: Optional[float] = None) -> str:
        """Queues a run; returns the job id."""
        options = service_pb2.RunOptions(sensitivity=_METHODS[sensitivity], params=list(params))
        if t_end is not None:
            options.t_end = t_end
        if dt is not None:
            options.dt = dt
        if fdm_eps is not None:
            options.fdm_eps = fdm_eps
        request = service_pb2.SubmitJobRequest(model=load_model(model), options=options,
                                               parameter_values=_param_values(param_values))
        if timeout_seconds is not None:
            request.timeout_seconds = timeout_seconds
        return self._call(self._stub.SubmitJob, request).job_id

    def get_job(self, job_id: str) -> Job:
        return Job(self._call(self._stub.GetJob, service_pb2.JobRequest(job_id=job_id)))

    def cancel(self, job_id: str) -> Job:
        return Job(self._call(self._stub.CancelJob, service_pb2.JobRequest(job_id=job_id)))

    def list_jobs(self, state: Union[str, int, None] = None, limit: int = 0) -> List[Job]:
        """Jobs in `state` (a name such as "RUNNING"; None: every state), newest first."""
        request = service_pb2.ListJobsRequest(state=_state_number(state), limit=limit)
        return [Job(j) for j in self._call(self._stub.ListJobs, request).jobs]

    def watch(self, job_id: str, callback: Optional[Callable[[Job], None]] = None,
              timeout: Optional[float] = None) -> Optional[Job]:
        """Follows the job to its end; returns the final Job (state SUCCEEDED, FAILED, ...)."""
        job = None
        try:
            for message in self._stub.WatchJob(service_pb2.JobRequest(job_id=job_id),
                                               metadata=self._metadata, timeout=timeout):
                job = Job(message)
                if callback:
                    callback(job)
        except grpc.RpcError as e:
            raise ServiceError(e.code(), e.details()) from None
        return job

    def result(self, job_id: str) -> Result:
        """A finished job's result, reassembled from the GetResult stream."""
        header = None
        columns = {service_pb2.HISTORIES_KIND_RESPONSES: [],
                   service_pb2.HISTORIES_KIND_SENSITIVITIES: []}
        times = {service_pb2.HISTORIES_KIND_RESPONSES: [],
                 service_pb2.HISTORIES_KIND_SENSITIVITIES: []}
        try:
            for message in self._stub.GetResult(service_pb2.JobRequest(job_id=job_id),
                                                metadata=self._metadata):
                if message.HasField("header"):
                    header = message.header
                    columns[service_pb2.HISTORIES_KIND_RESPONSES] = [
                        [] for _ in header.response_columns]
                    columns[service_pb2.HISTORIES_KIND_SENSITIVITIES] = [
                        [] for _ in header.sensitivity_columns]
                    continue
                chunk = message.chunk
                target = (times[chunk.kind] if chunk.column < 0
                          else columns[chunk.kind][chunk.column])
                if chunk.offset != sum(len(v) for v in target):
                    raise ServiceError(grpc.StatusCode.DATA_LOSS, "chunks out of order")
                target.append(np.asarray(chunk.values, dtype=np.float64))
        except grpc.RpcError as e:
            raise ServiceError(e.code(), e.details()) from None
        if header is None:
            raise ServiceError(grpc.StatusCode.DATA_LOSS, "no result header")

        def join(parts):
            return np.concatenate(parts) if parts else np.zeros(0)

        r, s = service_pb2.HISTORIES_KIND_RESPONSES, service_pb2.HISTORIES_KIND_SENSITIVITIES
        return Result(
            time=join(times[r]),
            responses={n: join(c) for n, c in zip(header.response_columns, columns[r])},
            sensitivity_time=join(times[s]),
            sensitivities={n: join(c) for n, c in zip(header.sensitivity_columns, columns[s])},
            summary=summary_dict(header.summary), name=header.job.model_name,
            job=Job(header.job))

    def put_model(self, model: ModelLike) -> str:
        return self._call(self._stub.PutModel,
                          service_pb2.PutModelRequest(model=load_model(model))).model_id

    def evaluate(self, model: Union[ModelLike, None], functionals: Iterable, *,
                 model_id: Optional[str] = None,
                 param_values: Optional[Mapping[str, float]] = None,
                 params: Sequence[str] = (), sensitivity: Optional[str] = "ddm",
                 fdm_eps: Optional[float] = None, t_end: Optional[float] = None,
                 dt: Optional[float] = None, no_cache: bool = False,
                 timeout: Optional[float] = None) -> Evaluation:
        """Functionals ('recorder:max', 'bottom_p:at:0.1', ...) and their gradients."""
        request = service_pb2.EvaluateRequest(
            functionals=[_functional(f) for f in functionals],
            parameter_values=_param_values(param_values), params=list(params),
            sensitivity=_METHODS[sensitivity], no_cache=no_cache)
        if model_id:
            request.model_id = model_id
        else:
            request.model.CopyFrom(load_model(model))
        for name, value in (("fdm_eps", fdm_eps), ("t_end", t_end), ("dt", dt)):
            if value is not None:
                setattr(request, name, value)
        response = self._call(self._stub.Evaluate, request, timeout=timeout,
                              attempts=self._max_attempts)
        n = len(response.parameters)
        return Evaluation(
            names=[v.name for v in response.values],
            values=np.array([v.value for v in response.values]),
            times=np.array([v.time for v in response.values]),
            gradients=np.array([list(v.gradient) for v in response.values]).reshape(
                len(response.values), n),
            parameters=list(response.parameters),
            parameter_values=np.array(response.parameter_values),
            cached=response.cached, wall_seconds=response.wall_seconds,
            summary=response.summary)


    def evaluate_many(self, model: Union[ModelLike, None], functionals: Iterable,
                      points: Sequence[Mapping[str, float]], *, concurrency: int = 1,
                      **options) -> List[Evaluation]:
        """evaluate() at every point (a dict of parameter values), `concurrency` calls at once
        (spread over the replicas of the target); the results in the order of `points`."""
        if concurrency < 1:
            raise ValueError("concurrency: must be >= 1")
        functionals = list(functionals)
        with concurrent.futures.ThreadPoolExecutor(max_workers=concurrency) as pool:
            return list(pool.map(lambda p: self.evaluate(model, functionals, param_values=p,
                                                         **options), points))


def summary_dict(summary: service_pb2.Summary) -> dict:
    """The summary as a dict with the keys and values of summary.json (status "completed",
    parameters {name: value}, ...)."""
    d = json.loads(json_format.MessageToJson(summary, preserving_proto_field_name=True,
                                             including_default_value_fields=True))
    d["status"] = service_pb2.RunStatus.Name(summary.status)[len("RUN_STATUS_"):].lower()
    d["parameters"] = dict(zip(summary.parameters, summary.parameter_values))
    del d["parameter_values"]
    for key in ("newton_iterations", "factorizations"):  # int64 fields come as JSON strings
        d[key] = int(d[key])
    return d
