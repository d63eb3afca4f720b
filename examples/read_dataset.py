#!/usr/bin/python3
"""Load one object's successful grasps, their frames and stress from a grip dataset.

Usage: /usr/bin/python3 examples/read_dataset.py DATASET.h5 [OBJECT_NAME]

Needs h5py and numpy (Debian: python3-h5py, python3-numpy). The schema is docs/dataset-format.md.
"""
import sys

import h5py
import numpy as np


def successful_grasps(path, object_name=None):
    """Returns (object name, [grasp dicts]) for the named object, or the first one."""
    with h5py.File(path, "r") as f:
        objects = f["objects"]
        key = next((k for k in sorted(objects)
                    if object_name is None or objects[k].attrs["name"].decode() == object_name),
                   None)
        if key is None:
            sys.exit(f"{path}: no object named '{object_name}'")
        obj = objects[key]
        table = f["candidates"]
        success = h5py.check_enum_dtype(table["status"].dtype)["success"]
        # A row is valid only once committed (done == 1).
        rows = np.flatnonzero((table["done"][:] == 1) & (table["status"][:] == success)
                              & (table["object"][:] == int(key)))
        grasps = []
        for row in rows:
            gripper = f["grippers"][f"{table['gripper'][row]:03d}"]
            hands = int(gripper.attrs["hands"])
            grasp = {
                "candidate": int(row),
                "gripper": gripper.attrs["name"].decode(),
                "hand_poses": table["hand_poses"][row][:hands],  # (hands, 3, 4) [R | t]
                "joints": table["joints"][row][:hands, :len(gripper["joint_names"])],
                "d1": table["d1"][row], "d2": table["d2"][row],
            }
            if table["trajectory_written"][row]:
                frames = obj["trajectories"][f"{table['gripper'][row]:03d}"]
                slot = table["frame_slot"][row]
                grasp["object_vertices"] = frames["object_vertices"][slot]  # (F, n, 3)
                grasp["contact_forces"] = frames["contact_forces"][slot]    # (F, n, 3)
            if table["stress_written"][row]:
                grasp["stress"] = obj["stress"][table["stress_slot"][row]]  # (tets,) Pa
            grasps.append(grasp)
        return obj.attrs["name"].decode(), grasps


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    name, grasps = successful_grasps(sys.argv[1], sys.argv[2] if len(sys.argv) == 3 else None)
    print(f"{name}: {len(grasps)} successful grasps")
    for g in grasps:
        line = f"  candidate {g['candidate']} ({g['gripper']}): D2 = {1e3 * g['d2']:.3f} mm"
        if "object_vertices" in g:
            line += f", {g['object_vertices'].shape[0]} frames"
        if "stress" in g:
            line += f", max von Mises {g['stress'].max():.3g} Pa"
        print(line)


if __name__ == "__main__":
    main()
