"""PNG plots of a result's histories (matplotlib, Agg backend: no display needed)."""
from __future__ import annotations

import os
from typing import List

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def _grid(n: int):
    cols = min(3, max(1, n))
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.2 * rows), squeeze=False)
    for ax in axes.flat[n:]:
        ax.set_visible(False)
    return fig, list(axes.flat[:n])


def plot_histories(result, out_dir: str) -> List[str]:
    """Writes responses.png (one panel per recorder) and, when the result has them,
    sensitivities.png (one panel per d<recorder>/d<param>) into out_dir; returns the paths."""
    os.makedirs(out_dir, exist_ok=True)
    written = []
    for name, time, series in (("responses", result.time, result.responses),
                               ("sensitivities", result.sensitivity_time, result.sensitivities)):
        if not series:
            continue
        fig, axes = _grid(len(series))
        for ax, (label, values) in zip(axes, series.items()):
            ax.plot(time, values, lw=1.4)
            ax.set_title(label, fontsize=10)
            ax.set_xlabel("t [s]")
            ax.grid(alpha=0.3)
        fig.suptitle(f"{result.name or 'model'}: {name}", fontsize=11)
        fig.tight_layout()
        path = os.path.join(out_dir, f"{name}.png")
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)
    return written
