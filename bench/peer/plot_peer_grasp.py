#!/usr/bin/python3
"""Draw one candidate of `grip bench peer --vtk DIR` in both engines: grip's settled grasp and
its last frame beside MuJoCo's (the VTK series STEM_grip.pvd and STEM_mujoco.pvd). The object
is orange, the gripper grey; the view looks across the closing axis. A tet body is drawn by its
boundary faces.
Usage: plot_peer_grasp.py DIR STEM OUT.png (Debian: python3-matplotlib, python3-numpy)."""
import os
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

OBJECT_RGBA = (0.93, 0.55, 0.2, 0.9)
GRIPPER_RGBA = (0.5, 0.53, 0.58, 0.45)
VTK_TRIANGLE, VTK_TETRA = 5, 10


def series(pvd):
    """The .vtu files of a .pvd collection, in time order, with their times."""
    root = ET.parse(pvd).getroot()
    sets = [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]
    return [(t, os.path.join(os.path.dirname(pvd), f)) for t, f in sorted(sets)]


def array(piece, path, name=None):
    for a in piece.find(path).iter("DataArray"):
        if name is None or a.get("Name") == name:
            return np.array(a.text.split(), dtype=float)
    raise KeyError(f"{path}/{name}")


def bodies(vtu):
    """{body id: (points, boundary triangles as point indices)} of one frame."""
    piece = ET.parse(vtu).getroot().find("UnstructuredGrid/Piece")
    points = array(piece, "Points").reshape(-1, 3)
    connectivity = array(piece, "Cells", "connectivity").astype(int)
    offsets = array(piece, "Cells", "offsets").astype(int)
    types = array(piece, "Cells", "types").astype(int)
    body = array(piece, "CellData", "body").astype(int)
    faces = {}
    start = 0
    for end, kind, b in zip(offsets, types, body):
        cell = connectivity[start:end]
        start = end
        if kind == VTK_TRIANGLE:
            faces.setdefault(b, {})[tuple(sorted(cell))] = cell
        elif kind == VTK_TETRA:
            for skip in range(4):  # a tet's face shared by two tets is interior: drop both
                face = np.delete(cell, skip)
                key = tuple(sorted(face))
                table = faces.setdefault(b, {})
                if key in table:
                    del table[key]
                else:
                    table[key] = face
    return {b: (points, np.array(list(f.values()))) for b, f in faces.items()}


def draw(ax, frame, title, view):
    everything = []
    for b, (points, triangles) in sorted(frame.items()):
        polygons = points[triangles]
        everything.append(polygons.reshape(-1, 3))
        ax.add_collection3d(Poly3DCollection(
            polygons, facecolor=OBJECT_RGBA if b == 0 else GRIPPER_RGBA,
            edgecolor=(0, 0, 0, 0.08), linewidth=0.2))
    allpoints = np.vstack(everything)
    center = 0.5 * (allpoints.min(0) + allpoints.max(0))
    half = 0.4 * (allpoints.max(0) - allpoints.min(0)).max()  # a little inside: 3D axes pad
    for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), center):
        setter(c - half, c + half)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(*view)
    ax.set_axis_off()
    ax.set_title(title, fontsize=9)


def across_closing(frame):
    """Elevation and azimuth of a view perpendicular to the line between the two fingers."""
    centers = [points[np.unique(tri)].mean(0) for b, (points, tri) in sorted(frame.items())
               if b != 0]
    closing = centers[-1] - centers[0]
    look = np.cross(closing, [0.0, 0.0, 1.0])
    if np.linalg.norm(look) < 1e-9 * np.linalg.norm(closing):
        look = np.cross(closing, [0.0, 1.0, 0.0])
    look /= np.linalg.norm(look)
    return 20.0, float(np.degrees(np.arctan2(look[1], look[0])))


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    folder, stem, out = sys.argv[1:]
    grip = series(os.path.join(folder, stem + "_grip.pvd"))
    mujoco = series(os.path.join(folder, stem + "_mujoco.pvd"))
    # grip's frames: closing (the last of them the settled grasp), then one per gravity phase.
    grip_frames = [bodies(f) for _, f in grip]
    settled = len(grip_frames) - 7 if len(grip_frames) >= 7 else 0
    panels = [(grip_frames[settled], "grip: settled grasp"),
              (grip_frames[-1], "grip: last frame"),
              (bodies(mujoco[0][1]), "MuJoCo: settled grasp"),
              (bodies(mujoco[-1][1]), "MuJoCo: last frame")]
    view = across_closing(panels[0][0])
    fig = plt.figure(figsize=(9, 9))
    for i, (frame, title) in enumerate(panels):
        draw(fig.add_subplot(2, 2, i + 1, projection="3d"), frame, title, view)
    fig.suptitle(stem.replace("_", " "), fontsize=10)
    fig.subplots_adjust(left=0, right=1, bottom=0, top=0.94, wspace=0, hspace=0.05)
    fig.savefig(out, dpi=110)
    print(out)


if __name__ == "__main__":
    main()
