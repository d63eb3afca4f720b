#!/usr/bin/python3
"""Plot `grip bench peer`'s CSVs (one per gripper, or several grippers in one): left, mean D1
and D2 (cm) per gripper and engine, beside the paper's Table I (IPC and Isaac Gym, all objects);
right, per gripper and category, how many candidates the engines agree on and the two kinds of
disagreement. Writes peer.png into OUT_DIR.
Usage: plot_peer.py peer.csv [peer-leap.csv ...] OUT_DIR (Debian: python3-matplotlib)."""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# GRIP's Table I, all objects (cm): its IPC validator and Isaac Gym.
PAPER = [("paper: IPC", 0.0, 0.12), ("paper: Isaac Gym", 0.87, 1.19)]


def mean(values):
    values = [v for v in values if v == v]
    return sum(values) / len(values) if values else float("nan")


def number(text):
    try:
        return float(text)
    except ValueError:
        return float("nan")


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    rows = []
    for path in sys.argv[1:-1]:
        with open(path, newline="") as f:
            rows += list(csv.DictReader(f))
    out_dir = sys.argv[-1]
    grippers = []
    for r in rows:
        if r["gripper"] not in grippers:
            grippers.append(r["gripper"])

    fig, (d_ax, v_ax) = plt.subplots(1, 2, figsize=(12, 4.5))
    labels, d1, d2 = [], [], []
    for g in grippers:
        mine = [r for r in rows if r["gripper"] == g]
        for engine in ("grip", "mujoco"):
            labels.append(f"{g}: {'grip' if engine == 'grip' else 'MuJoCo'}")
            # D1/D2 of the grasps each engine keeps, as the paper's table (mm -> cm).
            kept = [r for r in mine if r[f"{engine}_verdict"] == "success"]
            d1.append(mean([number(r[f"{engine}_d1_mm"]) for r in kept]) / 10)
            d2.append(mean([number(r[f"{engine}_d2_mm"]) for r in kept]) / 10)
    for name, p1, p2 in PAPER:
        labels.append(name)
        d1.append(p1)
        d2.append(p2)
    x = range(len(labels))
    d_ax.bar([i - 0.2 for i in x], d1, width=0.4, label="D1 (penetration)")
    d_ax.bar([i + 0.2 for i in x], d2, width=0.4, label="D2 (distance)")
    d_ax.set_xticks(list(x))
    d_ax.set_xticklabels(labels, rotation=30, ha="right", fontsize=8)
    d_ax.set_ylabel("mean over held grasps (cm)")
    d_ax.set_title("D1 and D2, beside GRIP's Table I")
    d_ax.legend(fontsize=8)

    groups, same, mujoco_only, grip_only = [], [], [], []
    for g in grippers:
        categories = []
        for r in rows:
            if r["gripper"] == g and r["category"] not in categories:
                categories.append(r["category"])
        for c in categories:
            mine = [r for r in rows if r["gripper"] == g and r["category"] == c]
            held = [(r["grip_verdict"] == "success", r["mujoco_verdict"] == "success") for r in mine]
            groups.append(f"{g}: {c}")
            same.append(sum(a == b for a, b in held))
            mujoco_only.append(sum(b and not a for a, b in held))
            grip_only.append(sum(a and not b for a, b in held))
    y = range(len(groups))
    v_ax.barh(list(y), same, label="same verdict")
    v_ax.barh(list(y), grip_only, left=same, label="grip holds, MuJoCo drops")
    v_ax.barh(list(y), mujoco_only, left=[s + g for s, g in zip(same, grip_only)],
              label="MuJoCo holds, grip drops")
    v_ax.set_yticks(list(y))
    v_ax.set_yticklabels(groups, fontsize=8)
    v_ax.invert_yaxis()
    v_ax.set_xlabel("candidates")
    v_ax.set_title("verdicts per category")
    v_ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.4, -0.12), ncol=3)

    fig.tight_layout()
    out = os.path.join(out_dir, "peer.png")
    fig.savefig(out, dpi=110)
    print(out)


if __name__ == "__main__":
    main()
