#!/usr/bin/python3
"""examples/stress_prediction on a dataset a tiny farm job makes: two soft capsules, one
fin-ray candidate each. The loader gives one item per committed candidate with the settled
frame and the volume-weighted vertex stress, refuses old format versions and reads the
gripper-side forces a later version adds; train.py's loss falls over a few steps, the same on
a second run with the same seed, its metrics are finite, and plot_stress.py draws a PNG.

  test_stress_training.py GRIP_EXECUTABLE SOURCE_DIR

Exit 77 (skipped) when Debian's Python lacks torch (python3-torch), h5py or numpy.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

JOB = """[job]
name = "stress"
seed = 4

[[objects]]
category = "capsule"
count = 2
soft = true
tet_edge = 0.012

[[grippers]]
name = "fin-ray"
candidates = 1

[randomization]
scale = [0.5, 0.6]

[trial]
metric_samples = 2000

[outputs]
closing_frames = 4
validation_frames = 6
"""


def fail(message):
    print(f"FAIL: {message}")
    sys.exit(1)


def check_loader(dataset_path, folder):
    import h5py
    import numpy as np
    import torch
    from grip_dataset import GraspStressDataset, collate_padded

    dataset = GraspStressDataset(dataset_path)
    with h5py.File(dataset_path, "r") as f:
        table = f["candidates"]
        done = int((table["done"][:] == 1).sum())
        if len(dataset) != done or done != 2:
            fail(f"{len(dataset)} items, {done} committed candidates (2 planned)")
        item = dataset[1]
        row, obj = int(item["candidate"]), int(item["object"])
        group = f[f"objects/{obj:06d}"]
        frames = group["trajectories/000"]
        settled = (int(table["frame_slot"][row]), int(f.attrs["closing_frames"]) - 1)
        if not np.array_equal(item["object_vertices"].numpy(), frames["object_vertices"][settled]):
            fail("object_vertices are not the settled frame's")
        if not np.array_equal(item["gripper_vertices"].numpy(),
                              frames["gripper_vertices"][settled]):
            fail("gripper_vertices are not the settled frame's")
        # One vertex's stress by hand: the volume-weighted mean over the tets that hold it.
        tets, rest = group["tets"][:], group["vertices"][:]
        tet_stress = group["stress"][int(table["stress_slot"][row])]
        vertex = int(np.argmax(item["stress"].numpy()))
        weighted = total = 0.0
        for t, corners in enumerate(tets):
            if vertex in corners:
                p = rest[corners]
                volume = abs(np.linalg.det((p[1:] - p[0]).T)) / 6
                weighted, total = weighted + volume * tet_stress[t], total + volume
        if not abs(item["stress"][vertex] - weighted / total) <= 1e-4 * weighted / total:
            fail(f"vertex {vertex}: stress {float(item['stress'][vertex])}, by hand "
                 f"{weighted / total}")
    if item["category"] != "capsule" or not bool(item["has_stress"]) or item["stress"].max() <= 0:
        fail(f"item 1: category {item['category']}, has_stress {bool(item['has_stress'])}")
    if len(GraspStressDataset(dataset_path, categories=["mug"])) != 0 or \
            len(GraspStressDataset(dataset_path, objects=[1])) != 1:
        fail("the category and object filters keep the wrong items")
    batch = collate_padded([dataset[0], dataset[1]])
    sizes = [len(dataset[i]["object_vertices"]) for i in (0, 1)]
    if batch["object_vertices"].shape != (2, max(sizes), 3) or \
            batch["object_mask"].sum(1).tolist() != sizes:
        fail(f"padded batch {tuple(batch['object_vertices'].shape)} for {sizes} points")

    # A file of format version 7 is refused; grip's own (9) has the gripper-side forces in its
    # items: at the settled grasp the fingers press on the object, equal and opposite to it.
    copy = os.path.join(folder, "copy.h5")
    shutil.copy(dataset_path, copy)
    with h5py.File(copy, "r+") as f:
        f.attrs["format_version"] = np.uint64(7)
    try:
        GraspStressDataset(copy)
        fail("format version 7 was not refused")
    except ValueError as error:
        print(f"refused: {error}")
    item = dataset[0]
    if item.get("gripper_contact_forces") is None:
        fail("the gripper-side forces of a format 9 file are not in its items")
    gripper_total = item["gripper_contact_forces"].double().sum(0)
    object_total = item["contact_forces"].double().sum(0)
    finger_push = item["gripper_contact_forces"].double().norm(dim=1).sum()
    if finger_push < 1.0 or (gripper_total + object_total).norm() > 1e-3 * finger_push:
        fail(f"gripper forces {gripper_total.tolist()} do not balance the object's "
             f"{object_total.tolist()}")
    # Format 10 on: the soft fingers' stress row of the candidate, as the file holds it.
    with h5py.File(dataset_path, "r") as f:
        table, gripper = f["candidates"], f["grippers"]["000"]
        row = int(item["candidate"])
        stored = gripper["finger_stress"][table["finger_stress_slot"][row]]
    if not item["has_finger_stress"] or not np.array_equal(item["finger_stress"].numpy(), stored) \
            or not stored.max() > 0:
        fail(f"finger stress of candidate {row} is not the file's row (max {stored.max():.3g} Pa)")
    if batch["finger_stress"].shape != (2, len(stored)) or not batch["finger_mask"].all():
        fail(f"batched finger stress {tuple(batch['finger_stress'].shape)}")
    print(f"loader: {len(dataset)} items, settled frames, vertex stress checked by hand")


def main():
    grip, source = sys.argv[1], sys.argv[2]
    try:
        import h5py  # noqa: F401
        import numpy  # noqa: F401
        import torch  # noqa: F401
    except ImportError as error:
        print(f"skipped: {error} (Debian: python3-torch, python3-h5py, python3-numpy)")
        return 77
    example = os.path.join(source, "examples", "stress_prediction")
    sys.dont_write_bytecode = True  # nothing left in examples/
    sys.path.insert(0, example)
    with tempfile.TemporaryDirectory() as folder:
        job, dataset = os.path.join(folder, "job.toml"), os.path.join(folder, "stress.h5")
        with open(job, "w", encoding="utf-8") as f:
            f.write(JOB)
        start = time.perf_counter()
        farm = subprocess.run([grip, "-q", "farm", job, "--output", dataset, "--threads", "1"],
                              capture_output=True, text=True, check=False)
        if farm.returncode != 0:
            fail(f"grip farm exit {farm.returncode}: {farm.stderr}")
        print(f"dataset made in {time.perf_counter() - start:.1f} s")
        check_loader(dataset, folder)

        import train
        runs = []
        for k in (1, 2):
            out = os.path.join(folder, f"run{k}")
            runs.append(train.main(["--dataset", dataset, "--out", out, "--test-per-category",
                                    "1", "--steps", "10", "--batch", "1", "--epochs", "100",
                                    "--seed", "3"]))
        losses = runs[0]["losses"]
        if len(losses) != 10 or not sum(losses[-3:]) / 3 < losses[0]:
            fail(f"the loss did not fall: {losses}")
        if runs[1]["losses"] != losses:
            fail(f"a second run with the same seed differs: {runs[1]['losses']} vs {losses}")
        row = runs[0]["categories"].get("capsule", {})
        if row.get("grasps") != 1 or not 0 <= row["relative_mae"] < 10 or not 0 <= row["kl"] < 10:
            fail(f"metrics of the test grasp: {row}")
        with open(os.path.join(folder, "run1", "metrics.json"), encoding="utf-8") as f:
            if json.load(f)["categories"] != runs[0]["categories"]:
                fail("metrics.json differs from what train.py returned")
        with open(os.path.join(folder, "run1", "metrics.md"), encoding="utf-8") as f:
            if "| capsule | 1 |" not in f.read():
                fail("metrics.md has no capsule row")
        print(f"loss {losses[0]:.3f} -> {sum(losses[-3:]) / 3:.3f}, same on a second run")

        png = os.path.join(folder, "stress.png")
        plot = subprocess.run([sys.executable, "-B", os.path.join(example, "plot_stress.py"),
                               "--run", os.path.join(folder, "run1"), "--out", png],
                              capture_output=True, text=True, check=False)
        if plot.returncode != 0 or not os.path.exists(png):
            fail(f"plot_stress.py: exit {plot.returncode}\n{plot.stdout}{plot.stderr}")
        with open(png, "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                fail(f"{png} is not a PNG file")
        print(plot.stdout.strip())
    return 0


if __name__ == "__main__":
    sys.exit(main())
