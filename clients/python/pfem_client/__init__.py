"""Python client of pfem-server (pfem.v1.GradientService).

    from pfem_client import Client, plot_histories
    client = Client("127.0.0.1:50051", token_file="tokens")
    job = client.submit("examples/hydrostatic.json", t_end=0.1, sensitivity="ddm")
    client.watch(job, callback=lambda j: print(j.state, j.progress.step))
    result = client.result(job)          # numpy arrays: result.time, result.responses[...]
    plot_histories(result, "plots")       # PNGs

The generated stubs (pfem/v1/*_pb2.py) must be on PYTHONPATH: CMake writes them to
build/python. Use Debian's /usr/bin/python3 (python3-grpcio, python3-protobuf).
"""
from .client import Client, Evaluation, Job, Result, ServiceError, load_model
from .plots import plot_histories

__all__ = ["Client", "Evaluation", "Job", "Result", "ServiceError", "load_model", "plot_histories"]
