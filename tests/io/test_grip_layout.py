#!/usr/bin/python3
"""`grip export --layout grip` read back with h5py: every key, shape and value of the exported
files against the grip dataset they came from, read the way GRIP's own reader reads its files.

usage: test_grip_layout.py GRIP DATASET.h5 WORK_FOLDER
"""
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np


def export(grip, dataset, folder, *extra):
    return subprocess.run([grip, "export", "--layout", "grip", dataset, folder, *extra],
                          capture_output=True, text=True)


def committed(src):
    """(object, gripper, id) of every committed candidate with a trajectory, and its status."""
    c = src["candidates"]
    rows = []
    for i in range(c["done"].shape[0]):
        if c["done"][i] and c["trajectory_written"][i] and c["frame_slot"][i] >= 0:
            rows.append((int(c["object"][i]), int(c["gripper"][i]), i, int(c["status"][i])))
    return rows


def read_like_grip(path, pose):
    """What GRIP's visualizer reads from one of its files, the same way."""
    with h5py.File(path, "r") as f:
        t = f["trajectories"]
        out = {"joints": t["finray_joint_states"][pose][:], "tf": t["finray_tf_states"][pose][:],
               "left": t["leftfinger_points"][pose][:], "right": t["rightfinger_points"][pose][:],
               "left_force": t["left_f_collisions"][pose, 0] + t["left_f_frictions"][pose, 0]}
        if f["object_config/object_type"][()] == b"rigid":
            out["object"] = t["object_vertices"][pose][:]
            out["faces"] = t["object_faces"][pose][:]
        else:
            out["object"] = t["object_points"][pose][:]
            out["cells"] = t["object_cells"][:]
        out["frames"] = t["left_f_collisions"][pose][:].shape[0]
        return out


def check_file(path, src, rows):
    """Checks one exported file against the source rows it must hold (id order)."""
    with h5py.File(path, "r") as f:
        obj_index, grip_index = rows[0][0], rows[0][1]
        o = src["objects/%06d" % obj_index]
        g = src["grippers/%03d" % grip_index]
        traj = o["trajectories/%03d" % grip_index]
        frames = int(src.attrs["closing_frames"] + src.attrs["validation_frames"])
        hands = int(g.attrs["hands"])
        parallel = g.attrs["kind"] == b"parallel"
        soft = bool(o.attrs["soft"])
        P = len(rows)
        ids = [r[2] for r in rows]
        cfg = f["object_config"]
        assert cfg["object_type"][()] == (b"soft" if soft else b"rigid"), cfg["object_type"][()]
        assert cfg["object_category"][()] == o.attrs["category"]
        for key, attr in [("object_density", "density"), ("object_youngs", "young_modulus"),
                          ("object_poisson", "poisson_ratio"), ("object_fric", "friction")]:
            assert cfg[key][()] == o.attrs[attr], key
        assert np.isnan(cfg["ground_fric"][()])
        t = f["trajectories"]
        assert list(t["candidate_id"][:]) == ids
        status = [r[3] for r in rows]
        assert list(t["success"][:]) == [1 if s == 1 else 0 for s in status]
        slots = [int(src["candidates/frame_slot"][i]) for i in ids]
        per_hand = g["vertices"].shape[0] // hands
        prefix = "finray" if parallel else g.attrs["name"].decode().replace("_", "-")
        hand_axis = (hands,) if hands > 1 else ()
        joints = traj["joints"][slots]  # (P, F, hands, J)
        poses = traj["hand_poses"][slots]  # (P, F, hands, 3, 4)
        js = t[prefix + "_joint_states"][:]
        tf = t[prefix + "_tf_states"][:]
        assert tf.shape == (P, frames) + hand_axis + (4, 4), tf.shape
        tf = tf.reshape(P, frames, hands, 4, 4)
        assert np.array_equal(tf[..., :3, :], poses)
        assert np.all(tf[..., 3, :] == [0, 0, 0, 1])
        assert np.array_equal(t["hand_translation"][:].reshape(P, frames, hands, 3), poses[..., 3])
        assert np.array_equal(t["hand_rotation"][:].reshape(P, frames, hands, 3, 3),
                              poses[..., :3])
        if parallel:
            assert js.shape == (P, frames) + hand_axis + (3,), js.shape
            js = js.reshape(P, frames, hands, 3)
            assert np.all(js[..., 0] == 0)
            assert np.array_equal(js[..., 1], joints[..., 0] / 2)
            assert np.array_equal(js[..., 2], joints[..., 0] / 2)
            half = per_hand // 2
            parts = [("leftfinger", "left", 0, half), ("rightfinger", "right", half, half)]
        else:
            assert js.shape == (P, frames) + hand_axis + (joints.shape[-1],), js.shape
            assert np.array_equal(js.reshape(joints.shape), joints)
            parts = [("hand", "hand", 0, per_hand)]
        gv = traj["gripper_vertices"][slots].reshape(P, frames, hands, per_hand, 3)
        gc = traj["gripper_contact_forces"][slots].reshape(P, frames, hands, per_hand, 3)
        gf = traj["gripper_friction_forces"][slots].reshape(P, frames, hands, per_hand, 3)
        triangles = g["triangles"][:]
        for name, side, first, count in parts:
            for key, source in [(name + "_points", gv), (side + "_f_collisions", gc),
                                (side + "_f_frictions", gf)]:
                a = t[key][:]
                assert a.shape == (P, frames) + hand_axis + (count, 3), (key, a.shape)
                expected = source[:, :, :, first:first + count]
                assert np.array_equal(a.reshape(expected.shape), expected), key
            faces = t[name + "_faces"][:]
            mine = [tri - first for tri in triangles if all(first <= v < first + count for v in tri)]
            assert faces.shape == (P,) + hand_axis + (len(mine), 3), (name, faces.shape)
            for p in range(P):
                first_hand = faces[p] if hands == 1 else faces[p, 0]
                assert np.array_equal(first_hand, np.array(mine).reshape(-1, 3))
        n = o["vertices"].shape[0]
        points = "object_points" if soft else "object_vertices"
        for key, source in [(points, "object_vertices"), ("object_f_collisions", "contact_forces"),
                            ("object_f_frictions", "friction_forces")]:
            a = t[key][:]
            assert a.shape == (P, frames, n, 3), (key, a.shape)
            assert np.array_equal(a, traj[source][slots]), key
        if soft:
            assert np.array_equal(t["object_cells"][:], o["tets"][:])
            stress = t["object_stress"][:]
            for p, i in enumerate(ids):
                slot = int(src["candidates/stress_slot"][i])
                if slot >= 0 and src["candidates/stress_written"][i]:
                    assert np.array_equal(stress[p], o["stress"][slot])
                else:
                    assert np.all(np.isnan(stress[p]))
        else:
            faces = t["object_faces"][:]
            assert faces.shape == (P,) + o["triangles"].shape
            assert all(np.array_equal(faces[p], o["triangles"][:]) for p in range(P))
        if parallel and hands == 1:
            seen = read_like_grip(path, P - 1)
            assert seen["frames"] == frames
    return len(rows)


