#!/usr/bin/python3
"""Plot `grip bench labels`'s CSV: left, each candidate's slip over the verdict's threshold
(largest over the gravity phases: 1 mm plus eps_v x the time under gravity by the phase's end)
at the defaults against the reference, one colour per arm, 1 as lines (points in the
off-diagonal quadrants are verdicts that disagree; candidates that never reached the gravity test
are left out); right, the closing forces of the fingers in contact at the end of closing, per
arm. Writes labels.png into OUT_DIR.
Usage: plot_labels.py labels.csv OUT_DIR (Debian: python3-matplotlib)."""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def number(text):
    try:
        return float(text)
    except ValueError:
        return float("nan")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    threshold = 1.0  # slip over the verdict's threshold
    arms = []
    for r in rows:
        if r["arm"] not in arms:
            arms.append(r["arm"])
    fig, (slip_ax, force_ax) = plt.subplots(1, 2, figsize=(10, 4.2))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    forces = []
    for k, arm in enumerate(arms):
        mine = [r for r in rows if r["arm"] == arm]
        points = [(number(r["slip_ratio"]), number(r["slip_ratio_reference"])) for r in mine]
        points = [(a, b) for a, b in points if a == a and b == b]
        if points:
            slip_ax.scatter([max(a, 1e-4) for a, _ in points], [max(b, 1e-4) for _, b in points],
                            s=14, color=colours[k % len(colours)], label=arm)
        forces.append([float(f) for r in mine if r["closed"] == "1"
                       for f in r["closing_forces_n"].split() if float(f) > 0])
    slip_ax.axvline(threshold, color="grey", lw=0.8)
    slip_ax.axhline(threshold, color="grey", lw=0.8)
    slip_ax.set_xscale("log")
    slip_ax.set_yscale("log")
    # At least two decades either side of the threshold, so that the plot reads at a glance.
    slip_ax.set_xlim(left=min(slip_ax.get_xlim()[0], threshold / 100),
                     right=max(slip_ax.get_xlim()[1], threshold * 100))
    slip_ax.set_ylim(bottom=min(slip_ax.get_ylim()[0], threshold / 100),
                     top=max(slip_ax.get_ylim()[1], threshold * 100))
    slip_ax.set_xlabel("slip over the verdict's threshold, defaults")
    slip_ax.set_ylabel("slip over the verdict's threshold, reference")
    slip_ax.set_title("verdicts: the same on the diagonal quadrants", fontsize=10)
    slip_ax.legend(fontsize=7)
    slip_ax.grid(alpha=0.3, which="both")
    force_ax.hist(forces, bins=30, label=arms, color=colours[:len(arms)])
    force_ax.set_xlabel("closing force of a finger in contact (N)")
    force_ax.set_ylabel("fingers")
    force_ax.set_title("at the end of closing, defaults", fontsize=10)
    force_ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(sys.argv[2], "labels.png"), dpi=120)


if __name__ == "__main__":
    main()
