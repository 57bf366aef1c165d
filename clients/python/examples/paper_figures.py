#!/usr/bin/python3
"""The paper's comparison of its two fluid formulations (Zhu & Scott 2017, Figs. 3, 4, 6, 8) from a
running pfem-server: each example is run with analysis.formulation "quasi-incompressible" (exact DDM)
and "incompressible" (Zhu & Scott's fractional step; its DDM is the approximate one, labelled
"ddm-approximate"), with DDM sensitivities to the example's end and with central finite differences
(FDM, eps = 1e-8) of each formulation's own response over the check window, where the perturbed
runs still remesh as the base run does (beyond it the FDM is a remeshing decision, not a derivative).

    PYTHONPATH=build/python:clients/python /usr/bin/python3 \\
        clients/python/examples/paper_figures.py --server 127.0.0.1:50051 --out examples

(scripts/paper-figures starts a server, runs this and stops it). Writes
    OUT/sloshing-beam-paper-mesh-fig3.png   Fig. 3: tip deflection and base pressure, both formulations
    OUT/sloshing-beam-paper-mesh-fig4.png   Fig. 4: their sensitivities to E and rho_f: both DDMs, FDM
    OUT/dam-break-obstacle-fig6.png         Fig. 6: tip deflection, both formulations, and the extreme
                                            base fiber's stress-strain loop
    OUT/dam-break-obstacle-fig8.png         Fig. 8: the tip's sensitivities to E and Fy: both DDMs, FDM
and prints what they show: the responses' largest difference relative to the peak, and each DDM's
largest difference from its formulation's FDM relative to the FDM's peak over the check window.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from pfem_client import Client, load_model  # noqa: E402

FORMULATIONS = ("quasi-incompressible", "incompressible")
STYLE = {"quasi-incompressible": dict(color="tab:blue", ls="-"),
         "incompressible": dict(color="tab:orange", ls="--")}
EXAMPLES = {
    # name: (model file, parameters, recorders of the sensitivity figure, FDM window [s], t_end [s])
    # The paper mesh's runs stop at 0.6 s: its incompressible runs take about 3 times the
    # quasi-incompressible ones (an hour for the figure's 1 s of both and their FDM on 2 cores).
    "dam-break-obstacle": ("examples/dam-break-obstacle.json", ["E", "Fy"], ["tip_ux"], 0.34, 1.0),
    "sloshing-beam-paper-mesh": ("examples/sloshing-beam-paper-mesh.json", ["E", "rho_f"],
                                 ["tip_ux", "base_p"], 0.3, 0.6),
}
# The obstacle's extreme base fiber (the stress recorder's), for the stress-strain loop.
FIBER_STRAIN = {"name": "base_fiber_strain", "quantity": "fiber_strain", "element": "obstacle/1",
                "section_point": 0, "fiber": 0}


def model_of(path, formulation):
    model = load_model(path)
    model.analysis.formulation = formulation
    if formulation == "incompressible":
        model.fluid.ClearField("kappa")  # it has none
    if model.name == "dam-break-obstacle":
        recorder = model.recorders.add()
        for key, value in FIBER_STRAIN.items():
            setattr(recorder, key, value)
    return model


def run_all(client, t_end):
    """{(example, formulation, method): Result}, the jobs two at a time on the server's workers:
    the DDM to the example's end (or t_end), the FDM over its window."""
    jobs = {}
    for name, (path, params, _, window, end) in EXAMPLES.items():
        for f in FORMULATIONS:
            for method in ("ddm", "fdm"):
                run_to = t_end or end
                jobs[(name, f, method)] = client.submit(
                    model_of(path, f), t_end=min(window, run_to) if method == "fdm" else run_to,
                    sensitivity=method, params=params, fdm_eps=1e-8 if method == "fdm" else None)
                print(f"submitted {name} {f} {method}: job {jobs[(name, f, method)]}", flush=True)
    results = {}
    for key, job_id in jobs.items():
        job = client.watch(job_id)
        if job.state != "SUCCEEDED":
            sys.exit(f"paper_figures: {' '.join(key)} (job {job_id}) {job.state}: {job.error.message}")
        results[key] = client.result(job_id)
        s = results[key].summary
        print(f"{' '.join(key)}: {s.get('steps')} steps, {s.get('wall_seconds', 0):.0f} s, "
              f"sensitivity_method {s.get('sensitivity_method')}", flush=True)
    return results


def largest_difference(a, b):
    """max |a - b| over max |b|, over b's samples (a may run longer)."""
    a = a[:len(b)]
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


