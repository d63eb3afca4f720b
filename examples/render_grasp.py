#!/usr/bin/python3
"""Draws one trial of a grip dataset as a PNG: the settled grasp and the last gravity frame.

Usage: /usr/bin/python3 examples/render_grasp.py DATASET.h5 [--record N] [--out FILE.png]
       /usr/bin/python3 examples/render_grasp.py DATASET.h5 --list

Both panels show the gripper's surface (grey, see-through) and the object's, as the dataset's
frames place them. A soft object is coloured by von Mises stress per tet (its boundary
triangles take their tet's value): at the settled grasp the stored field, in the last frame
the same stable Neo-Hookean formula applied to that frame's vertices. A rigid object is
coloured by the normal contact force on each vertex. Soft fingers whose stress was kept are
coloured at the settled grasp by their own von Mises stress (viridis, a scale of their own,
ending at the 98th percentile).
Without --record it draws the first successful grasp of a soft object that has stress, else the
first successful one with frames.

Needs matplotlib, numpy and h5py (Debian: python3-matplotlib, python3-numpy, python3-h5py);
no display: it draws with matplotlib's Agg backend. The schema is docs/dataset-format.md.
"""
import argparse
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

GRIPPER_RGBA = (0.55, 0.58, 0.62, 0.35)
LIGHT = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def records(f, rows=None):
    """One dict per candidate row that has frames (of `rows`, or of all), in row order."""
    table = f["candidates"]
    status = {v: k for k, v in h5py.check_enum_dtype(table["status"].dtype).items()}
    failure = {v: k for k, v in h5py.check_enum_dtype(table["failure"].dtype).items()}
    column = {name: table[name][:] for name in ("done", "trajectory_written", "object", "gripper",
                                                "status", "failure", "stress_written", "d2")}
    objects = [(text(f["objects"][k].attrs["name"]), bool(f["objects"][k].attrs["soft"]))
               for k in sorted(f["objects"])]
    grippers = [text(f["grippers"][k].attrs["name"]) for k in sorted(f["grippers"])]
    with_frames = np.flatnonzero((column["done"] == 1) & (column["trajectory_written"] == 1))
    return [{
        "row": int(row),
        "object": objects[column["object"][row]][0],
        "soft": objects[column["object"][row]][1],
        "gripper": grippers[column["gripper"][row]],
        "status": status[column["status"][row]],
        "failure": failure[column["failure"][row]],
        "stress": bool(column["stress_written"][row]),
        "d2": float(column["d2"][row]),
    } for row in with_frames if rows is None or row in rows]


def default_record(found):
    """The first successful grasp with stress, else the first successful one, else the first."""
    successes = [r for r in found if r["status"] == "success"]
    return next((r for r in successes if r["stress"]), (successes or found or [None])[0])


def von_mises(rest, deformed, tets, youngs, poisson):
    """Von Mises stress per tet (Pa) of the solver's stable Neo-Hookean material: the deviator
    of its Cauchy stress is mu / J dev(F F^T), so only mu enters. NaN where a tet is inverted."""
    mu = youngs / (2.0 * (1.0 + poisson))

    def edges(x):  # per tet, the matrix of its edge vectors from corner 0
        return np.stack([x[tets[:, k]] - x[tets[:, 0]] for k in (1, 2, 3)], axis=2)

    f = edges(deformed) @ np.linalg.inv(edges(rest))
    j = np.linalg.det(f)
    b = f @ f.transpose(0, 2, 1)
    deviator = b - np.trace(b, axis1=1, axis2=2)[:, None, None] / 3.0 * np.eye(3)
    stress = np.sqrt(1.5) * mu / np.abs(j) * np.sqrt((deviator**2).sum(axis=(1, 2)))
    return np.where(j > 0, stress, np.nan)


def triangle_tets(triangles, tets):
    """For each boundary triangle, the tet it is a face of (-1 if none)."""
    owner = {}
    for t, tet in enumerate(tets):
        for face in ((0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)):
            owner[tuple(sorted(tet[list(face)]))] = t
    return np.array([owner.get(tuple(sorted(tri)), -1) for tri in triangles])


def finger_faces(gripper, stress):
    """Per gripper surface triangle, the stress of the finger tet it is a face of (NaN where
    none is). The surface's vertices are the finger tets' own, bit for bit."""
    tet_vertex = {tuple(v): i for i, v in enumerate(gripper["tet_vertices"][:])}
    on_tets = np.array([tet_vertex.get(tuple(v), -1) for v in gripper["vertices"][:]])
    triangles = on_tets[gripper["triangles"][:]]
    owner = triangle_tets(triangles, gripper["tets"][:])
    owner[(triangles < 0).any(axis=1)] = -1
    return np.where(owner >= 0, stress[owner], np.nan)


