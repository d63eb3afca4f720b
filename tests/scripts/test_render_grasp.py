#!/usr/bin/python3
"""examples/render_grasp.py on a dataset a tiny farm job makes: a soft capsule and a rigid
cylinder, one candidate each. Each record is drawn to a valid PNG of the expected size, an
unknown record is refused, and the script's von Mises formula gives the stress the trial
stored at the settled grasp. A second job grasps the cylinder with the soft fin-ray: its
settled fingers are coloured by their stored stress, every surface triangle by a finger tet.

  test_render_grasp.py GRIP_EXECUTABLE SOURCE_DIR

Exit 77 (skipped) when Debian's Python lacks matplotlib, h5py or numpy, except under CI (the
CI variable set), where scripts/install-deps.sh has installed them and their absence fails.
"""
import os
import struct
import subprocess
import sys
import tempfile

JOB = """[job]
name = "render"
seed = 4

[[objects]]
category = "capsule"
soft = true
tet_edge = 0.012

[[objects]]
category = "cylinder"

[[grippers]]
name = "parallel-jaw"
candidates = 1

[randomization]
scale = [0.5, 0.6]

[trial]
metric_samples = 2000

[outputs]
closing_frames = 4
validation_frames = 6
"""

FIN_RAY_JOB = JOB.replace('category = "capsule"\nsoft = true\ntet_edge = 0.012\n\n[[objects]]\n',
                          "").replace('"parallel-jaw"', '"fin-ray"')


def fail(message):
    print(f"FAIL: {message}")
    sys.exit(1)


def png_size(path):
    """(width, height) of a PNG file, or fails the test."""
    with open(path, "rb") as f:
        head = f.read(24)
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        fail(f"{path} is not a PNG file")
    return struct.unpack(">II", head[16:24])


def render(script, *args):
    return subprocess.run(["/usr/bin/python3", script, *args], capture_output=True, text=True,
                          check=False)


def main():
    grip, source = sys.argv[1], sys.argv[2]
    try:
        import h5py
        import matplotlib  # noqa: F401
        import numpy as np
    except ImportError as error:
        if os.environ.get("CI"):
            fail(f"{error}; scripts/install-deps.sh installs python3-matplotlib, -h5py, -numpy")
        print(f"skipped: {error}")
        return 77
    script = os.path.join(source, "examples", "render_grasp.py")
    with tempfile.TemporaryDirectory() as folder:
        job, dataset = os.path.join(folder, "job.toml"), os.path.join(folder, "render.h5")
        with open(job, "w", encoding="utf-8") as f:
            f.write(JOB)
        farm = subprocess.run([grip, "-q", "farm", job, "--output", dataset, "--threads", "1"],
                              capture_output=True, text=True, check=False)
        if farm.returncode != 0:
            fail(f"grip farm exit {farm.returncode}: {farm.stderr}")

        listed = render(script, dataset, "--list")
        rows = listed.stdout.splitlines()
        if listed.returncode != 0 or len(rows) != 2 or "stress" not in rows[0]:
            fail(f"--list: exit {listed.returncode}, printed\n{listed.stdout}{listed.stderr}")

        for record in (None, "0", "1"):
            out = os.path.join(folder, f"grasp_{record}.png")
            args = [dataset, "--out", out] + (["--record", record] if record else [])
            run = render(script, *args)
            if run.returncode != 0 or "drawn to" not in run.stdout:
                fail(f"record {record}: exit {run.returncode}\n{run.stdout}{run.stderr}")
            if png_size(out) != (900, 440):
                fail(f"{out} is {png_size(out)} pixels, not 900 x 440")
            print(run.stdout.strip())

        refused = render(script, dataset, "--record", "7", "--out", os.path.join(folder, "x.png"))
        if refused.returncode == 0 or "no record 7" not in refused.stderr:
            fail(f"record 7 of 2 was not refused: {refused.stdout}{refused.stderr}")

        sys.dont_write_bytecode = True  # nothing left in examples/
        sys.path.insert(0, os.path.dirname(script))
        import render_grasp
        with h5py.File(dataset, "r") as f:
            obj, table = f["objects/000000"], f["candidates"]
            settled = int(f.attrs["closing_frames"]) - 1
            frames = obj["trajectories/000/object_vertices"]
            vertices = frames[table["frame_slot"][0], settled].astype(float)
            recomputed = render_grasp.von_mises(obj["vertices"][:], vertices, obj["tets"][:],
                                                obj.attrs["young_modulus"],
                                                obj.attrs["poisson_ratio"])
            stored = obj["stress"][table["stress_slot"][0]]
        difference = np.abs(recomputed - stored).max() / stored.max()
        if not stored.max() > 0 or not difference < 1e-3:
            fail(f"von Mises recomputed from the settled frame differs from the stored field "
                 f"by {difference:.2e} of its maximum {stored.max():.3g} Pa")
        print(f"von Mises at the settled grasp: within {difference:.1e} of the stored field")

        fin_ray_job, fin_ray = os.path.join(folder, "fin_ray.toml"), os.path.join(folder, "f.h5")
        with open(fin_ray_job, "w", encoding="utf-8") as f:
            f.write(FIN_RAY_JOB)
        farm = subprocess.run([grip, "-q", "farm", fin_ray_job, "--output", fin_ray, "--threads",
                               "1"], capture_output=True, text=True, check=False)
        if farm.returncode != 0:
            fail(f"grip farm (fin-ray) exit {farm.returncode}: {farm.stderr}")
        out = os.path.join(folder, "fin_ray.png")
        run = render(script, fin_ray, "--record", "0", "--out", out)
        if run.returncode != 0 or png_size(out) != (900, 440):
            fail(f"fin-ray record: exit {run.returncode}\n{run.stdout}{run.stderr}")
        with h5py.File(fin_ray, "r") as f:
            gripper, table = f["grippers/000"], f["candidates"]
            stored = gripper["finger_stress"][table["finger_stress_slot"][0]].astype(float)
            faces = render_grasp.finger_faces(gripper, stored)
        if not (np.isfinite(faces).all() and faces.max() > 0 and faces.max() <= stored.max()):
            fail(f"finger faces: {np.isfinite(faces).sum()} of {len(faces)} found a finger tet, "
                 f"largest {faces.max():.3g} Pa against the stored {stored.max():.3g} Pa")
        print(f"fin-ray fingers: {len(faces)} surface triangles coloured, peak "
              f"{faces.max() / 1e3:.0f} kPa")
    return 0


if __name__ == "__main__":
    sys.exit(main())
