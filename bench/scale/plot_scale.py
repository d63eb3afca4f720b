#!/usr/bin/python3
"""Plot `grip bench scale`'s CSV: the predicted parallel efficiency against MPI ranks, one line
per scenario (the farm's protocol and each what-if), and where the farm's rank-seconds of the
trial phase go (trials, claims, idle waiting for others, commits).
Usage: plot_scale.py scale.csv scale.png (Debian: python3-matplotlib)."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(csv_path, png_path):
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    scenarios = list(dict.fromkeys(r["scenario"] for r in rows))
    fig, (eff_ax, share_ax) = plt.subplots(1, 2, figsize=(10, 3.8))
    for scenario in scenarios:
        mine = [r for r in rows if r["scenario"] == scenario]
        eff_ax.plot([int(r["ranks"]) for r in mine], [100 * float(r["efficiency"]) for r in mine],
                    "o-", label=scenario)
    eff_ax.axhline(90, color="k", ls="--", lw=0.8)
    eff_ax.set_xscale("log", base=2)
    eff_ax.set_xlabel("MPI ranks (one core each)")
    eff_ax.set_ylabel("parallel efficiency (%)")
    eff_ax.set_title("predicted efficiency")
    eff_ax.grid(alpha=0.3)
    eff_ax.legend(fontsize=8, loc="lower left")

    farm = [r for r in rows if r["scenario"] == scenarios[0]]
    ranks = [int(r["ranks"]) for r in farm]
    bottom = [0.0] * len(farm)
    labels = (("work_share", "trials"), ("claim_share", "claims"),
              ("idle_share", "idle (waiting for others)"), ("commit_share", "commits"))
    for key, label in labels:
        share = [100 * float(r[key]) for r in farm]
        share_ax.bar(range(len(farm)), share, bottom=bottom, label=label)
        bottom = [b + s for b, s in zip(bottom, share)]
    share_ax.set_xticks(range(len(farm)))
    share_ax.set_xticklabels([str(r) for r in ranks])
    share_ax.set_xlabel("MPI ranks")
    share_ax.set_ylabel("% of rank-seconds, trial phase")
    share_ax.set_title(f"where the time goes ({scenarios[0]})")
    share_ax.legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    fig.savefig(png_path, dpi=120)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
