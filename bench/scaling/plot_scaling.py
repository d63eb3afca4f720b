#!/usr/bin/python3
"""Plot `grip bench scaling`'s CSV: trials per second and speedup against MPI ranks, one line
per batch-size setting (envs; 0 is the farm's default, which grows with the threads per rank).
The ideal speedup is the ratio of cores used (ranks x threads per rank).
Usage: plot_scaling.py scaling.csv scaling.png (Debian: python3-matplotlib)."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(csv_path, png_path):
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    settings = sorted({int(r["envs"]) for r in rows})
    fig, (rate_ax, speed_ax) = plt.subplots(1, 2, figsize=(9, 3.6))
    for envs in settings:
        mine = sorted((r for r in rows if int(r["envs"]) == envs), key=lambda r: int(r["ranks"]))
        ranks = [int(r["ranks"]) for r in mine]
        label = "default batch" if envs == 0 else f"batch {envs}"
        rate_ax.plot(ranks, [float(r["trials_per_second"]) for r in mine], "o-", label=label)
        speed_ax.plot(ranks, [float(r["speedup"]) for r in mine], "o-", label=label)
        for r in mine:
            rate_ax.annotate(f"{r['ranks']}x{r['threads']}, b{r['batch']}",
                             (int(r["ranks"]), float(r["trials_per_second"])), fontsize=7,
                             textcoords="offset points", xytext=(4, 4))
    all_ranks = sorted({int(r["ranks"]) for r in rows})
    first = rows[0]
    cores0 = int(first["ranks"]) * int(first["threads"])
    ideal = sorted({(int(r["ranks"]), int(r["ranks"]) * int(r["threads"]) / cores0) for r in rows})
    speed_ax.plot([x for x, _ in ideal], [y for _, y in ideal], "k--", lw=0.8,
                  label="ideal (cores used)")
    for ax, title in ((rate_ax, "trials per second"), (speed_ax, "speedup")):
        ax.set_xlabel("MPI ranks")
        ax.set_xticks(all_ranks)
        ax.set_title(title)
        ax.grid(alpha=0.3)
    speed_ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png_path, dpi=120)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