class Trial:
    """The meshes and the two frames of one candidate row."""

    def __init__(self, f, row):
        table = f["candidates"]
        if not 0 <= row < len(table["done"]):
            sys.exit(f"no record {row}: the dataset has {len(table['done'])} (0 to "
                     f"{len(table['done']) - 1})")
        if not (table["done"][row] and table["trajectory_written"][row]):
            sys.exit(f"record {row} has no frames (not done, or its job stored none); "
                     "--list shows the records that have")
        self.info = records(f, rows={row})[0]
        obj = f["objects"][f"{table['object'][row]:06d}"]
        gripper = f["grippers"][f"{table['gripper'][row]:03d}"]
        frames = obj["trajectories"][f"{table['gripper'][row]:03d}"]
        slot = table["frame_slot"][row]
        closing = int(f.attrs["closing_frames"])
        count = closing + int(f.attrs["validation_frames"])
        self.frame_numbers = (closing - 1, count - 1)
        self.triangles = obj["triangles"][:]
        self.object_vertices = [frames["object_vertices"][slot, i].astype(float)
                                for i in self.frame_numbers]
        # Every hand's surface, hand after hand, as the frames' gripper vertices run.
        self.gripper_triangles = gripper["triangles"][:]
        self.gripper_vertices = [frames["gripper_vertices"][slot, i].astype(float)
                                 for i in self.frame_numbers]
        self.finger_values = None  # kPa per gripper triangle at the settled grasp
        if "finger_stress_written" in table and table["finger_stress_written"][row]:
            stored = gripper["finger_stress"][table["finger_stress_slot"][row]].astype(float)
            self.finger_values = finger_faces(gripper, stored) / 1e3
        if self.info["soft"] and len(obj["tets"]):
            stored = table["stress_slot"][row] if self.info["stress"] else None
            self.label, self.face_values = "von Mises stress (kPa)", self.stress(obj, stored)
        else:
            self.label = "normal contact force per vertex (N)"
            self.face_values = []
            for i in self.frame_numbers:
                force = np.linalg.norm(frames["contact_forces"][slot, i].astype(float), axis=1)
                self.face_values.append(force[self.triangles].mean(axis=1))

    def stress(self, obj, stored_slot):
        """kPa per boundary triangle in both frames: the stored field at the settled grasp where
        there is one, else (and in the last frame) recomputed from the frame's vertices."""
        tets = obj["tets"][:]
        youngs, poisson = obj.attrs["young_modulus"], obj.attrs["poisson_ratio"]
        fields = [von_mises(obj["vertices"][:], x, tets, youngs, poisson)
                  for x in self.object_vertices]
        if stored_slot is not None:
            fields[0] = obj["stress"][stored_slot].astype(float)
        owner = triangle_tets(self.triangles, tets)
        return [np.where(owner >= 0, field[owner] / 1e3, np.nan) for field in fields]


def shaded(colours, faces):
    """Colours darkened by a fixed light, so the surfaces read as 3D."""
    normals = np.cross(faces[:, 1] - faces[:, 0], faces[:, 2] - faces[:, 0])
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.divide(normals, lengths, out=np.zeros_like(normals), where=lengths > 0)
    light = 0.65 + 0.35 * np.abs(normals @ LIGHT)
    out = colours.copy()
    out[:, :3] *= light[:, None]
    return out


def view_azimuth(gripper_vertices):
    """Degrees: a view across the gripper's widest horizontal extent (a jaw gripper's closing
    direction), turned 35 degrees so one contact side faces the camera."""
    xy = gripper_vertices[:, :2] - gripper_vertices[:, :2].mean(axis=0)
    widest = np.linalg.eigh(xy.T @ xy)[1][:, -1]
    return np.degrees(np.arctan2(widest[1], widest[0])) + 90.0 - 35.0


class View:
    """What both panels share: one box around both bodies in both frames, one camera, one
    colour scale."""

    def __init__(self, trial):
        points = np.concatenate(trial.object_vertices + trial.gripper_vertices)
        self.centre = (points.min(axis=0) + points.max(axis=0)) / 2
        self.half = (points.max(axis=0) - points.min(axis=0)).max() / 2 * 1.05
        self.azimuth = view_azimuth(trial.gripper_vertices[0])
        values = np.concatenate(trial.face_values)
        top = np.nanmax(values) if np.isfinite(values).any() else 0.0
        self.norm = matplotlib.colors.Normalize(vmin=0.0, vmax=top if top > 0 else 1.0)
        self.colour_map = plt.get_cmap("magma_r")
        if trial.finger_values is not None:
            # A few rib joints carry most of the peak: the scale ends at the 98th percentile.
            finite = trial.finger_values[np.isfinite(trial.finger_values)]
            top = np.percentile(finite, 98) if len(finite) else 0.0
            self.finger_norm = matplotlib.colors.Normalize(vmin=0.0, vmax=top if top > 0 else 1.0)
            self.finger_colour_map = plt.get_cmap("viridis")