def check_export(grip, dataset, folder, all_candidates):
    result = export(grip, dataset, folder, *(["--all"] if all_candidates else []))
    assert result.returncode == 0, result.stderr
    with h5py.File(dataset, "r") as src:
        rows = [r for r in committed(src) if all_candidates or r[3] == 1]
        by_pair = {}
        for r in rows:
            by_pair.setdefault((r[1], r[0]), []).append(r)
        files = sorted(os.listdir(folder))
        assert len(files) == len(by_pair), (files, len(by_pair))
        checked = 0
        for (grip_index, obj_index), pair_rows in sorted(by_pair.items()):
            o = src["objects/%06d" % obj_index]
            g = src["grippers/%03d" % grip_index]
            name = "%s_%s_%s.h5" % (g.attrs["name"].decode().replace("_", "-"),
                                    o.attrs["name"].decode().replace("_", "-"),
                                    "soft" if o.attrs["soft"] else "rigid")
            assert name in files, (name, files)
            checked += check_file(os.path.join(folder, name), src, pair_rows)
        assert checked == len(rows)
        return checked


def main():
    grip, dataset, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    every = check_export(grip, dataset, os.path.join(work, "all"), True)
    successes = check_export(grip, dataset, os.path.join(work, "successes"), False)
    assert 0 < successes < every, (successes, every)
    # A second export into the same folder is refused, naming a file, and changes nothing.
    folder = os.path.join(work, "all")
    before = {n: open(os.path.join(folder, n), "rb").read() for n in os.listdir(folder)}
    again = export(grip, dataset, folder, "--all")
    assert again.returncode == 1, again.returncode
    assert "exists already" in again.stderr and ".h5" in again.stderr, again.stderr
    after = {n: open(os.path.join(folder, n), "rb").read() for n in os.listdir(folder)}
    assert before == after
    print("exported %d grasps (%d successes), every key checked" % (every, successes))


if __name__ == "__main__":
    main()