def response_panel(ax, results, name, recorder, scale, unit):
    for f in FORMULATIONS:
        r = results[(name, f, "ddm")]
        ax.plot(r.time, r.responses[recorder] * scale, lw=1.3, label=f, **STYLE[f])
    ax.set_xlabel("t [s]")
    ax.set_ylabel(f"{recorder} [{unit}]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)


def sensitivity_panel(ax, results, name, recorder, param):
    """Both DDMs as lines, each formulation's FDM as markers; the axis follows the exact DDM and
    its FDM, and what leaves it (the approximate DDM growing) is clipped at the edge."""
    column = f"d{recorder}/d{param}"
    q = results[(name, "quasi-incompressible", "ddm")]
    t = q.sensitivity_time
    exact = q.sensitivities[column]
    fdm_q = results[(name, "quasi-incompressible", "fdm")].sensitivities[column]
    tf = results[(name, "quasi-incompressible", "fdm")].sensitivity_time
    lo, hi = float(min(exact.min(), fdm_q.min())), float(max(exact.max(), fdm_q.max()))
    pad = 0.25 * (hi - lo) if hi > lo else max(abs(hi), 1e-300)
    lo, hi = lo - pad, hi + pad
    for f in FORMULATIONS:
        d = results[(name, f, "ddm")].sensitivities[column]
        label = "DDM, quasi-incompressible" if f == FORMULATIONS[0] else "DDM, incompressible (approximate)"
        ax.plot(t, np.clip(d, lo, hi), lw=1.3, label=label, **STYLE[f])
        fdm = results[(name, f, "fdm")].sensitivities[column]
        every = max(1, len(tf) // 30)
        ax.plot(tf[::every], np.clip(fdm[::every], lo, hi), "o" if f == FORMULATIONS[0] else "x", ms=3.5,
                mfc="none", color=STYLE[f]["color"], label=f"FDM (1e-8), {f}")
    ax.set_ylim(lo, hi)
    ax.set_title(column, fontsize=10)
    ax.set_xlabel("t [s]")
    ax.grid(alpha=0.3)


def print_checks(results, name, recorders, params, window):
    q, i = (results[(name, f, "ddm")] for f in FORMULATIONS)
    for r in q.responses:
        if r in recorders:
            print(f"{name} {r} to {q.time[-1]:g} s: the formulations' largest difference "
                  f"{largest_difference(i.responses[r], q.responses[r]):.3f} of the "
                  f"quasi-incompressible peak {np.max(np.abs(q.responses[r])):.4g}")
    for r in recorders:
        for p in params:
            column = f"d{r}/d{p}"
            row = []
            for f in FORMULATIONS:
                d = results[(name, f, "ddm")].sensitivities[column]
                fdm = results[(name, f, "fdm")]
                row.append(f"{f} {largest_difference(d, fdm.sensitivities[column]):.2e}")
            print(f"{name} {column} to {window} s: |DDM - FDM| / max |FDM|: " + "; ".join(row))


def save(fig, title, path):
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def sloshing_figures(results, out):
    name = "sloshing-beam-paper-mesh"
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.6))
    response_panel(axes[0], results, name, "tip_ux", 1e3, "mm")
    response_panel(axes[1], results, name, "base_p", 1.0, "Pa")
    fig3 = save(fig, "Fig. 3: sloshing beam (4125 triangles), tip deflection and base pressure",
                os.path.join(out, f"{name}-fig3.png"))
    _, params, recorders, _, _ = EXAMPLES[name]
    fig, axes = plt.subplots(len(recorders), len(params), figsize=(10, 7), squeeze=False)
    for a, r in enumerate(recorders):
        for b, p in enumerate(params):
            sensitivity_panel(axes[a][b], results, name, r, p)
    axes[0][0].legend(fontsize=7)
    fig4 = save(fig, "Fig. 4: sloshing beam, sensitivities (the incompressible DDM clipped where it "
                "leaves the axis)", os.path.join(out, f"{name}-fig4.png"))
    return [fig3, fig4]


def obstacle_figures(results, out):
    name = "dam-break-obstacle"
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    response_panel(axes[0], results, name, "tip_ux", 1e3, "mm")
    for f in FORMULATIONS:
        r = results[(name, f, "ddm")]
        axes[1].plot(r.responses["base_fiber_strain"], r.responses["base_fiber_stress"] / 1e3, lw=1.0,
                     label=f, **STYLE[f])
    axes[1].set_xlabel("strain [-]")
    axes[1].set_ylabel("stress [kPa]")
    axes[1].set_title("extreme base fiber (obstacle/1, point 0, fiber 0)", fontsize=10)
    axes[1].grid(alpha=0.3)
    axes[1].legend(fontsize=8)
    fig6 = save(fig, "Fig. 6: yielding obstacle, tip deflection and the base fiber's stress-strain loop",
                os.path.join(out, f"{name}-fig6.png"))
    _, params, _, _, _ = EXAMPLES[name]
    fig, axes = plt.subplots(1, len(params), figsize=(10, 3.8), squeeze=False)
    for b, p in enumerate(params):
        sensitivity_panel(axes[0][b], results, name, "tip_ux", p)
    axes[0][0].legend(fontsize=7)
    fig8 = save(fig, "Fig. 8: yielding obstacle, sensitivity of the tip deflection",
                os.path.join(out, f"{name}-fig8.png"))
    return [fig6, fig8]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--server", required=True, help="HOST:PORT of pfem-server")
    ap.add_argument("--token-file")
    ap.add_argument("--t-end", type=float, help="shorter runs than the figures' own (EXAMPLES)")
    ap.add_argument("--out", default="examples", help="where the PNGs go")
    args = ap.parse_args(argv)
    with Client(args.server, token_file=args.token_file) as client:
        results = run_all(client, args.t_end)
    for name, (_, params, recorders, window, _) in EXAMPLES.items():
        print_checks(results, name, recorders, params, window)
    os.makedirs(args.out, exist_ok=True)
    for path in obstacle_figures(results, args.out) + sloshing_figures(results, args.out):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