def draw_panel(ax, trial, panel, view):
    object_faces = trial.object_vertices[panel][trial.triangles]
    gripper_faces = trial.gripper_vertices[panel][trial.gripper_triangles]
    values = trial.face_values[panel]
    colours = view.colour_map(view.norm(np.nan_to_num(values, nan=0.0)))
    colours[np.isnan(values)] = (0.8, 0.8, 0.8, 1.0)
    # One collection, so the faces of both bodies are depth-sorted together.
    faces = np.concatenate([object_faces, gripper_faces])
    gripper_colours = np.tile(GRIPPER_RGBA, (len(gripper_faces), 1))
    if panel == 0 and trial.finger_values is not None:
        stressed = np.isfinite(trial.finger_values)
        gripper_colours[stressed] = view.finger_colour_map(
            view.finger_norm(trial.finger_values[stressed]))
        gripper_colours[stressed, 3] = 0.9
    colours = np.concatenate([colours, gripper_colours])
    edges = [(0, 0, 0, 0)] * len(object_faces) + [(0.2, 0.2, 0.25, 0.5)] * len(gripper_faces)
    ax.add_collection3d(Poly3DCollection(list(faces), facecolors=shaded(colours, faces),
                                         edgecolors=edges, linewidths=0.4))
    for axis, c in zip("xyz", view.centre):
        getattr(ax, f"set_{axis}lim")(c - view.half, c + view.half)
        getattr(ax, f"set_{axis}label")(f"{axis} (m)", fontsize=7, labelpad=-8)
    ax.set_box_aspect((1, 1, 1))
    ax.tick_params(labelsize=6, pad=-3)
    ax.view_init(elev=22, azim=view.azimuth)
    if panel == 1:  # the last gravity phase pulls along -z
        corner = view.centre + 0.8 * view.half * np.array([1.0, 1.0, 0.75])
        ax.quiver(*corner, 0, 0, -0.4 * view.half, color="tab:blue", linewidth=1.5)
        ax.text(*(corner + [0, 0, 0.05 * view.half]), "g", color="tab:blue")


def render(path, row, out):
    with h5py.File(path, "r") as f:
        if row is None:
            chosen = default_record(records(f))
            if chosen is None:
                sys.exit(f"{path}: no record has frames (the job's [outputs] frames is false?)")
            row = chosen["row"]
        trial = Trial(f, row)
    info, view = trial.info, View(trial)
    figure = plt.figure(figsize=(9.0, 4.4), dpi=100)
    figure.subplots_adjust(left=0.0, right=0.88, bottom=0.02, top=0.9, wspace=0.02)
    titles = ("settled grasp (frame {})", "last gravity frame, along -z (frame {})")
    for panel in (0, 1):
        ax = figure.add_subplot(1, 2, panel + 1, projection="3d")
        draw_panel(ax, trial, panel, view)
        ax.set_title(titles[panel].format(trial.frame_numbers[panel]), fontsize=9)
    verdict = info["status"] + ("" if info["failure"] == "none" else f" ({info['failure']})")
    figure.suptitle(f"record {row}: {info['object']} ({'soft' if info['soft'] else 'rigid'}) "
                    f"in {info['gripper']}, {verdict}, D2 = {1e3 * info['d2']:.2f} mm",
                    fontsize=10)
    bars = [(view.norm, view.colour_map, trial.label)]
    if trial.finger_values is not None:
        figure.subplots_adjust(right=0.8)
        bars.append((view.finger_norm, view.finger_colour_map,
                     "finger von Mises stress (kPa), settled (98th pct.)"))
    for k, (norm, colour_map, label) in enumerate(bars):
        left = 0.9 if len(bars) == 1 else 0.83 + 0.085 * k
        bar = figure.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap=colour_map),
                              cax=figure.add_axes((left, 0.18, 0.015, 0.6)))
        bar.set_label(label, fontsize=8)
        bar.ax.tick_params(labelsize=7)
    figure.savefig(out)
    plt.close(figure)
    print(f"record {row} ({info['object']}, {info['gripper']}, {verdict}) drawn to {out}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("dataset", help="a grip dataset (.h5)")
    parser.add_argument("--record", type=int, help="candidate row (default: see above)")
    parser.add_argument("--out", default="grasp.png", help="PNG to write (default: grasp.png)")
    parser.add_argument("--list", action="store_true", help="list the records that have frames")
    args = parser.parse_args()
    if args.list:
        with h5py.File(args.dataset, "r") as f:
            for r in records(f):
                print(f"{r['row']:6d}  {r['object']:<16} {'soft' if r['soft'] else 'rigid':<5} "
                      f"{r['gripper']:<16} {r['status']:<8} {r['failure']:<20}"
                      f"{' stress' if r['stress'] else ''}")
        return
    render(args.dataset, args.record, args.out)


if __name__ == "__main__":
    main()
