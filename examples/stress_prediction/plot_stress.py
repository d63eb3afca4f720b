#!/usr/bin/python3
"""Draws predicted against simulated stress on one held-out grasp of a train.py run: two 3-D
scatter panels of the object's points at the settled grasp, coloured on one colour scale.

Usage: /usr/bin/python3 examples/stress_prediction/plot_stress.py --run DIR [--candidate ID]
           [--dataset DATASET.h5] [--out FILE.png]

DIR is train.py's --out (model.pt, metrics.json); without --candidate the first test grasp;
the dataset is the run's unless --dataset names another (the file moved). Writes DIR/stress.png
unless --out says otherwise.
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)
import torch  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from grip_dataset import GraspStressDataset  # noqa: E402
from metrics import grasp_metrics  # noqa: E402
from model import StressNet  # noqa: E402
from train import predict  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--run", required=True, help="train.py's output folder")
    parser.add_argument("--candidate", type=int, help="candidate id (default: first test grasp)")
    parser.add_argument("--dataset", help="the dataset (default: the run's)")
    parser.add_argument("--out", help="PNG to write (default: RUN/stress.png)")
    args = parser.parse_args()
    with open(os.path.join(args.run, "metrics.json"), encoding="utf-8") as f:
        run = json.load(f)
    candidate = run["grasps"][0]["candidate"] if args.candidate is None else args.candidate
    dataset = GraspStressDataset(args.dataset or run["dataset"])
    index = next((i for i, row in enumerate(dataset.rows) if row == candidate), None)
    if index is None:
        sys.exit(f"{dataset.path}: no candidate {candidate} with frames")
    saved = torch.load(os.path.join(args.run, "model.pt"))
    net = StressNet(width=saved["width"])
    net.load_state_dict(saved["state"])
    net.eval()
    item = dataset[index]
    predicted, simulated = predict(net, item).numpy(), item["stress"].numpy()
    values = grasp_metrics(predicted, simulated)

    points = item["object_vertices"].numpy()
    top = max(predicted.max(), simulated.max()) / 1e3
    figure = plt.figure(figsize=(10, 4.6))
    for k, (title, stress) in enumerate((("simulated", simulated), ("predicted", predicted))):
        axes = figure.add_subplot(1, 2, k + 1, projection="3d")
        dots = axes.scatter(*points.T, c=stress / 1e3, cmap="viridis", vmin=0, vmax=top, s=6)
        axes.set_title(f"{title} von Mises stress")
        axes.set_box_aspect(points.max(0) - points.min(0))
        axes.set_axis_off()
    figure.colorbar(dots, ax=figure.axes, shrink=0.7, label="kPa")
    figure.suptitle(f"candidate {candidate} ({item['object_name']}, {item['gripper_name']}): "
                    f"relative MAE {100 * values['relative_mae']:.1f} %, KL {values['kl']:.3f}")
    out = args.out or os.path.join(args.run, "stress.png")
    figure.savefig(out, dpi=90)
    print(f"candidate {candidate} drawn to {out}")


if __name__ == "__main__":
    main()
