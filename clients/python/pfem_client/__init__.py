"""Python clients of the PFEM-DDM engine: the gRPC client of pfem-server
(pfem.v1.GradientService) and what it shares with the in-process `pfem` module: the Result
type (numpy histories and a summary dict) and the plots.

    from pfem_client import Client, plot_histories
    client = Client("127.0.0.1:50051", token_file="tokens")
    job = client.submit("examples/hydrostatic.json", t_end=0.1, sensitivity="ddm")
    client.watch(job, callback=lambda j: print(j.state, j.progress.step))
    result = client.result(job)          # numpy arrays: result.time, result.responses[...]
    plot_histories(result, "plots")       # PNGs

The generated stubs (pfem/v1/*_pb2.py) must be on PYTHONPATH: CMake writes them to
build/python. Use Debian's /usr/bin/python3 (python3-grpcio, python3-protobuf). The gRPC
part is imported on first use, so that `pfem` (in-process) needs neither.
"""
from .plots import plot_histories
from .results import Result, read_result_dir

_CLIENT_NAMES = ("Client", "Evaluation", "Job", "ServiceError", "load_model", "summary_dict")

__all__ = ["Result", "plot_histories", "read_result_dir", *_CLIENT_NAMES]


def __getattr__(name):
    if name in _CLIENT_NAMES:
        from . import client
        return getattr(client, name)
    raise AttributeError(f"module 'pfem_client' has no attribute {name!r}")
