#!/usr/bin/python3
"""Plot `grip bench trial`'s CSV: per arm, the median seconds of a trial per solver stage as a
stacked bar (left), and the same as shares of their sum (right, so that cheap arms read too).
Medians as trial.md takes them: each candidate's over its repeats at the defaults, then over the
arm's candidates. Writes trial.png into OUT_DIR.
Usage: plot_trial.py trial.csv OUT_DIR (Debian: python3-matplotlib)."""
import csv
import os
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STAGES = ["broad_phase", "derivatives", "assembly", "factorization", "solve", "ccd",
          "line_search", "friction_lag", "diagnostics", "other"]
LABELS = ["broad phase", "derivatives", "assembly", "factorization", "solve", "CCD",
          "line search", "friction lag", "diagnostics", "protocol and other"]


def arm_medians(rows):
    """{arm: [median seconds per stage]}, arms in the CSV's order."""
    by_candidate = {}
    for r in rows:
        if r["settings"] != "defaults":
            continue
        key = (r["category"], r["seed"], r["candidate"])
        by_candidate.setdefault(r["arm"], {}).setdefault(key, []).append(r)
    medians = {}
    for arm, candidates in by_candidate.items():
        per_candidate = [[statistics.median(float(r[s + "_s"]) for r in runs) for s in STAGES]
                         for runs in candidates.values()]
        medians[arm] = [statistics.median(c[i] for c in per_candidate)
                        for i in range(len(STAGES))]
    return medians


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1], newline="") as f:
        medians = arm_medians(list(csv.DictReader(f)))
    if not medians:
        sys.exit("no runs at the defaults in " + sys.argv[1])
    arms = list(medians)
    fig, (seconds_ax, share_ax) = plt.subplots(1, 2, figsize=(11, 4.5))
    colours = plt.get_cmap("tab10").colors
    seconds_bottom = [0.0] * len(arms)
    share_bottom = [0.0] * len(arms)
    for i, label in enumerate(LABELS):
        seconds = [medians[a][i] for a in arms]
        shares = [100 * medians[a][i] / (sum(medians[a]) or 1) for a in arms]
        seconds_ax.bar(arms, seconds, bottom=seconds_bottom, color=colours[i], label=label)
        share_ax.bar(arms, shares, bottom=share_bottom, color=colours[i])
        seconds_bottom = [b + s for b, s in zip(seconds_bottom, seconds)]
        share_bottom = [b + s for b, s in zip(share_bottom, shares)]
    seconds_ax.set_ylabel("median seconds per trial (one thread)")
    share_ax.set_ylabel("share of the trial (%)")
    for ax in (seconds_ax, share_ax):
        ax.tick_params(axis="x", labelrotation=20, labelsize=8)
        ax.grid(axis="y", alpha=0.3)
    seconds_ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(sys.argv[2], "trial.png"), dpi=120)


if __name__ == "__main__":
    main()
