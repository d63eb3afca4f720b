#!/usr/bin/python3
"""Trains StressNet (model.py) on the soft objects' settled grasps of a grip dataset and
reports the paper's metrics (relative MAE, KL; metrics.py) per category on held-out objects.

Usage: /usr/bin/python3 examples/stress_prediction/train.py --dataset DATASET.h5 --out DIR
           [--categories bowl mug] [--test-per-category 2] [--epochs 50] [--steps S]
           [--seed 0] [--threads 1]

The last --test-per-category objects of each category (by object index) are held out; the
net trains on the successful grasps of the others. Writes to DIR: metrics.json (per category
and per test grasp, the loss of every step, wall times), metrics.md (the table beside the
paper's values and a constant field's: the training mean stress everywhere, what a net that
learnt nothing of the grasp scores), model.pt (weights and the net's settings). Deterministic
for a seed on CPU.
"""
import argparse
import json
import os
import sys
import time

import numpy as np
import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from grip_dataset import OBJECT_KEYS, GraspStressDataset, collate_padded  # noqa: E402
from metrics import by_category, grasp_metrics  # noqa: E402
from model import StressNet, stress_to_target, target_to_stress  # noqa: E402

# GRIP paper, Section V-D: relative MAE and KL of its stress predictor, bowl and mug.
PAPER = {"bowl": {"relative_mae": 0.089, "kl": 0.11}, "mug": {"relative_mae": 0.072, "kl": 0.18}}
METRICS = ("relative_mae", "kl", "constant_relative_mae", "constant_kl")


