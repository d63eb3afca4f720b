#!/usr/bin/python3
"""Plot `grip bench model`'s CSV: wall time of the lean and the full model per comparison
(median of the repeats), each pair annotated with the full/lean ratio of wall and of CPU time
and the lean model's largest surface-vertex error against the full one.
Usage: plot_model.py model.csv model.png (Debian: python3-matplotlib)."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(csv_path, png_path):
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    fig, (time_ax, its_ax) = plt.subplots(1, 2, figsize=(11, 4.2))
    x = range(len(rows))
    width = 0.38
    lean_s = [float(r["lean_s"]) for r in rows]
    full_s = [float(r["full_s"]) for r in rows]
    time_ax.bar([i - width / 2 for i in x], lean_s, width, label="lean model", color="tab:green")
    time_ax.bar([i + width / 2 for i in x], full_s, width, label="full model", color="tab:gray")
    for i, r in enumerate(rows):
        error_um = float(r["vertex_error_m"]) * 1e6
        cpu_ratio = float(r["full_cpu_s"]) / float(r["lean_cpu_s"])
        note = f"{full_s[i] / lean_s[i]:.2f}x (CPU {cpu_ratio:.2f}x)\nerr {error_um:.2g} um"
        time_ax.annotate(note, (i, max(lean_s[i], full_s[i])), ha="center", va="bottom",
                         fontsize=8, textcoords="offset points", xytext=(0, 3))
    time_ax.set_yscale("log")
    time_ax.set_ylabel("wall time (s, median)")
    time_ax.set_title("time: lean vs full model")
    time_ax.margins(y=0.35)

    lean_its = [int(r["lean_iterations"]) for r in rows]
    full_its = [int(r["full_iterations"]) for r in rows]
    its_ax.bar([i - width / 2 for i in x], lean_its, width, label="lean model", color="tab:green")
    its_ax.bar([i + width / 2 for i in x], full_its, width, label="full model", color="tab:gray")
    for i, r in enumerate(rows):
        its_ax.annotate(f"{r['lean_dofs']} / {r['full_dofs']}\nDOFs",
                        (i, max(lean_its[i], full_its[i])), ha="center", va="bottom",
                        fontsize=8, textcoords="offset points", xytext=(0, 3))
    its_ax.set_ylabel("Newton iterations (batch: environment-iterations)")
    its_ax.set_title("Newton iterations and DOFs solved for")
    its_ax.margins(y=0.25)

    for ax in (time_ax, its_ax):
        ax.set_xticks(list(x))
        ax.set_xticklabels([r["comparison"] for r in rows], fontsize=8, rotation=12)
        ax.grid(axis="y", alpha=0.3)
        ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(png_path, dpi=130)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
