"""A grip dataset (docs/dataset-format.md) as a torch.utils.data.Dataset of settled grasps.

One item per committed candidate (done == 1) that has a trajectory, taken at the settled grasp:
frame closing_frames - 1, the end of closing, where grip takes the stress. Each item is a dict:

  candidate, object, gripper       int64 scalars: table row, object and gripper group index
  category, object_name,           str
  gripper_name
  object_vertices   (n, 3) float32  the object's vertices at the settled grasp (world, m)
  rest_vertices     (n, 3) float32  the same vertices at rest, in the object frame (m)
  triangles         (m, 3) int64    the object's boundary triangles
  stress            (n,) float32    von Mises per vertex (Pa): the per-tet row averaged onto the
                                    vertices, weighted by the tets' rest volumes; 0 without stress
  has_stress        bool scalar     the candidate's stress row was written
  gripper_vertices  (g, 3) float32  every hand's surface vertices at that frame (world, m)
  contact_forces,   (n, 3) float32  normal and friction force on each object vertex (N)
  friction_forces
  gripper_contact_forces,           (g, 3) float32: the same on the gripper's vertices, from
  gripper_friction_forces           format 9 on (absent from a format 8 file's items)
  finger_stress     (k,) float32    von Mises per tet of the soft fingers (Pa; the gripper's
                                    tets), 0 without a row; format 10 on, like has_finger_stress
  has_finger_stress bool scalar     the candidate's finger stress row was written
  status, failure   int64 scalars   the verdict's codes (their names: the dataset's
                                    status_names, failure_names)
  success           bool scalar     status == success
  closing_forces    (H, P) float32  each finger's force when closing stopped (N); NaN padded to
                                    the file's max_hands x max_fingers, so it stacks

Why volume-weighted vertex stress: the tets of a graded mesh differ in size by up to 3x, and
a small sliver's stress is noisier than a large tet's; weighting by volume is the L2 projection
of the piecewise-constant field onto vertices with a lumped mass, so the vertex value is the
stress of the material around it. Tets whose stress is not finite get no weight.

The HDF5 file is opened lazily in each process (h5py handles do not survive fork), so the
dataset can be used with DataLoader(num_workers > 0).
"""
import os

import h5py
import numpy as np
import torch

MIN_FORMAT_VERSION = 8
OBJECT_KEYS = ("object_vertices", "rest_vertices", "stress", "contact_forces", "friction_forces")
GRIPPER_KEYS = ("gripper_vertices", "gripper_contact_forces", "gripper_friction_forces")
FINGER_KEYS = ("finger_stress",)
OPTIONAL_TRAJECTORY = ("gripper_contact_forces", "gripper_friction_forces")
# The table's columns an item needs, read whole once (they are small; the frames are not).
TABLE_COLUMNS = ("done", "trajectory_written", "stress_written", "object", "gripper", "status",
                 "failure", "frame_slot", "stress_slot", "closing_forces")
FINGER_COLUMNS = ("finger_stress_written", "finger_stress_slot")  # format 10 on


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def enum_names(dataset):
    """{code: name} of an HDF5 enum column."""
    return {code: name for name, code in h5py.check_enum_dtype(dataset.dtype).items()}


def tet_volumes(vertices, tets):
    edges = np.stack([vertices[tets[:, k]] - vertices[tets[:, 0]] for k in (1, 2, 3)], axis=2)
    return np.abs(np.linalg.det(edges)) / 6.0


def vertex_stress(tet_stress, tets, volumes, vertex_count):
    """Per-tet values averaged onto vertices by incident-tet volume (0 where no tet has one)."""
    weights = np.where(np.isfinite(tet_stress), volumes, 0.0)
    values = np.nan_to_num(tet_stress.astype(np.float64), nan=0.0, posinf=0.0, neginf=0.0)
    corners = tets.reshape(-1)
    weighted = np.bincount(corners, np.repeat(weights * values, 4), vertex_count)
    total = np.bincount(corners, np.repeat(weights, 4), vertex_count)
    return np.divide(weighted, total, out=np.zeros(vertex_count), where=total > 0)