def arguments(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--dataset", required=True, help="a grip dataset (HDF5)")
    parser.add_argument("--out", required=True, help="folder for metrics and weights")
    parser.add_argument("--categories", nargs="+", help="object categories (default: all)")
    parser.add_argument("--test-per-category", type=int, default=2,
                        help="held-out objects per category, the last by object index")
    parser.add_argument("--epochs", type=int, default=50)
    parser.add_argument("--steps", type=int, help="stop after this many steps (a cap)")
    parser.add_argument("--batch", type=int, default=4, help="grasps per step")
    parser.add_argument("--points", type=int, default=2048,
                        help="object points per grasp per training step (a random subset)")
    parser.add_argument("--lr", type=float, default=1e-3)
    parser.add_argument("--width", type=int, default=64, help="feature width of the net")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--threads", type=int, default=1, help="torch.set_num_threads")
    parser.add_argument("--workers", type=int, default=0, help="DataLoader worker processes")
    return parser.parse_args(argv)


def split(dataset, test_per_category):
    """(train indices, test indices): the last objects of each category are the test's."""
    objects = {}
    for i in range(len(dataset)):
        objects.setdefault(dataset.category(i), set()).add(int(dataset.row_objects[i]))
    held_out = set()
    for category, members in sorted(objects.items()):
        held_out |= set(sorted(members)[-test_per_category:] if test_per_category > 0 else [])
        if len(members) <= test_per_category:
            print(f"warning: {category} has {len(members)} objects with grasps, all held out")
    test = [i for i in range(len(dataset)) if int(dataset.row_objects[i]) in held_out]
    train = [i for i in range(len(dataset)) if int(dataset.row_objects[i]) not in held_out]
    return train, test


def subsample(item, count, generator):
    """The item with at most `count` of its object points, drawn at random."""
    n = item["object_vertices"].shape[0]
    if n <= count:
        return item
    keep = torch.randperm(n, generator=generator)[:count]
    return {k: (v[keep] if k in OBJECT_KEYS else v) for k, v in item.items()}


def loss_of(net, batch):
    prediction = net(batch["object_vertices"], batch["object_mask"],
                     batch["gripper_vertices"], batch["gripper_mask"])
    error = (prediction - stress_to_target(batch["stress"])) ** 2
    mask = batch["object_mask"].float()
    return (error * mask).sum() / mask.sum()


def train(net, dataset, indices, args):
    """Adam on the masked squared error in log scale; returns every step's loss and the mean
    stress of the points trained on (the constant baseline's prediction)."""
    generator = torch.Generator().manual_seed(args.seed)
    loader = torch.utils.data.DataLoader(
        torch.utils.data.Subset(dataset, indices), batch_size=args.batch, shuffle=True,
        generator=generator, collate_fn=list, num_workers=args.workers)
    optimizer = torch.optim.Adam(net.parameters(), lr=args.lr)
    losses, stress_sum, points = [], 0.0, 0
    for _ in range(args.epochs):
        for items in loader:
            if args.steps is not None and len(losses) >= args.steps:
                return losses, stress_sum / points
            batch = collate_padded([subsample(item, args.points, generator) for item in items])
            stress_sum += float(batch["stress"][batch["object_mask"]].sum())
            points += int(batch["object_mask"].sum())
            loss = loss_of(net, batch)
            optimizer.zero_grad()
            loss.backward()
            optimizer.step()
            losses.append(float(loss))
    return losses, stress_sum / points


@torch.no_grad()
def predict(net, item):
    """Predicted stress (Pa) at every object point of one item."""
    points, grip = item["object_vertices"][None], item["gripper_vertices"][None]
    target = net(points, torch.ones(points.shape[:2], dtype=torch.bool),
                 grip, torch.ones(grip.shape[:2], dtype=torch.bool))
    return target_to_stress(target[0])


def evaluate(net, dataset, indices, constant):
    """Per test grasp: the net's metrics, and a constant field's (the training mean: what a
    net that learnt nothing of the grasp would score)."""
    net.eval()
    grasps = []
    for i in indices:
        item = dataset[i]
        simulated = item["stress"].numpy()
        values = grasp_metrics(predict(net, item).numpy(), simulated)
        baseline = grasp_metrics(np.full_like(simulated, constant), simulated)
        grasps.append({"candidate": int(item["candidate"]), "object": int(item["object"]),
                       "category": item["category"], **values,
                       **{f"constant_{k}": v for k, v in baseline.items()}})
    return grasps


def table(summary):
    """Markdown: each category's means beside the paper's values."""
    def paper(category, name):
        value = PAPER.get(category, {}).get(name)
        if value is None:
            return "-"
        return f"{100 * value:.1f} %" if name == "relative_mae" else f"{value:.2f}"

    lines = ["| category | test grasps | relative MAE | paper | KL | paper | "
             "constant field: relative MAE | KL |", "| --- " * 8 + "|"]
    for category, row in summary.items():
        lines.append(f"| {category} | {row['grasps']} | {100 * row['relative_mae']:.1f} % | "
                     f"{paper(category, 'relative_mae')} | {row['kl']:.3f} | "
                     f"{paper(category, 'kl')} | {100 * row['constant_relative_mae']:.1f} % | "
                     f"{row['constant_kl']:.3f} |")
    return "\n".join(lines) + "\n"


def main(argv=None):
    args = arguments(argv)
    torch.manual_seed(args.seed)
    torch.set_num_threads(args.threads)
    torch.use_deterministic_algorithms(True)
    dataset = GraspStressDataset(args.dataset, successes_only=True, soft_only=True,
                                 categories=args.categories)
    train_indices, test_indices = split(dataset, args.test_per_category)
    if not train_indices or not test_indices:
        sys.exit(f"{args.dataset}: {len(train_indices)} training and {len(test_indices)} test "
                 "grasps; both need at least one (soft objects' successful grasps)")
    net = StressNet(width=args.width)
    start = time.perf_counter()
    losses, mean_stress = train(net, dataset, train_indices, args)
    train_seconds = time.perf_counter() - start
    grasps = evaluate(net, dataset, test_indices, mean_stress)
    summary = by_category([(g["category"], {k: g[k] for k in METRICS}) for g in grasps])
    os.makedirs(args.out, exist_ok=True)
    torch.save({"state": net.state_dict(), "width": args.width},
               os.path.join(args.out, "model.pt"))
    report = {"dataset": os.path.abspath(args.dataset), "arguments": vars(args),
              "train_grasps": len(train_indices), "test_grasps": len(test_indices),
              "steps": len(losses), "train_seconds": train_seconds,
              "categories": summary, "paper": PAPER, "grasps": grasps, "losses": losses}
    with open(os.path.join(args.out, "metrics.json"), "w", encoding="utf-8") as f:
        json.dump(report, f, indent=1)
    with open(os.path.join(args.out, "metrics.md"), "w", encoding="utf-8") as f:
        f.write(table(summary))
    print(f"{len(train_indices)} training grasps, {len(losses)} steps in {train_seconds:.1f} s "
          f"(loss {losses[0]:.4f} -> {np.mean(losses[-3:]):.4f}); "
          f"{len(test_indices)} test grasps")
    print(table(summary), end="")
    return report


if __name__ == "__main__":
    main()
