"""Result: a run's histories as numpy arrays and its summary, the one result type of the
in-process `pfem` module, of the gRPC client (pfem_client.Client.result) and of a result
directory written by `pfem run` or `pfemctl result` (read_result_dir)."""
from __future__ import annotations

import csv
import json
import os
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional

import numpy as np


@dataclass
class Result:
    """time[i] and responses[recorder][i]; sensitivity_time and sensitivities["d<recorder>/d<param>"]
    (empty without sensitivities); summary: the keys of summary.json (status, message, steps,
    wall_seconds, ..., parameters {name: value}); job: the server's Job when one ran it."""

    time: np.ndarray
    responses: Dict[str, np.ndarray]
    sensitivity_time: np.ndarray
    sensitivities: Dict[str, np.ndarray]
    summary: Dict[str, Any]
    name: str = ""
    job: Optional[Any] = field(default=None, repr=False)

    def sensitivity(self, recorder: str, param: str) -> np.ndarray:
        return self.sensitivities[f"d{recorder}/d{param}"]

    @property
    def parameters(self) -> List[str]:
        return list(self.summary.get("parameters", {}))

    @property
    def parameter_values(self) -> np.ndarray:
        return np.array(list(self.summary.get("parameters", {}).values()), dtype=np.float64)

    @property
    def status(self) -> str:
        """"completed", "failed" or "cancelled"."""
        return self.summary.get("status", "")

    @property
    def method(self) -> str:
        return self.summary.get("sensitivity_method", "")

    @property
    def message(self) -> str:
        return self.summary.get("message", "")


def from_columns(columns, time, values) -> Dict[str, np.ndarray]:
    """{column: values[:, j]} from a (rows, columns) array."""
    values = np.asarray(values, dtype=np.float64).reshape(len(time), len(columns))
    return {name: values[:, j].copy() for j, name in enumerate(columns)}


def read_result_dir(path: str) -> Result:
    """A Result from responses.csv, sensitivities.csv (if any) and summary.json (if any)."""
    def read(file):
        with open(file, newline="") as f:
            rows = list(csv.reader(f))
        data = np.array(rows[1:], dtype=np.float64).reshape(-1, len(rows[0]))
        return data[:, 0], from_columns(rows[0][1:], data[:, 0], data[:, 1:])

    time, responses = read(os.path.join(path, "responses.csv"))
    sens_file = os.path.join(path, "sensitivities.csv")
    sens_time, sensitivities = read(sens_file) if os.path.exists(sens_file) else (np.zeros(0), {})
    summary = {}
    if os.path.exists(os.path.join(path, "summary.json")):
        with open(os.path.join(path, "summary.json"), encoding="utf-8") as f:
            summary = json.load(f)
    return Result(time=time, responses=responses, sensitivity_time=sens_time,
                  sensitivities=sensitivities, summary=summary,
                  name=os.path.basename(os.path.normpath(path)))