class GraspStressDataset(torch.utils.data.Dataset):
    """Settled grasps of a grip dataset. Filters (all optional):

    successes_only  keep status == success
    soft_only       keep soft objects whose stress row was written
    objects         keep these object indices
    categories      keep these object categories (e.g. ["bowl", "mug"])
    """

    def __init__(self, path, successes_only=False, soft_only=False, objects=None,
                 categories=None):
        self.path = os.fspath(path)
        self._file, self._pid, self._objects = None, None, {}
        with h5py.File(self.path, "r") as f:
            version = int(f.attrs.get("format_version", 0))
            if text(f.attrs.get("format", b"")) != "grip-dataset" or version < MIN_FORMAT_VERSION:
                raise ValueError(f"{self.path}: not a grip dataset of format version "
                                 f"{MIN_FORMAT_VERSION} or newer (format_version {version})")
            self.settled_frame = int(f.attrs["closing_frames"]) - 1
            table = f["candidates"]
            self.status_names, self.failure_names = (enum_names(table["status"]),
                                                     enum_names(table["failure"]))
            success = h5py.check_enum_dtype(table["status"].dtype)["success"]
            keys = sorted(f["objects"])
            self.object_info = [{"category": text(f["objects"][k].attrs["category"]),
                                 "name": text(f["objects"][k].attrs["name"]),
                                 "soft": bool(f["objects"][k].attrs["soft"])} for k in keys]
            self.gripper_names = [text(f["grippers"][k].attrs["name"])
                                  for k in sorted(f["grippers"])]
            self.finger_tets = [len(f["grippers"][k]["tets"]) if "tets" in f["grippers"][k] else 0
                                for k in sorted(f["grippers"])]
            names = TABLE_COLUMNS + (FINGER_COLUMNS if FINGER_COLUMNS[0] in table else ())
            column = {name: table[name][:] for name in names}
        committed = column["done"] == 1
        keep = committed & (column["trajectory_written"] == 1)
        # Committed rows left out because the job stored no trajectory for them (frames = false).
        self.without_frames = int((committed & ~keep).sum())
        if successes_only:
            keep &= column["status"] == success
        if soft_only:
            soft = np.array([info["soft"] for info in self.object_info], dtype=bool)
            keep &= soft[column["object"]] & (column["stress_written"] == 1)
        if objects is not None:
            keep &= np.isin(column["object"], list(objects))
        if categories is not None:
            category = np.array([info["category"] for info in self.object_info])
            keep &= np.isin(category[column["object"]], list(categories))
        self.rows = np.flatnonzero(keep)
        self.row_objects = column["object"][self.rows]
        self._table = {name: values[self.rows] for name, values in column.items()}

    def __len__(self):
        return len(self.rows)

    def category(self, index):
        return self.object_info[self.row_objects[index]]["category"]

    def __getstate__(self):  # a pickled copy (spawned worker) opens its own handle
        state = dict(self.__dict__)
        state.update(_file=None, _pid=None, _objects={})
        return state

    def _h5(self):
        if self._file is None or self._pid != os.getpid():
            self._file, self._pid, self._objects = h5py.File(self.path, "r"), os.getpid(), {}
        return self._file

    def _object(self, index):
        """The object's meshes and tet volumes, read once per process."""
        if index not in self._objects:
            group = self._h5()["objects"][f"{index:06d}"]
            rest, tets = group["vertices"][:], group["tets"][:].astype(np.int64)
            self._objects[index] = {"rest": rest, "tets": tets,
                                    "triangles": group["triangles"][:].astype(np.int64),
                                    "volumes": tet_volumes(rest, tets)}
        return self._objects[index]

    def __getitem__(self, index):
        f, row = self._h5(), int(self.rows[index])
        column = {name: values[index] for name, values in self._table.items()}
        obj_index, gripper = int(column["object"]), int(column["gripper"])
        obj, info = self._object(obj_index), self.object_info[obj_index]
        group = f["objects"][f"{obj_index:06d}"]
        frames = group["trajectories"][f"{gripper:03d}"]
        slot, frame = int(column["frame_slot"]), self.settled_frame
        n = len(obj["rest"])
        has_stress = bool(column["stress_written"])
        stress = np.zeros(n)
        if has_stress:
            tet_stress = group["stress"][int(column["stress_slot"])]
            stress = vertex_stress(tet_stress, obj["tets"], obj["volumes"], n)
        status = int(column["status"])
        item = {
            "candidate": torch.tensor(row), "object": torch.tensor(obj_index),
            "gripper": torch.tensor(gripper), "category": info["category"],
            "object_name": info["name"], "gripper_name": self.gripper_names[gripper],
            "object_vertices": torch.from_numpy(frames["object_vertices"][slot, frame]),
            "rest_vertices": torch.from_numpy(obj["rest"].astype(np.float32)),
            "triangles": torch.from_numpy(obj["triangles"]),
            "stress": torch.from_numpy(stress.astype(np.float32)),
            "has_stress": torch.tensor(has_stress),
            "gripper_vertices": torch.from_numpy(frames["gripper_vertices"][slot, frame]),
            "contact_forces": torch.from_numpy(frames["contact_forces"][slot, frame]),
            "friction_forces": torch.from_numpy(frames["friction_forces"][slot, frame]),
            "status": torch.tensor(status), "failure": torch.tensor(int(column["failure"])),
            "success": torch.tensor(self.status_names[status] == "success"),
            "closing_forces": torch.from_numpy(column["closing_forces"].astype(np.float32)),
        }
        for name in OPTIONAL_TRAJECTORY:
            if name in frames:
                item[name] = torch.from_numpy(frames[name][slot, frame])
        if "finger_stress_written" in column:
            has_finger_stress = bool(column["finger_stress_written"])
            finger_stress = np.zeros(self.finger_tets[gripper], dtype=np.float32)
            if has_finger_stress:
                finger_stress = f["grippers"][f"{gripper:03d}"]["finger_stress"][
                    int(column["finger_stress_slot"])]
            item["finger_stress"] = torch.from_numpy(finger_stress)
            item["has_finger_stress"] = torch.tensor(has_finger_stress)
        return item


def pad(tensors):
    """Stacks tensors of differing first sizes, zero padded; returns (batch, mask)."""
    size = max(t.shape[0] for t in tensors)
    out = tensors[0].new_zeros((len(tensors), size) + tuple(tensors[0].shape[1:]))
    mask = torch.zeros(len(tensors), size, dtype=torch.bool)
    for i, t in enumerate(tensors):
        out[i, :t.shape[0]], mask[i, :t.shape[0]] = t, True
    return out, mask


def collate_padded(items):
    """DataLoader collate_fn: per-vertex (per-finger-tet) tensors zero padded with object_mask /
    gripper_mask / finger_mask (True on real values), triangles and strings as lists, the rest
    stacked. For no padding at all, pass collate_fn=list and get the items themselves."""
    batch = {}
    masks = {**dict.fromkeys(OBJECT_KEYS, "object_mask"),
             **dict.fromkeys(GRIPPER_KEYS, "gripper_mask"),
             **dict.fromkeys(FINGER_KEYS, "finger_mask")}
    for key in items[0]:
        values = [item[key] for item in items]
        if key in masks:
            batch[key], batch[masks[key]] = pad(values)
        elif key == "triangles" or isinstance(values[0], str):
            batch[key] = values
        else:
            batch[key] = torch.stack(values)
    return batch
