#!/usr/bin/python3
"""Plot `grip bench hard`'s CSVs: per case, Newton iterations per step (mean bar, max tick, and
step by step as a heat map), the smallest distance over d_hat the run reached, and the smallest
det F; a failed case is red.
Usage: plot_hard.py hard.csv hard_steps.csv hard.png (Debian: python3-matplotlib)."""
import csv
import math
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.colors  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def main(cases_path, steps_path, png_path):
    with open(cases_path, newline="") as f:
        cases = list(csv.DictReader(f))
    with open(steps_path, newline="") as f:
        steps = list(csv.DictReader(f))
    names = [c["case"] for c in cases]
    y = list(range(len(names)))[::-1]
    colour = ["tab:blue" if c["passed"] == "1" else "tab:red" for c in cases]
    fig, (newton_ax, trace_ax, dist_ax, det_ax) = plt.subplots(
        1, 4, figsize=(15, 0.38 * len(names) + 1.6), gridspec_kw={"width_ratios": [1, 1.6, 1, 1]})

    newton_ax.barh(y, [float(c["newton_mean"]) for c in cases], color=colour, alpha=0.8,
                   label="mean")
    newton_ax.plot([int(c["newton_max"]) for c in cases], y, "k|", ms=10, label="max")
    newton_ax.set_yticks(y)
    newton_ax.set_yticklabels(names, fontsize=8)
    newton_ax.set_title("Newton iterations per step")
    newton_ax.legend(fontsize=7, loc="lower right")

    # Heat map of Newton iterations, one row per case (top to bottom as in the bars), one
    # column per step; white where a case ran fewer steps.
    longest = max((int(s["step"]) for s in steps), default=1)
    grid = np.full((len(names), longest), np.nan)
    for s in steps:
        grid[names.index(s["case"]), int(s["step"]) - 1] = int(s["newton_iterations"])
    image = trace_ax.imshow(grid, aspect="auto", cmap="viridis", interpolation="nearest",
                            norm=matplotlib.colors.LogNorm(vmin=1, vmax=max(2, np.nanmax(grid))),
                            extent=(0.5, longest + 0.5, -0.5, len(names) - 0.5))
    fig.colorbar(image, ax=trace_ax, pad=0.01, label="Newton iterations")
    trace_ax.set_yticks(y)
    trace_ax.set_yticklabels([])
    trace_ax.set_xlabel("step")
    trace_ax.set_title("Newton iterations, step by step")

    ratio = [float(c["min_distance_over_d_hat"]) for c in cases]
    touched = [r if math.isfinite(r) else float("nan") for r in ratio]
    dist_ax.barh(y, touched, color=colour, alpha=0.8)
    dist_ax.set_xscale("log")
    dist_ax.axvline(1.0, color="k", lw=0.8, ls="--")
    dist_ax.set_yticks(y)
    dist_ax.set_yticklabels([])
    dist_ax.set_title("min distance / d_hat (> 0)")

    det_ax.barh(y, [float(c["min_volume_ratio"]) for c in cases], color=colour, alpha=0.8)
    det_ax.axvline(0.0, color="k", lw=0.8)
    det_ax.set_yticks(y)
    det_ax.set_yticklabels([])
    det_ax.set_xlim(0, 1.05)
    det_ax.set_title("min det F (> 0: no inversion)")

    for ax in (newton_ax, dist_ax, det_ax):
        ax.grid(alpha=0.3)
    for ax in (newton_ax, trace_ax, dist_ax, det_ax):
        ax.set_ylim(-0.5, len(names) - 0.5)
    fig.tight_layout()
    fig.savefig(png_path, dpi=120)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3])
