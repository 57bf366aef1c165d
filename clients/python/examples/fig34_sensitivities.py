#!/usr/bin/python3
"""Fig. 3/4-style plots from a server run: two responses (in the paper, the tip deflection of
the elastic plate and the pressure at its base) and their DDM sensitivities to the plate's
Young's modulus E and the fluid density rho_f.

Run it against a running pfem-server (stubs from the build on PYTHONPATH):

    PYTHONPATH=build/python:clients/python /usr/bin/python3 \\
        clients/python/examples/fig34_sensitivities.py --server 127.0.0.1:50051 \\
        MODEL.json --recorders tip_ux,base_p --params E,rho_f --out fig34

It prints the job id, one progress line per update and the written files:
    fig34/fig3_responses.png       each recorder against time
    fig34/fig4_sensitivities.png   d recorder / d param for every pair (scaled by the
                                   parameter's value with --scaled: the change per 100 %)
    fig34/responses.png, fig34/sensitivities.png   pfem_client.plot_histories' overview
Any model works: name its recorders and parameters with --recorders and --params.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from pfem.v1 import service_pb2  # noqa: E402
from pfem_client import Client, plot_histories  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("model", help="model JSON file (pfem.v1.Model)")
    ap.add_argument("--server", required=True, help="HOST:PORT of pfem-server")
    ap.add_argument("--token-file")
    ap.add_argument("--recorders", default="tip_ux,base_p", help="two (or more) recorders")
    ap.add_argument("--params", default="E,rho_f", help="parameters to differentiate")
    ap.add_argument("--sensitivity", default="ddm", choices=["ddm", "fdm"])
    ap.add_argument("--t-end", type=float)
    ap.add_argument("--scaled", action="store_true", help="plot param * d r / d param")
    ap.add_argument("--out", default="fig34")
    args = ap.parse_args(argv)
    recorders = [r for r in args.recorders.split(",") if r]
    params = [p for p in args.params.split(",") if p]

    with Client(args.server, token_file=args.token_file) as client:
        job_id = client.submit(args.model, t_end=args.t_end, sensitivity=args.sensitivity,
                               params=params)
        print(job_id, flush=True)
        job = client.watch(job_id, callback=lambda j: print(
            f"{j.progress.step}/{j.progress.total_steps} t={j.progress.time:.4g} s", flush=True))
        result = client.result(job_id)
    if job.state != service_pb2.JOB_STATE_SUCCEEDED:
        print(f"the run ended early: {result.summary.message}", file=sys.stderr)

    os.makedirs(args.out, exist_ok=True)
    values = dict(zip(result.summary.parameters, result.summary.parameter_values))

    fig, axes = plt.subplots(1, len(recorders), figsize=(5 * len(recorders), 3.6), squeeze=False)
    for ax, r in zip(axes[0], recorders):
        ax.plot(result.time, result.responses[r], "k-", lw=1.5)
        ax.set_xlabel("t [s]")
        ax.set_ylabel(r)
        ax.grid(alpha=0.3)
    fig.suptitle("Fig. 3 style: responses")
    fig.tight_layout()
    fig3 = os.path.join(args.out, "fig3_responses.png")
    fig.savefig(fig3, dpi=120)
    plt.close(fig)

    fig, axes = plt.subplots(len(recorders), len(params),
                             figsize=(4.6 * len(params), 3.2 * len(recorders)), squeeze=False)
    for i, r in enumerate(recorders):
        for k, p in enumerate(params):
            ax = axes[i][k]
            s = result.sensitivity(r, p) * (values.get(p, 1.0) if args.scaled else 1.0)
            ax.plot(result.sensitivity_time, s, "b-", lw=1.4, label=args.sensitivity.upper())
            ax.set_title(f"{'%s · ' % p if args.scaled else ''}d{r}/d{p}", fontsize=10)
            ax.set_xlabel("t [s]")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
    fig.suptitle("Fig. 4 style: sensitivities")
    fig.tight_layout()
    fig4 = os.path.join(args.out, "fig4_sensitivities.png")
    fig.savefig(fig4, dpi=120)
    plt.close(fig)

    for path in [fig3, fig4] + plot_histories(result, args.out):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
