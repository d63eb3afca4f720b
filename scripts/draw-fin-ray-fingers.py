#!/usr/bin/python3
"""Draws grip's fin-ray fingers' profiles beside GRIP's finger outline, as a PNG.

Usage: build/grip asset gallery --out DIR
       /usr/bin/python3 scripts/draw-fin-ray-fingers.py DIR/grippers [--out FILE.png]

Reads the gallery's fin_ray_finger.msh (production) and fin_ray_finger_80mm.msh (Gmsh 2.2,
metres, finger frame: x across the width, y from the contact face, z from the mount) and draws
each one's profile: the tet faces on its x = min side. GRIP's finger (its released models' UMI
finger body: 123.5 mm long, 41.5 mm deep at the mount, about 3.3 mm at the tip) is drawn as a
dashed outline over the production finger. Needs matplotlib (Debian: python3-matplotlib).
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)
from matplotlib.collections import PolyCollection  # noqa: E402

GRIP_OUTLINE_MM = [(0.0, 0.0), (41.5, 0.0), (3.3, 123.5), (0.0, 123.5), (0.0, 0.0)]


def read_msh(path):
    """The vertices (list of (x, y, z)) and tets (lists of four 0-based indices) of a Gmsh 2.2 file."""
    with open(path) as f:
        lines = f.read().split("\n")
    at = lines.index("$Nodes")
    vertices = [tuple(float(v) for v in lines[at + 2 + i].split()[1:4])
                for i in range(int(lines[at + 1]))]
    at = lines.index("$Elements")
    tets = []
    for i in range(int(lines[at + 1])):
        fields = lines[at + 2 + i].split()
        if fields[1] == "4":  # a 4-node tetrahedron; its nodes are the last four fields
            tets.append([int(v) - 1 for v in fields[-4:]])
    return vertices, tets


def profile_triangles(vertices, tets):
    """The tet faces whose three vertices lie on the smallest x, as (y, z) in mm."""
    side = min(v[0] for v in vertices)
    triangles = set()
    for tet in tets:
        on_side = tuple(sorted(v for v in tet if vertices[v][0] == side))
        if len(on_side) == 3:
            triangles.add(on_side)
    return [[(1e3 * vertices[v][1], 1e3 * vertices[v][2]) for v in t] for t in triangles]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("gallery_grippers", help="the grippers folder of grip asset gallery")
    parser.add_argument("--out", default="fin_ray_fingers.png")
    args = parser.parse_args()
    fingers = [("fin_ray_finger.msh", "production (GRIP's size)"),
               ("fin_ray_finger_80mm.msh", "80 mm variant")]
    figure, axes = plt.subplots(1, 2, figsize=(6.4, 5.2), sharey=True)
    for axis, (name, title) in zip(axes, fingers):
        vertices, tets = read_msh(os.path.join(args.gallery_grippers, name))
        width = 1e3 * (max(v[0] for v in vertices) - min(v[0] for v in vertices))
        axis.add_collection(PolyCollection(profile_triangles(vertices, tets), facecolors="#c9d6e3",
                                           edgecolors="#40576e", linewidths=0.3))
        axis.set_title(f"{title}\n{len(vertices)} vertices, {len(tets)} tets, {width:.0f} mm wide",
                       fontsize=9)
        axis.set_xlabel("y: from the contact face (mm)")
        axis.set_aspect("equal")
        axis.set_xlim(-3, 46)
        axis.set_ylim(-3, 128)
    y, z = zip(*GRIP_OUTLINE_MM)
    axes[0].plot(y, z, "--", color="#b5452b", linewidth=1.2, label="GRIP's finger body")
    axes[0].legend(loc="upper right", fontsize=8)
    axes[0].set_ylabel("z: from the mount (mm)")
    figure.tight_layout()
    figure.savefig(args.out, dpi=130)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
