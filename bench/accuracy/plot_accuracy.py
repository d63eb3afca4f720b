#!/usr/bin/python3
"""Plot `grip bench accuracy`'s CSV: the object's pose error in the gripper frame against the
cost of a run, one panel per swept setting, one line per scene, each point labelled with its
value and the default marked by a star. Writes accuracy.png (against CPU time) and
accuracy_iterations.png (against Newton iterations) into OUT_DIR. Zero errors (the mesh sweep's
own finest mesh) cannot sit on the log axis and are left out.
Usage: plot_accuracy.py accuracy.csv OUT_DIR (Debian: python3-matplotlib)."""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FormatStrFormatter, LogFormatter  # noqa: E402


def plot(rows, cost_key, cost_label, png_path):
    sweeps = []
    for r in rows:
        if r["sweep"] != "reference" and r["sweep"] not in sweeps:
            sweeps.append(r["sweep"])
    scenes = []
    for r in rows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    columns = min(4, len(sweeps))
    lines = math.ceil(len(sweeps) / columns)
    fig, axes = plt.subplots(lines, columns, figsize=(3.6 * columns, 3.2 * lines), squeeze=False)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for ax, sweep in zip(axes.flat, sweeps):
        for k, scene in enumerate(scenes):
            mine = [r for r in rows if r["scene"] == scene and r["sweep"] == sweep
                    and float(r["translation"]) > 0]
            mine.sort(key=lambda r: float(r[cost_key]))
            if not mine:
                continue
            x = [float(r[cost_key]) for r in mine]
            y = [float(r["translation"]) * 1e3 for r in mine]
            colour = colours[k % len(colours)]
            ax.plot(x, y, "o-", color=colour, ms=4, label=scene)
            for r, xi, yi in zip(mine, x, y):
                if r["default"] == "1":
                    ax.plot(xi, yi, "*", color=colour, ms=13, mec="black", mew=0.6)
                ax.annotate(f"{float(r['value']):g}", (xi, yi), fontsize=6,
                            textcoords="offset points", xytext=(3, 3))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(sweep, fontsize=10)
        ax.set_xlabel(cost_label, fontsize=8)
        ax.set_ylabel("pose error (mm)", fontsize=8)
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_major_formatter(FormatStrFormatter("%g"))
            # Minor ticks labelled only where an axis spans less than about a decade.
            axis.set_minor_formatter(LogFormatter(labelOnlyBase=False))
        ax.tick_params(labelsize=7)
        ax.grid(alpha=0.3, which="both")
    for ax in list(axes.flat)[len(sweeps):]:
        ax.axis("off")
    handles, labels = axes.flat[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower right", fontsize=8,
               title="star: default", title_fontsize=8)
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


def main(csv_path, out_dir):
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    plot(rows, "cpu_seconds", "CPU time of the trials (s)", os.path.join(out_dir, "accuracy.png"))
    plot(rows, "newton_iterations", "Newton iterations",
         os.path.join(out_dir, "accuracy_iterations.png"))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
