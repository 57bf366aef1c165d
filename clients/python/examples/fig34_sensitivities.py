#!/usr/bin/python3
"""Fig. 3/4-style plots of the sloshing example from a pfem-server run: the tip deflection of
the soft beam and the fluid pressure at its base (Fig. 3) and their DDM sensitivities to the
beam's Young's modulus E and the fluid density rho_f (Fig. 4), with central finite
differences (FDM) overlaid when available.

Against a running pfem-server (stubs from the build on PYTHONPATH):

    PYTHONPATH=build/python:clients/python /usr/bin/python3 \\
        clients/python/examples/fig34_sensitivities.py examples/sloshing-beam.json \\
        --server 127.0.0.1:50051 --t-end 0.3 --fdm --out out/fig34

submits the model with DDM (and, with --fdm, a second job with FDM; both run side by side on
the server's workers), follows them, fetches the results and plots. `--job ID` plots a job
submitted earlier (e.g. by `pfemctl submit`) instead of submitting one; `--fdm-job ID` takes
the FDM overlay from another job. Without a server, `--result-dir DIR` reads what
`pfemctl result ID --out DIR` (or `pfem run`) wrote, `--fdm-dir DIR` the FDM overlay.

It prints the job ids, progress, a gradient summary (final value and extreme |value| of each
recorder with its sensitivities) and the files written:
    OUT/fig3_responses.png       each recorder against time
    OUT/fig4_sensitivities.png   d recorder / d param for every pair (DDM line, FDM markers;
                                 times the parameter's value with --scaled: the change per 100 %)
    OUT/responses.png, OUT/sensitivities.png   pfem_client.plot_histories' overview
Any model works: name its recorders and parameters with --recorders and --params.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from pfem_client import plot_histories, read_result_dir  # noqa: E402

_UNITS = {"ux": "m", "uy": "m", "rz": "rad", "vx": "m/s", "vy": "m/s", "p": "Pa"}


def _label(recorder: str) -> str:
    """'tip_ux [m]' when the name ends in a quantity (tip_ux, base_p), else the name."""
    unit = _UNITS.get(recorder.rsplit("_", 1)[-1])
    return f"{recorder} [{unit}]" if unit else recorder


def fetch(args, params):
    """(DDM result, FDM result or None) from the server: submitted here or given by id."""
    from pfem_client import Client

    def progress(tag):
        last = [-1]

        def show(job):
            p = job.progress
            if p.total_steps and (p.step * 10 // p.total_steps != last[0] or
                                  job.finished):
                last[0] = p.step * 10 // p.total_steps
                print(f"{tag} {job.state} step "
                      f"{p.step}/{p.total_steps} t={p.time:.4g} s "
                      f"elapsed {p.elapsed_seconds:.1f} s", flush=True)
        return show

    with Client(args.server, token_file=args.token_file) as client:
        def submit(method):
            if not args.model:
                sys.exit("fig34: a MODEL file is needed to submit a job")
            job_id = client.submit(args.model, t_end=args.t_end, sensitivity=method,
                                   params=params)
            print(f"{method} job {job_id}", flush=True)
            return job_id

        ddm_id = args.job or submit("ddm")
        fdm_id = args.fdm_job or (submit("fdm") if args.fdm else None)
        out = []
        for tag, job_id in (("ddm", ddm_id), ("fdm", fdm_id)):
            if job_id is None:
                out.append(None)
                continue
            job = client.watch(job_id, callback=progress(f"{tag} {job_id}"))
            if job.state != "SUCCEEDED":
                print(f"fig34: job {job_id} {job.state}: "
                      f"{job.error.message}" + (" (no FDM overlay)" if tag == "fdm" else ""),
                      file=sys.stderr)
                if tag == "fdm":
                    out.append(None)
                    continue
            out.append(client.result(job_id))
        return out[0], out[1]


def extreme_row(values):
    return int(np.argmax(np.abs(values)))


def print_summary(result, recorders, params):
    """Final value and extreme |value| of each recorder, with their sensitivities."""
    print(f"{'':>8} {'t [s]':>7} {'recorder':>12} {'value':>13}" +
          "".join(f" {'d/d' + p:>13}" for p in params))
    for r in recorders:
        values = result.responses[r]
        for label, i in (("final", len(values) - 1), ("max|.|", extreme_row(values))):
            t = result.time[i]
            j = int(np.argmin(np.abs(result.sensitivity_time - t))) if params else 0
            grads = "".join(f" {result.sensitivity(r, p)[j]:13.5e}" for p in params)
            print(f"{label:>8} {t:7.3f} {r:>12} {values[i]:13.5e}{grads}")


def plot(result, fdm, recorders, params, out, scaled=False):
    os.makedirs(out, exist_ok=True)
    values = dict(zip(result.parameters, result.parameter_values))

    fig, axes = plt.subplots(1, len(recorders), figsize=(5 * len(recorders), 3.6), squeeze=False)
    for ax, r in zip(axes[0], recorders):
        ax.plot(result.time, result.responses[r], "k-", lw=1.5)
        ax.set_xlabel("t [s]")
        ax.set_ylabel(_label(r))
        ax.set_title(r, fontsize=10)
        ax.grid(alpha=0.3)
    fig.suptitle(f"Fig. 3 style: responses ({result.name})")
    fig.tight_layout()
    fig3 = os.path.join(out, "fig3_responses.png")
    fig.savefig(fig3, dpi=120)
    plt.close(fig)

    fig, axes = plt.subplots(len(recorders), len(params),
                             figsize=(4.6 * len(params), 3.2 * len(recorders)), squeeze=False)
    for i, r in enumerate(recorders):
        for k, p in enumerate(params):
            ax = axes[i][k]
            scale = values.get(p, 1.0) if scaled else 1.0
            ax.plot(result.sensitivity_time, result.sensitivity(r, p) * scale, "b-", lw=1.4,
                    label=(result.method or "ddm").upper())
            if fdm is not None and f"d{r}/d{p}" in fdm.sensitivities:
                every = max(1, len(fdm.sensitivity_time) // 40)
                t, f = fdm.sensitivity_time[::every], fdm.sensitivity(r, p)[::every] * scale
                # The axis follows the DDM curve; FDM points far off it (a perturbed run that
                # remeshed differently) are drawn at the edge and counted in the legend.
                d = result.sensitivity(r, p) * scale
                lo, hi = float(np.min(d)), float(np.max(d))
                pad = 0.15 * (hi - lo) if hi > lo else max(abs(hi), 1e-300)
                lo, hi = lo - pad, hi + pad
                off = (f < lo) | (f > hi)
                ax.plot(t[~off], f[~off], "o", mfc="none", mec="tab:red", ms=4, label="FDM")
                if off.any():
                    ax.plot(t[off], np.clip(f[off], lo, hi), "^", color="tab:red", ms=5,
                            label=f"FDM off scale ({int(off.sum())})")
                ax.set_ylim(lo, hi)
            ax.set_title(f"{'%s · ' % p if scaled else ''}d{r}/d{p}", fontsize=10)
            ax.set_xlabel("t [s]")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
    fig.suptitle("Fig. 4 style: sensitivities" + (" (DDM vs FDM)" if fdm is not None else ""))
    fig.tight_layout()
    fig4 = os.path.join(out, "fig4_sensitivities.png")
    fig.savefig(fig4, dpi=120)
    plt.close(fig)

    written = [fig3, fig4]
    return written + plot_histories(result, out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("model", nargs="?", help="model JSON file (pfem.v1.Model) to submit")
    ap.add_argument("--server", help="HOST:PORT of pfem-server")
    ap.add_argument("--token-file")
    ap.add_argument("--job", help="plot this finished (or running) job instead of submitting")
    ap.add_argument("--fdm", action="store_true", help="also submit an FDM job and overlay it")
    ap.add_argument("--fdm-job", help="overlay the FDM sensitivities of this job")
    ap.add_argument("--result-dir", help="read a result directory instead of a server")
    ap.add_argument("--fdm-dir", help="FDM result directory to overlay (with --result-dir)")
    ap.add_argument("--recorders", default="tip_ux,base_p", help="two (or more) recorders")
    ap.add_argument("--params", default="E,rho_f", help="parameters to differentiate")
    ap.add_argument("--t-end", type=float)
    ap.add_argument("--scaled", action="store_true", help="plot param * d r / d param")
    ap.add_argument("--out", default="fig34")
    args = ap.parse_args(argv)
    recorders = [r for r in args.recorders.split(",") if r]
    params = [p for p in args.params.split(",") if p]

    if args.result_dir:
        result = read_result_dir(args.result_dir)
        fdm = read_result_dir(args.fdm_dir) if args.fdm_dir else None
    elif args.server:
        result, fdm = fetch(args, params)
    else:
        ap.error("give --server HOST:PORT (with MODEL or --job ID) or --result-dir DIR")
    if result.message:
        print(f"fig34: the run ended early: {result.message}", file=sys.stderr)
    params = [p for p in params if p in result.parameters]

    print_summary(result, recorders, params)
    if fdm is not None and np.array_equal(fdm.sensitivity_time, result.sensitivity_time):
        # Per pair: the largest |DDM - FDM| relative to the DDM history's peak, and the first
        # time they differ by more than 1 % of it (FDM breaks where a perturbed run remeshes
        # differently).
        rows = []
        for r in recorders:
            for p in params:
                d, f = result.sensitivity(r, p), fdm.sensitivity(r, p)
                rel = np.abs(d - f) / max(np.max(np.abs(d)), 1e-300)
                far = np.nonzero(rel > 1e-2)[0]
                rows.append((float(np.max(rel)), f"d{r}/d{p}",
                             result.sensitivity_time[far[0]] if far.size else None))
        worst = max(rows, key=lambda x: x[0])
        print(f"DDM vs FDM: largest difference {worst[0]:.2e} of the history's peak "
              f"({worst[1]})")
        for rel, name, t in rows:
            if t is not None:
                print(f"  {name}: FDM departs from DDM by > 1 % of the peak from t = {t:.3f} s")
    for path in plot(result, fdm, recorders, params, args.out, args.scaled):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
