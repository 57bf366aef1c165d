"""The PFEM-DDM engine in-process: build or load a model, validate it, run it (with DDM or FDM
sensitivities) and get numpy histories back, without a server.

    import pfem
    model = pfem.load_model("examples/sloshing-beam.json")   # or a dict, or a JSON string
    model.data["analysis"]["t_end"] = 0.1                     # the model as a plain dict
    errors = pfem.validate(model)                            # [] or [("fluid.rho", "must be > 0")]
    pfem.check(model)["warnings"], pfem.check(model)["estimate"]["seconds"]
    result = pfem.run(model, sensitivity="ddm", params=["E"], threads=2)
    result.responses["tip_ux"], result.sensitivity("tip_ux", "E"), result.summary["steps"]

run() releases the GIL while the engine works; Ctrl-C stops it at the end of the step in
progress and raises RunInterrupted (a KeyboardInterrupt) carrying the partial result. The
Result type and the plots are those of the gRPC client (pfem_client).

Build tree: PYTHONPATH=build/python:clients/python, Debian's /usr/bin/python3.
"""
from __future__ import annotations

import copy
import json
import os
import pkgutil
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

# The package spans two folders: this one (Python) and build/python/pfem (the compiled _engine
# module and the generated pfem.v1 stubs).
__path__ = pkgutil.extend_path(__path__, __name__)

from pfem_client.plots import plot_histories  # noqa: E402
from pfem_client.results import Result, from_columns, read_result_dir  # noqa: E402

from . import _engine  # noqa: E402

# A checkpoint run() cannot continue (another model, options or engine build; damaged).
CheckpointError = _engine.CheckpointError

__all__ = ["CheckpointError", "Model", "ModelError", "Result", "RunInterrupted", "check", "load_model",
           "plot_histories",
           "read_result_dir", "run", "validate"]


class ModelError(ValueError):
    """An invalid model or run option: `errors` lists (field path, message) pairs, all of them."""

    def __init__(self, errors: List[Tuple[str, str]]):
        super().__init__("\n".join(f"{p}: {m}" for p, m in errors))
        self.errors = errors


class RunInterrupted(KeyboardInterrupt):
    """Ctrl-C during run(): `result` holds every step done (status "cancelled")."""

    def __init__(self, result: Result):
        super().__init__(f"run interrupted after {result.summary.get('steps', 0)} steps")
        self.result = result


class Model:
    """A model file's content as a dict (`data`, the proto3 JSON of pfem.v1.Model), edited freely
    and checked by validate() or run()."""

    def __init__(self, data: Mapping[str, Any], source: str = ""):
        self.data: Dict[str, Any] = copy.deepcopy(dict(data))
        self.source = source

    def json(self) -> str:
        return json.dumps(self.data)

    @property
    def name(self) -> str:
        return self.data.get("name", "")

    def __repr__(self):
        return f"Model({self.name or self.source or 'unnamed'!r})"


ModelLike = Union[Model, Mapping[str, Any], str, os.PathLike]


def load_model(model: ModelLike) -> Model:
    """A Model from a Model (copied), a dict, a JSON string or the path of a JSON file. A JSON
    syntax error is a ModelError with the line and column."""
    if isinstance(model, Model):
        return Model(model.data, model.source)
    if isinstance(model, Mapping):
        return Model(model)
    text, source = str(model), ""
    if not text.lstrip().startswith("{"):
        source = text
        with open(text, encoding="utf-8") as f:
            text = f.read()
    try:
        return Model(json.loads(text), source)
    except json.JSONDecodeError:
        errors = _engine.validate(text)["errors"]  # the engine's message, as `pfem validate`
        raise ModelError(errors or [("model", "invalid JSON")]) from None


def validate(model: ModelLike) -> List[Tuple[str, str]]:
    """Every problem of the model as (field path, message) pairs; [] when it is valid."""
    return _engine.validate(load_model(model).json())["errors"]


def check(model: ModelLike) -> Dict[str, Any]:
    """What `pfem validate` says: {"errors": [...], "warnings": [...] (implausible values, for a
    model without errors), "estimate": {particles, elements, steps, seconds,
    seconds_per_particle_step} (absent when the model cannot be read)}."""
    return _engine.validate(load_model(model).json())


def run(model: ModelLike, *, sensitivity: str = "none", params: Sequence[str] = (),
        t_end: Optional[float] = None, dt: Optional[float] = None, threads: int = 1,
        fdm_eps: Optional[float] = None, vtk_dir: str = "",
        progress: Optional[Callable[[dict], None]] = None, checkpoint_every: int = 0,
        checkpoint_file: str = "", restart_from: str = "") -> Result:
    """Runs the model as `pfem run` does (the same engine, the same numbers). sensitivity: "none",
    "ddm" or "fdm"; params: the parameters to differentiate (default: all of the model's);
    t_end, dt: overrides; vtk_dir: write ParaView files there; progress: called after every step
    with {step, total_steps, time, t_end, newton_iterations, elapsed_seconds, remaining_seconds}
    (an exception it raises stops the run and is raised here). checkpoint_every N: the state
    after every N-th step, and when stopped, written to checkpoint_file (the format of `pfem run
    --checkpoint-every`); restart_from: continue such a checkpoint, of this model and these
    options, bit-identically (else CheckpointError saying what differs). A simulation failure is
    not an exception: result.status is "failed" and result.message says why."""
    m = load_model(model)
    out = _engine.run(m.json(), sensitivity=sensitivity, params=list(params), t_end=t_end, dt=dt,
                      threads=threads, fdm_eps=fdm_eps, vtk_dir=vtk_dir, progress=progress,
                      checkpoint_every=checkpoint_every, checkpoint_file=checkpoint_file,
                      restart_from=restart_from)
    if "errors" in out:
        raise ModelError(out["errors"])
    r, s = out["responses"], out["sensitivities"]
    result = Result(time=r["time"], responses=from_columns(r["columns"], r["time"], r["values"]),
                    sensitivity_time=s["time"],
                    sensitivities=from_columns(s["columns"], s["time"], s["values"]),
                    summary=json.loads(out["summary_json"]), name=m.name)
    if out["interrupted"]:
        raise RunInterrupted(result)
    return result
