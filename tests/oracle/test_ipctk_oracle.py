#!/usr/bin/env python3
"""grip's per-primitive kernels against ipc-toolkit (ipctk 1.6.1, the IPC authors' reference).

Usage: test_ipctk_oracle.py KERNEL_VALUES   (the oracle_kernel_values program)

Generates random and degenerate configurations (fixed seed), has KERNEL_VALUES evaluate grip's
kernels on them (binary rows in a temporary folder), evaluates ipctk on the same, and prints per
kernel and quantity the configuration count and the largest relative difference

    err = max_i |grip_i - ipctk_i| / max(max_i |grip_i|, max_i |ipctk_i|, floor)

over the entries i of one configuration's value, gradient or Hessian (floor: the size of the
round-off of that quantity, from the configuration's coordinate magnitude; see FLOORS), then
checks err <= rtol (RTOL). Then it perturbs grip's values (a Hessian entry by 1e-6 relative, a
gradient sign, a time of impact past ipctk's) and asserts each comparison catches it.

Exit status: 0 all agree, 1 a disagreement (or a perturbation not caught), 77 ipctk (or numpy)
is missing: ctest reports the test skipped, and the script says so loudly.

Conventions (what maps to what):
- distances: both libraries return SQUARED distances; types are the same enums (same order).
  Where the types differ (ties: a point exactly over a triangle edge, parallel edges), grip's
  type must be a closest pair too (ipctk's distance with grip's type equals ipctk's own) and
  the gradient and Hessian are compared with ipctk's at grip's type.
- barrier: ipctk.barrier(d, dhat) and grip's barrier(d, d_hat) are the same function of two
  numbers, b = -(d - dhat)^2 ln(d / dhat). ipctk's potentials feed it squared distances and
  dhat^2; grip's contact_barrier feeds it the unsquared distance and d_hat. So grip's
  contact_barrier is compared with ipctk's BarrierPotential run with a Barrier whose b(s) is
  ipctk.barrier(sqrt(s), dhat): ipctk's own chain rule and mollifier product rule.
  barrier_force_magnitude: both -2 kappa sqrt(s) b'(s, dhat^2) of the squared distance s.
- edge-edge mollifier: the same m(x) = (2 - x / eps_x) x / eps_x, eps_x = 1e-3 |a|^2 |b|^2 at
  rest; ipctk's scalar edge_edge_mollifier_gradient/hessian(x, eps_x) are m' and m''.
- friction mollifier: smooth_friction_f0/f1/f1_over_x are grip's friction_f0/f1/f1_over_y;
  ipctk's smooth_friction_f2_x_minus_f1_over_x3 = (f1' y - f1) / y^3 is grip's
  friction_f1_over_y_derivative divided by y (compared for y > 0; ipctk's is singular at 0).
- friction potential: ipctk's FrictionPotential(eps) on a *TangentialCollision whose tangent
  basis and closest point ipctk computes from the lagged positions, with mu_s = mu_k = mu and
  normal force lambda, against grip's friction_potential of the tangent operator built from
  grip's tangent basis, closest point and relative-velocity Jacobian with mu lambda: the same
  D(dx) = mu lambda f0(|T^T Gamma dx|). Bases are compared as projectors B B^T (a basis is
  defined up to a rotation in the tangent plane, to which D is blind).
- additive CCD: ipctk.AdditiveCCD(conservative_rescaling = 0.9) is grip's rescaling s = 0.1
  (ipctk's eta = 1 - s). Where ipctk finds an impact grip must too, no later (up to round-off),
  except where ipctk reports the impact of a step that ends past t_max: its own lower bound then
  clears [toi, t_max] and grip answers no impact (checked with ipctk's distance).
"""
import math
import os
import subprocess
import sys
import tempfile

try:
    import numpy as np
    import ipctk
except ImportError as error:
    print(f"ipc-toolkit oracle NOT RUN: {error} (python {sys.executable}); "
          "run scripts/install-peers.sh", flush=True)
    sys.exit(77)

SEED = 20260101
EPS = np.finfo(float).eps

# Relative tolerances, err <= rtol with err as in the docstring. Two implementations of the
# same formula in double precision differ by a few ulps of the floor where the configuration is
# well conditioned; the degenerate families below (nearly parallel edges, slivers, points 1e-10
# off a plane) lose digits to cancellation in both, which the floors bound: the largest err
# seen is 2e-10 (Hessians of nearly parallel edges). 1e-9 keeps a margin over it and still
# catches a 1e-6 relative change of any entry the floor resolves (the self-check).
RTOL = {
    "value": 1e-9,
    "gradient": 1e-9,
    "hessian": 1e-9,
}


# ---- configurations --------------------------------------------------------------------------

def unit(v):
    return v / np.linalg.norm(v)


def perpendicular(rng, v):
    w = np.cross(v, rng.normal(size=3))
    return unit(w)


def random_transform(rng, points):
    """Rotate, scale (1e-6 .. 1e3) and translate a configuration (rows: points)."""
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    scale = 10.0 ** rng.choice([-6, -3, -1, 0, 0, 0, 1, 3])
    shift = rng.normal(size=3) * scale * rng.choice([0.0, 1.0, 100.0])
    return points @ q.T * scale + shift


def point_triangle_configs(rng, n):
    configs = []
    for i in range(n):
        t = rng.uniform(-1, 1, size=(3, 3))
        a, b = t[1] - t[0], t[2] - t[0]
        normal = unit(np.cross(a, b))
        kind = i % 8
        s, r = rng.uniform(0.05, 0.9), rng.uniform(0.05, 0.9)
        h = rng.choice([0.0, 1e-10, 1e-4, 0.3]) * rng.choice([-1, 1])
        if kind == 0:
            p = rng.uniform(-1.5, 1.5, size=3)
        elif kind == 1:  # over the face
            u = rng.dirichlet([1, 1, 1])
            p = u @ t + h * normal
        elif kind == 2:  # exactly over an edge (the P_T / P_E tie)
            e = rng.integers(3)
            p = t[e] + s * (t[(e + 1) % 3] - t[e]) + h * normal
        elif kind == 3:  # over or at a vertex
            p = t[rng.integers(3)] + h * normal
        elif kind == 4:  # beside an edge, in or off the plane
            e = rng.integers(3)
            m = t[e] + s * (t[(e + 1) % 3] - t[e])
            out = unit(m - t.mean(axis=0))
            p = m + r * out + h * normal
        elif kind == 5:  # nearly flat (sliver) triangle: t2 almost on line t0 t1
            t[2] = t[0] + rng.uniform(-0.5, 1.5) * a + rng.choice([0.0, 1e-9, 1e-6]) * \
                perpendicular(rng, a)
            p = rng.uniform(-1, 1, size=3)
        elif kind == 6:  # two vertices almost coincident
            t[2] = t[1] + rng.choice([0.0, 1e-12, 1e-7]) * rng.normal(size=3)
            p = rng.uniform(-1, 1, size=3)
        else:  # beyond a vertex, in the plane
            v = rng.integers(3)
            p = t[v] + r * unit(t[v] - t.mean(axis=0)) + h * normal
        configs.append(random_transform(rng, np.vstack([p, t])))
    return np.array(configs)


def edge_edge_configs(rng, n):
    configs = []
    for i in range(n):
        ea = rng.uniform(-1, 1, size=(2, 3))
        a = ea[1] - ea[0]
        kind = i % 7
        gap = rng.choice([0.0, 1e-10, 1e-4, 0.3])
        if kind == 0:
            eb = rng.uniform(-1, 1, size=(2, 3))
        elif kind in (1, 2):  # parallel (kind 1) or nearly parallel (kind 2), offset by gap
            off = gap * perpendicular(rng, a)
            angle = 0.0 if kind == 1 else rng.choice([1e-9, 1e-6, 1e-3])
            bdir = unit(a + angle * np.linalg.norm(a) * perpendicular(rng, a))
            start = ea[0] + rng.uniform(-1.0, 1.5) * a + off
            eb = np.vstack([start, start + rng.uniform(0.2, 2.0) * np.linalg.norm(a) * bdir])
            if rng.random() < 0.5:
                eb = eb[::-1]
        elif kind == 3:  # crossing interiors at a gap along the common normal
            b = perpendicular(rng, a) + rng.normal(size=3) * 0.3
            n_ab = unit(np.cross(a, b))
            c = ea[0] + rng.uniform(0.1, 0.9) * a + gap * n_ab
            eb = np.vstack([c - rng.uniform(0.1, 0.9) * b, c + rng.uniform(0.1, 0.9) * b])
        elif kind == 4:  # an endpoint of b on or near a's interior
            c = ea[0] + rng.uniform(0.1, 0.9) * a + gap * perpendicular(rng, a)
            eb = np.vstack([c, c + rng.normal(size=3)])
        elif kind == 5:  # endpoints near each other
            c = ea[rng.integers(2)] + gap * unit(rng.normal(size=3))
            eb = np.vstack([c, c + rng.normal(size=3)])
        else:  # collinear, overlapping or apart
            eb = np.vstack([ea[0] + rng.uniform(-1, 2) * a, ea[0] + rng.uniform(-1, 2) * a])
        configs.append(random_transform(rng, np.vstack([ea, eb])))
    return np.array(configs)


def point_edge_configs(rng, n):
    configs = []
    for i in range(n):
        e = rng.uniform(-1, 1, size=(2, 3))
        d = e[1] - e[0]
        kind = i % 5
        h = rng.choice([0.0, 1e-10, 1e-4, 0.3])
        if kind == 0:
            p = rng.uniform(-1.5, 1.5, size=3)
        elif kind == 1:  # over the interior
            p = e[0] + rng.uniform(0.05, 0.95) * d + h * perpendicular(rng, d)
        elif kind == 2:  # exactly over an endpoint (the P_E / P_E0 tie)
            p = e[rng.integers(2)] + h * perpendicular(rng, d)
        elif kind == 3:  # on the line beyond an endpoint
            p = e[0] + rng.choice([-0.5, 1.5]) * d + h * perpendicular(rng, d)
        else:  # a tiny or zero-length edge
            e[1] = e[0] + rng.choice([0.0, 1e-12, 1e-7]) * rng.normal(size=3)
            p = rng.uniform(-1, 1, size=3)
        configs.append(random_transform(rng, np.vstack([p, e])))
    return np.array(configs)


def point_point_configs(rng, n):
    configs = []
    for i in range(n):
        p0 = rng.uniform(-1, 1, size=3)
        p1 = p0 + rng.choice([0.0, 1e-12, 1e-6, 1.0]) * rng.normal(size=3)
        configs.append(random_transform(rng, np.vstack([p0, p1])))
    return np.array(configs)


# ---- the comparison --------------------------------------------------------------------------

class Report:
    """Per (kernel, quantity): count and largest err; a failure list."""

    def __init__(self):
        self.rows = []
        self.failures = []
        self.errors = {}  # (kernel, quantity): err per configuration
        self.sizes = {}  # (kernel, quantity): its denominator per configuration

    def compare(self, kernel, quantity, grip, ref, floors, rtol):
        """grip, ref: (n, k) arrays; floors: (n,). Records the worst config."""
        grip = np.asarray(grip, float).reshape(len(floors), -1)
        ref = np.asarray(ref, float).reshape(len(floors), -1)
        diff = np.max(np.abs(grip - ref), axis=1)
        size = np.maximum(np.maximum(np.max(np.abs(grip), axis=1), np.max(np.abs(ref), axis=1)),
                          floors)
        err = np.where(diff == 0.0, 0.0, diff / np.where(size > 0, size, 1.0))
        err = np.where(np.isfinite(err), err, np.inf)
        worst = int(np.argmax(err)) if len(err) else 0
        largest = float(err[worst]) if len(err) else 0.0
        self.rows.append((kernel, quantity, len(err), largest, rtol))
        self.errors[(kernel, quantity)] = err
        self.sizes[(kernel, quantity)] = size
        if largest > rtol:
            self.failures.append(f"{kernel} {quantity}: err {largest:.3g} > rtol {rtol:g} at "
                                 f"configuration {worst}")
        return largest

    def check(self, kernel, what, ok, detail):
        self.rows.append((kernel, what, None, None, None))
        if not ok:
            self.failures.append(f"{kernel} {what}: {detail}")

    def note(self, kernel, text):
        self.rows.append((kernel, text, None, None, None))

    def print(self):
        for kernel, quantity, n, largest, rtol in self.rows:
            if n is None:
                print(f"  {kernel:32s} {quantity}")
            else:
                print(f"  {kernel:32s} {quantity:22s} n={n:6d}  max rel diff {largest:9.3g}"
                      f"  (rtol {rtol:g})")


def coordinate_floor(configs):
    """Per configuration: its largest |coordinate| L and its diameter h."""
    flat = configs.reshape(len(configs), -1, 3)
    big = np.max(np.abs(flat), axis=(1, 2))
    diameter = np.max(np.linalg.norm(flat[:, :, None, :] - flat[:, None, :, :], axis=3),
                      axis=(1, 2))
    return big, diameter


def run_grip(program, inputs):
    """inputs: {kernel: (n, width) array} -> {kernel: (n, out_width) array}."""
    with tempfile.TemporaryDirectory(prefix="ipctk_oracle_") as tmp:
        for name, rows in inputs.items():
            np.ascontiguousarray(rows, dtype="<f8").tofile(os.path.join(tmp, name + ".in"))
        subprocess.run([program, tmp], check=True)
        return {name: np.fromfile(os.path.join(tmp, name + ".out"), dtype="<f8").reshape(
            len(rows), -1) for name, rows in inputs.items()}


# ---- kernels ---------------------------------------------------------------------------------
# Each `reference_*` returns ipctk's values laid out as kernel_values.cpp writes grip's, and each
# `compare_*` compares two such arrays (the self-check reuses it on perturbed grip values).

DISTANCES = {
    # name: (vertices, ipctk functions, ipctk type enum)
    "point_point_distance": (2, "point_point_distance", None),
    "point_edge_distance": (3, "point_edge_distance", ipctk.PointEdgeDistanceType),
    "point_triangle_distance": (4, "point_triangle_distance", ipctk.PointTriangleDistanceType),
    "edge_edge_distance": (4, "edge_edge_distance", ipctk.EdgeEdgeDistanceType),
}


def reference_distance(name, configs, grip_out):
    """ipctk's type, value (AUTO), value / gradient / Hessian at grip's type."""
    _, fn, enum = DISTANCES[name]
    value = getattr(ipctk, fn)
    gradient = getattr(ipctk, fn + "_gradient")
    hessian = getattr(ipctk, fn + "_hessian")
    rows = []
    for x, out in zip(configs, grip_out):
        pts = list(x)
        if enum is None:
            rows.append(np.concatenate([[value(*pts)], gradient(*pts), hessian(*pts).ravel()]))
            continue
        own_type = int(getattr(ipctk, fn + "_type")(*pts))
        grip_type = enum(int(out[0]))
        rows.append(np.concatenate([[own_type, value(*pts), value(*pts, grip_type)],
                                    gradient(*pts, grip_type),
                                    hessian(*pts, grip_type).ravel()]))
    return np.array(rows)


def compare_distance(report, name, configs, grip, ref):
    nv = DISTANCES[name][0]
    big, diameter = coordinate_floor(configs)
    # Round-off of a squared distance ~ eps L h (differences of coordinates of size L, times a
    # length h); of its gradient ~ eps L; its Hessian entries are O(1) in units of the
    # configuration (2 I for points; 1 / sin for slivers, which the max entry then carries).
    floors = {"value": big * diameter, "gradient": big, "hessian": np.ones(len(configs))}
    dof = 3 * nv
    if DISTANCES[name][2] is None:
        report.compare(name, "value", grip[:, 0], ref[:, 0], floors["value"], RTOL["value"])
        report.compare(name, "gradient", grip[:, 1:1 + dof], ref[:, 1:1 + dof],
                       floors["gradient"], RTOL["gradient"])
        report.compare(name, "hessian", grip[:, 1 + dof:], ref[:, 1 + dof:], floors["hessian"],
                       RTOL["hessian"])
        return
    differ = grip[:, 0] != ref[:, 0]
    report.compare(name, "value", grip[~differ, 1], ref[~differ, 1], floors["value"][~differ],
                   RTOL["value"])
    report.compare(name, "value at grip's type", grip[:, 1], ref[:, 2], floors["value"],
                   RTOL["value"])
    # Where the types differ (ties, and nearly parallel edges, where ipctk picks an endpoint-edge
    # pair by its parallel rule and grip the nearest of the four) grip's distance must not exceed
    # ipctk's beyond round-off; it may be smaller (a closer pair). Both in units of the floor.
    excess = (grip[differ, 1] - ref[differ, 1]) / floors["value"][differ]
    report.check(name, f"types differ in {int(differ.sum())} of {len(differ)} (compared at "
                       f"grip's type); there grip's distance is below ipctk's by at most "
                       f"{-excess.min(initial=0):.3g}, above by {excess.max(initial=0):.3g}",
                 excess.max(initial=0) <= RTOL["value"],
                 "grip's distance exceeds ipctk's")
    report.compare(name, "gradient", grip[:, 2:2 + dof], ref[:, 3:3 + dof], floors["gradient"],
                   RTOL["gradient"])
    report.compare(name, "hessian", grip[:, 2 + dof:], ref[:, 3 + dof:], floors["hessian"],
                   RTOL["hessian"])


def barrier_inputs(rng, n):
    dhat = 10.0 ** rng.uniform(-8, 0, size=n)
    ratio = np.concatenate([10.0 ** rng.uniform(-12, 0, size=n - n // 4),
                            1.0 - 10.0 ** rng.uniform(-15, -1, size=n // 8),
                            1.0 + rng.uniform(0, 1, size=n - (n - n // 4) - n // 8)])
    return np.column_stack([ratio * dhat, dhat])


def compare_barrier(report, inputs, grip, ref):
    d, dhat = inputs[:, 0], inputs[:, 1]
    # b ~ dhat^2, b' ~ dhat, b'' ~ 1 in the barrier's own units. Near d = dhat the two
    # libraries' formulas cancel differently (ipctk's 1 - dhat / d in b', (dhat / d + 2) dhat / d
    # - 3 in b'', whose round-off is ~10 eps), so values below 1e-6 of those units (1e-4 for
    # b'') are compared at that scale.
    units = [("b", 1e-6 * dhat**2), ("b'", 1e-6 * dhat), ("b''", 1e-4 * np.ones_like(d))]
    for j, (q, floor) in enumerate(units):
        report.compare("barrier", q, grip[:, j], ref[:, j], floor, RTOL["value"])


def mollifier_inputs(rng, configs):
    """Nearly parallel edge pairs (the mollifier's active zone) and random ones, with rest
    positions equal to, or a small perturbation of, the current ones."""
    rest = configs + rng.normal(size=configs.shape) * 1e-3 * np.max(np.abs(configs), axis=(1, 2),
                                                                      keepdims=True)
    keep = rng.random(len(configs)) < 0.5
    rest[keep] = configs[keep]
    return np.concatenate([configs.reshape(len(configs), -1), rest.reshape(len(rest), -1)], axis=1)


def reference_mollifier(inputs):
    rows = []
    for row in inputs:
        x, rest = list(row[:12].reshape(4, 3)), list(row[12:].reshape(4, 3))
        eps_x = ipctk.edge_edge_mollifier_threshold(*rest)
        rows.append(np.concatenate([[eps_x, ipctk.edge_edge_cross_squarednorm(*x),
                                     ipctk.edge_edge_mollifier(*x, eps_x)],
                                    ipctk.edge_edge_mollifier_gradient(*x, eps_x),
                                    ipctk.edge_edge_mollifier_hessian(*x, eps_x).ravel()]))
    return np.array(rows)


def compare_mollifier(report, inputs, grip, ref):
    configs = inputs[:, :12].reshape(-1, 4, 3)
    big, diameter = coordinate_floor(configs)
    eps_x = ref[:, 0]
    # x = |a x b|^2 ~ h^4 with round-off eps L h^3; m is O(1) with m' ~ 1 / eps_x, so the
    # gradient's round-off is eps L h^3 / eps_x and the Hessian's eps h^2 / eps_x (per unit).
    name = "edge_edge_mollifier"
    report.compare(name, "eps_x", grip[:, 0], ref[:, 0], np.zeros(len(ref)), RTOL["value"])
    report.compare(name, "x = |a x b|^2", grip[:, 1], ref[:, 1], big * diameter**3,
                   RTOL["value"])
    active = ref[:, 1] < eps_x
    report.note(name, f"{int(active.sum())} of {len(ref)} pairs inside the mollifier "
                      "(x < eps_x)")
    ratio = big * diameter**3 / eps_x
    report.compare(name, "m", grip[:, 2], ref[:, 2], ratio, RTOL["value"])
    report.compare(name, "gradient", grip[:, 3:15], ref[:, 3:15], ratio / big, RTOL["gradient"])
    report.compare(name, "hessian", grip[:, 15:], ref[:, 15:], ratio / (big * diameter),
                   RTOL["hessian"])


def mollifier_scalar_inputs(rng, n):
    eps_x = 10.0 ** rng.uniform(-12, 0, size=n)
    ratio = np.concatenate([rng.uniform(0, 1, size=n - n // 4), [0.0, 1.0],
                            rng.uniform(1, 3, size=n // 4 - 2)])
    return np.column_stack([ratio * eps_x, eps_x])


def reference_mollifier_scalar(inputs):
    return np.array([[ipctk.edge_edge_mollifier(x, e), ipctk.edge_edge_mollifier_gradient(x, e),
                      ipctk.edge_edge_mollifier_hessian(x, e)] for x, e in inputs])


def compare_mollifier_scalar(report, inputs, grip, ref):
    eps_x = inputs[:, 1]
    name = "edge_edge_mollifier(x)"
    zero = np.zeros(len(eps_x))
    report.compare(name, "m", grip[:, 0], ref[:, 0], zero, RTOL["value"])
    report.compare(name, "m'", grip[:, 1], ref[:, 1], zero, RTOL["gradient"])
    report.compare(name, "m''", grip[:, 2], ref[:, 2], zero, RTOL["hessian"])


def friction_mollifier_inputs(rng, n):
    eps = 10.0 ** rng.uniform(-8, 0, size=n)
    ratio = np.concatenate([rng.uniform(0, 1, size=n - n // 4), [0.0, 1.0, 1e-12],
                            rng.uniform(1, 10, size=n // 4 - 3)])
    return np.column_stack([ratio * eps, eps])


def reference_friction_mollifier(inputs):
    rows = []
    for y, eps in inputs:
        f1_over_y_derivative = ipctk.smooth_friction_f2_x_minus_f1_over_x3(y, eps) * y \
            if y > 0 else np.nan
        rows.append([ipctk.smooth_friction_f0(y, eps), ipctk.smooth_friction_f1(y, eps),
                     ipctk.smooth_friction_f1_over_x(y, eps), f1_over_y_derivative])
    return np.array(rows)


def compare_friction_mollifier(report, inputs, grip, ref):
    y = inputs[:, 0]
    name = "friction_mollifier"
    zero = np.zeros(len(y))
    report.compare(name, "f0", grip[:, 0], ref[:, 0], zero, RTOL["value"])
    report.compare(name, "f1", grip[:, 1], ref[:, 1], zero, RTOL["value"])
    report.compare(name, "f1/y", grip[:, 2], ref[:, 2], zero, RTOL["gradient"])
    positive = y > 0
    report.compare(name, "(f1/y)' = ipctk f2.. * y", grip[positive, 3], ref[positive, 3],
                   zero[positive], RTOL["hessian"])


FRICTION = {
    # name: (vertices, configurations, ipctk collision from positions)
    "friction_point_point": (2, point_point_configs, lambda x, bp: (
        ipctk.VertexVertexTangentialCollision(ipctk.VertexVertexNormalCollision(0, 1), x, bp))),
    "friction_point_edge": (3, point_edge_configs, lambda x, bp: (
        ipctk.EdgeVertexTangentialCollision(ipctk.EdgeVertexNormalCollision(0, 0), x, bp))),
    "friction_point_triangle": (4, point_triangle_configs, lambda x, bp: (
        ipctk.FaceVertexTangentialCollision(ipctk.FaceVertexNormalCollision(0, 0), x, bp))),
    "friction_edge_edge": (4, edge_edge_configs, lambda x, bp: (
        ipctk.EdgeEdgeTangentialCollision(ipctk.EdgeEdgeNormalCollision(0, 1, 0.0), x, bp))),
}
MU = 0.4


def friction_inputs(rng, name, n):
    """Lagged positions with a usable tangent frame (no degenerate primitive: there the frame is
    each library's own fallback), displacements around eps, lambda and eps."""
    nv, make, _ = FRICTION[name]
    configs = make(rng, 2 * n)
    _, diameter = coordinate_floor(configs)
    flat = configs.reshape(len(configs), nv, 3)
    ok = np.ones(len(configs), bool)
    if nv == 3:
        ok = np.linalg.norm(flat[:, 2] - flat[:, 1], axis=1) > 1e-3 * diameter
        cross = np.cross(flat[:, 2] - flat[:, 1], flat[:, 0] - flat[:, 1])
        ok &= np.linalg.norm(cross, axis=1) > 1e-3 * diameter**2
    elif nv == 4:
        edge_edge = name == "friction_edge_edge"
        a = flat[:, 1] - flat[:, 0] if edge_edge else flat[:, 2] - flat[:, 1]
        b = flat[:, 3] - flat[:, 2] if edge_edge else flat[:, 3] - flat[:, 1]
        cross = np.linalg.norm(np.cross(a, b), axis=1)
        ok = cross > 1e-3 * np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1)
    else:
        ok = np.linalg.norm(flat[:, 0] - flat[:, 1], axis=1) > 1e-3 * diameter
    configs = configs[ok][:n]
    n = len(configs)
    diameter = diameter[ok][:n]
    eps = diameter * 10.0 ** rng.uniform(-4, -1, size=n)
    dx = rng.normal(size=(n, 3 * nv)) * (eps * 10.0 ** rng.uniform(-2, 1, size=n))[:, None]
    mu_lambda = MU * 10.0 ** rng.uniform(-3, 3, size=n)
    return np.column_stack([configs.reshape(n, -1), dx, mu_lambda, eps])


def reference_friction(name, inputs):
    nv, _, collision = FRICTION[name]
    barrier = ipctk.BarrierPotential(1.0, 1.0)
    rows = []
    for row in inputs:
        x, dx = row[:3 * nv], row[3 * nv:6 * nv]
        mu_lambda, eps = row[6 * nv], row[6 * nv + 1]
        c = collision(x, barrier)
        c.normal_force_magnitude = mu_lambda / MU
        c.mu_s = c.mu_k = c.mu_s_effective_lagged = c.mu_k_effective_lagged = MU
        potential = ipctk.FrictionPotential(eps)
        coords = np.zeros(2)
        coords[:len(c.closest_point)] = c.closest_point
        basis = c.tangent_basis
        rows.append(np.concatenate([(basis @ basis.T).ravel(), coords, [potential(c, dx)],
                                    potential.gradient(c, dx),
                                    potential.hessian(c, dx).ravel()]))
    return np.array(rows)


def compare_friction(report, name, inputs, grip, ref):
    nv = FRICTION[name][0]
    n = len(inputs)
    dof = 3 * nv
    basis = grip[:, :6].reshape(n, 3, 2)
    projector = np.einsum("nij,nkj->nik", basis, basis).reshape(n, 9)
    one = np.ones(n)
    report.compare(name, "basis projector", projector, ref[:, :9], one, RTOL["value"])
    report.compare(name, "closest point", grip[:, 6:8], ref[:, 9:11], one, RTOL["value"])
    mu_lambda, eps = inputs[:, 6 * nv], inputs[:, 6 * nv + 1]
    # D ~ mu lambda eps, grad ~ mu lambda, hess ~ mu lambda / eps (f0, f1, f1/y's units).
    report.compare(name, "value", grip[:, 8], ref[:, 11], mu_lambda * eps * 1e-6, RTOL["value"])
    report.compare(name, "gradient", grip[:, 9:9 + dof], ref[:, 12:12 + dof], mu_lambda * 1e-6,
                   RTOL["gradient"])
    report.compare(name, "hessian", grip[:, 9 + dof:], ref[:, 12 + dof:],
                   mu_lambda / eps * 1e-6, RTOL["hessian"])


class SqrtBarrier(ipctk.Barrier):
    """grip's parameterization for ipctk's BarrierPotential, which calls its barrier with the
    squared distance s: b(s) = ipctk.barrier(sqrt(s), dhat) and its derivatives in s."""

    def __init__(self, dhat):
        ipctk.Barrier.__init__(self)
        self.dhat = dhat

    def __call__(self, s, _):
        return ipctk.barrier(math.sqrt(s), self.dhat)

    def first_derivative(self, s, _):
        d = math.sqrt(s)
        return ipctk.barrier_first_derivative(d, self.dhat) / (2.0 * d)

    def second_derivative(self, s, _):
        d = math.sqrt(s)
        return (ipctk.barrier_second_derivative(d, self.dhat) -
                ipctk.barrier_first_derivative(d, self.dhat) / d) / (4.0 * s)

    def units(self, _):
        return 1.0


def contact_barrier_inputs(rng, name, n):
    """Pairs at a positive distance, d_hat from 1.05 to 10 times it (active), or below it
    (inactive, 1 in 8); edge pairs get the mollifier threshold of their rest (= current or
    nearby) positions, so nearly parallel ones are mollified."""
    edge_edge = name.endswith("edge_edge")
    configs = (edge_edge_configs if edge_edge else point_triangle_configs)(rng, 2 * n)
    dist_fn = ipctk.edge_edge_distance if edge_edge else ipctk.point_triangle_distance
    dist = np.sqrt([dist_fn(*list(x)) for x in configs])
    _, diameter = coordinate_floor(configs)
    keep = dist > 1e-6 * diameter  # the barrier's round-off at contact is the distances'
    configs, dist = configs[keep][:n], dist[keep][:n]
    n = len(configs)
    factor = np.where(rng.random(n) < 0.125, rng.uniform(0.5, 0.99, n), rng.uniform(1.05, 10, n))
    kappa = 10.0 ** rng.uniform(-2, 4, size=n)
    eps_x = np.zeros(n)
    if edge_edge:
        rest = mollifier_inputs(rng, configs)[:, 12:]
        eps_x = np.array([ipctk.edge_edge_mollifier_threshold(*list(r.reshape(4, 3)))
                          for r in rest])
    return np.column_stack([configs.reshape(n, -1), dist * factor, kappa, eps_x])


# Point-triangle pairs become, in ipctk, the collision of their distance type: a face-vertex
# collision (point-plane distance) for P_T, an edge-vertex or vertex-vertex one otherwise, on
# the stencil's vertices (positions in the 4-vertex pair, and ipctk's constructor).
POINT_TRIANGLE_COLLISION = {
    6: ([0, 1, 2, 3], lambda: ipctk.FaceVertexNormalCollision(0, 0)),
    3: ([0, 1, 2], lambda: ipctk.EdgeVertexNormalCollision(0, 0)),
    4: ([0, 2, 3], lambda: ipctk.EdgeVertexNormalCollision(0, 0)),
    5: ([0, 3, 1], lambda: ipctk.EdgeVertexNormalCollision(0, 0)),
    0: ([0, 1], lambda: ipctk.VertexVertexNormalCollision(0, 1)),
    1: ([0, 2], lambda: ipctk.VertexVertexNormalCollision(0, 1)),
    2: ([0, 3], lambda: ipctk.VertexVertexNormalCollision(0, 1)),
}


def reference_contact_barrier(name, inputs, grip_types):
    """grip_types: grip's point-triangle distance types of the pairs (at a tie, such as a point
    over a vertex or a triangle with two coincident vertices, the pair is compared as grip
    classifies it; the distance comparison checks that the type realizes the distance)."""
    rows = []
    edge_edge = name.endswith("edge_edge")
    for row, grip_type in zip(inputs, grip_types):
        x, dhat, kappa, eps_x = row[:12], row[12], row[13], row[14]
        barrier = SqrtBarrier(dhat)  # kept alive: the potential holds it by reference only
        potential = ipctk.BarrierPotential(barrier, dhat, kappa)
        if edge_edge:
            vertices, collision = [0, 1, 2, 3], ipctk.EdgeEdgeNormalCollision(0, 1, eps_x)
        else:
            vertices, make = POINT_TRIANGLE_COLLISION[int(grip_type)]
            collision = make()
        dofs = np.array([3 * v + k for v in vertices for k in range(3)])
        gradient, hessian = np.zeros(12), np.zeros((12, 12))
        gradient[dofs] = potential.gradient(collision, x[dofs])
        hessian[np.ix_(dofs, dofs)] = potential.hessian(collision, x[dofs])
        rows.append(np.concatenate([[potential(collision, x[dofs])], gradient, hessian.ravel()]))
    return np.array(rows)


def compare_contact_barrier(report, name, inputs, grip, ref):
    configs = inputs[:, :12].reshape(-1, 4, 3)
    big, diameter = coordinate_floor(configs)
    dhat, kappa, eps_x = inputs[:, 12], inputs[:, 13], inputs[:, 14]
    # kappa b ~ kappa dhat^2 in the barrier's units, 1e-6 of which is compared at that scale.
    # A mollified edge pair adds the round-off of x = |a x b|^2 (eps L h^3, from intermediates of
    # size L h^3) carried by m' = 2 / eps_x into kappa b m: for parallel edges x is round-off
    # alone, different in each library.
    floor = 1e-6 * kappa * dhat**2
    length = dhat  # the scale of one derivative: d_hat, or a mollified edge's length
    if name.endswith("edge_edge"):
        b = np.array([ipctk.barrier(math.sqrt(ipctk.edge_edge_distance(*list(x))), h)
                      for x, h in zip(configs, dhat)])
        mollified = np.array([ipctk.edge_edge_cross_squarednorm(*list(x)) < e
                              for x, e in zip(configs, eps_x)])
        floor = np.maximum(floor, np.where(mollified, kappa * np.abs(b) * 2.0 / eps_x * big *
                                           diameter**3, 0.0))
        report.note(name, f"{int(mollified.sum())} of {len(mollified)} pairs mollified")
        a, b = configs[:, 1] - configs[:, 0], configs[:, 3] - configs[:, 2]
        length = np.where(mollified, np.minimum(dhat, np.minimum(np.linalg.norm(a, axis=1),
                                                                 np.linalg.norm(b, axis=1))), dhat)
        # grad x = 2 (|b|^2 a - (a.b) b) cancels to |a| |b|^2 sin, so it is known to eps / sin
        # only, and the derivatives of m with it: a relative floor of 64 eps / sin.
        sin = np.linalg.norm(np.cross(a, b), axis=1) / (np.linalg.norm(a, axis=1) *
                                                        np.linalg.norm(b, axis=1))
        noise = np.where(mollified, 64 * EPS / np.maximum(sin, EPS) / RTOL["hessian"], 0.0)
    else:
        noise = np.zeros(len(inputs))
    top_gradient = np.max(np.abs(ref[:, 1:13]), axis=1)
    top_hessian = np.max(np.abs(ref[:, 13:]), axis=1)
    report.compare(name, "value", grip[:, 0], ref[:, 0], floor, RTOL["value"])
    report.compare(name, "gradient", grip[:, 1:13], ref[:, 1:13],
                   np.maximum(floor / length, noise * top_gradient), RTOL["gradient"])
    report.compare(name, "hessian", grip[:, 13:], ref[:, 13:],
                   np.maximum(floor / length**2, noise * top_hessian), RTOL["hessian"])


def accd_inputs(rng, name, n):
    """Motions over [0, 1]: a primitive driven into the other (impact), grazing past, random,
    and shared motion (none relative); minimum separation 0 or a fraction of the start gap."""
    edge_edge = name.endswith("edge_edge")
    configs = (edge_edge_configs if edge_edge else point_triangle_configs)(rng, 2 * n)
    dist_fn = ipctk.edge_edge_distance if edge_edge else ipctk.point_triangle_distance
    dist = np.sqrt([dist_fn(*list(x)) for x in configs])
    _, diameter = coordinate_floor(configs)
    keep = dist > 1e-6 * diameter
    configs, dist = configs[keep][:n], dist[keep][:n]
    diameter = diameter[keep][:n]
    n = len(configs)
    rows = []
    for i, x0 in enumerate(configs):
        kind = i % 4
        first = slice(0, 1) if not edge_edge else slice(0, 2)
        other = slice(1, 4) if not edge_edge else slice(2, 4)
        toward = x0[other].mean(axis=0) - x0[first].mean(axis=0)
        x1 = x0.copy()
        if kind == 0:  # drive the first primitive through the other's centroid
            x1[first] += rng.uniform(1.1, 3.0) * toward
        elif kind == 1:  # random motions of the size of the pair
            x1 += rng.normal(size=x0.shape) * diameter[i] * rng.uniform(0.1, 2.0)
        elif kind == 2:  # both move, one faster: relative approach and rotation
            x1 += rng.normal(size=3) * diameter[i]
            x1[first] += rng.uniform(0.5, 2.0) * toward + rng.normal(size=3) * 0.1 * diameter[i]
        else:  # the same rigid translation for all: no relative motion
            x1 += rng.normal(size=3) * diameter[i]
        min_sep = rng.choice([0.0, 0.0, 0.1, 0.5]) * dist[i]
        rows.append(np.concatenate([x0.ravel(), x1.ravel(), [min_sep, 1.0]]))
    return np.array(rows)


def reference_accd(name, inputs):
    ccd = ipctk.AdditiveCCD(conservative_rescaling=0.9)
    query = ccd.edge_edge_ccd if name.endswith("edge_edge") else ccd.point_triangle_ccd
    rows = []
    for row in inputs:
        x = row[:24].reshape(8, 3)
        hit, toi = query(*list(x), min_distance=row[24], tmax=row[25])
        rows.append([toi if hit else row[25], 1.0 if hit else 0.0])
    return np.array(rows)


def ipctk_trailing_step_clears(name, row, toi):
    """Whether ipctk's lower bound at its own toi already passes t_max: (toi, toi + t_l) then
    holds no contact, so "no impact by t_max" is what the bound proves (grip's answer)."""
    edge_edge = name.endswith("edge_edge")
    x0, x1 = row[:12].reshape(4, 3), row[12:24].reshape(4, 3)
    dx = x1 - x0
    dx = dx - dx.mean(axis=0)
    norms = np.linalg.norm(dx, axis=1)
    l_p = max(norms[0], norms[1]) + max(norms[2], norms[3]) if edge_edge else \
        norms[0] + max(norms[1:])
    dist_fn = ipctk.edge_edge_distance if edge_edge else ipctk.point_triangle_distance
    d = math.sqrt(dist_fn(*list(x0 + toi * dx)))
    xi = row[24]
    return toi + 0.9 * (d - xi) / l_p > row[25]


def remaining_gap_ratio(name, row, toi):
    """(d(toi) - xi) / (s (d0 - xi)) by ipctk's distance on the linear path: at least 1 where
    ACCD may stop (its rule: the step to toi left at least s of the starting gap)."""
    edge_edge = name.endswith("edge_edge")
    x0, x1 = row[:12].reshape(4, 3), row[12:24].reshape(4, 3)
    dist_fn = ipctk.edge_edge_distance if edge_edge else ipctk.point_triangle_distance
    d0 = math.sqrt(dist_fn(*list(x0)))
    d = math.sqrt(dist_fn(*list(x0 + toi * (x1 - x0))))
    return (d - row[24]) / (0.1 * (d0 - row[24]))


def compare_accd(report, name, inputs, grip, ref):
    toi_g, hit_g, toi_i, hit_i = grip[:, 0], grip[:, 1] > 0, ref[:, 0], ref[:, 1] > 0
    both = hit_g & hit_i
    missed = hit_i & ~hit_g
    cleared = np.array([ipctk_trailing_step_clears(name, inputs[i], toi_i[i])
                        for i in np.flatnonzero(missed)], bool)
    report.check(name, f"impacts: ipctk {int(hit_i.sum())}, grip {int(hit_g.sum())}, both "
                       f"{int(both.sum())} of {len(inputs)}", True, "")
    report.check(name, f"ipctk impact, grip none: {int(missed.sum())}, all past t_max by ipctk's "
                       f"own bound: {bool(cleared.all())}", cleared.all(),
                 f"configurations {np.flatnonzero(missed)[~cleared].tolist()}")
    earlier = np.where(both, toi_i - toi_g, 0.0)
    worst = int(np.argmax(earlier)) if len(earlier) else 0
    report.check(name, f"grip earlier by at most {earlier.max():.3g} (ipctk {toi_i[worst]:.6g}, "
                       f"grip {toi_g[worst]:.6g}); grip impact, ipctk none: "
                       f"{int((hit_g & ~hit_i).sum())}", True, "")
    # Where grip's toi is the later one (grazing motions of 1e3 to 1e5 steps, where ipctk's
    # accumulated positions drift off the linear path), grip's stop must still leave the rescaled
    # gap by ipctk's distance; 1e-9 is the distances' round-off at that gap.
    later = np.flatnonzero(both & (toi_g > toi_i))
    ratio = np.array([remaining_gap_ratio(name, inputs[i], toi_g[i]) for i in later])
    lateness = (toi_g[later] - toi_i[later]) / toi_i[later]
    short = later[ratio < 1 - 1e-9]
    report.check(name, f"grip later: {len(later)}, by at most {lateness.max(initial=0):.3g} "
                       f"relative ({int(grip[later, 2].max(initial=0))} steps), gap left >= "
                       f"{ratio.min(initial=np.inf):.10g} of the rescaled gap",
                 len(short) == 0, f"configurations {short.tolist()} stop inside the gap")


# ---- the run ---------------------------------------------------------------------------------

def build_inputs(rng):
    inputs, extra = {}, {}
    counts = {"point_point_distance": (point_point_configs, 600),
              "point_edge_distance": (point_edge_configs, 1500),
              "point_triangle_distance": (point_triangle_configs, 3200),
              "edge_edge_distance": (edge_edge_configs, 2800)}
    for name, (make, n) in counts.items():
        configs = make(rng, n)
        extra[name] = configs
        inputs[name] = configs.reshape(n, -1)
    inputs["barrier"] = barrier_inputs(rng, 4000)
    s = 10.0 ** rng.uniform(-16, -2, size=1000)
    dhat = np.sqrt(s) * rng.uniform(1.01, 10, size=1000)
    kappa = 10.0 ** rng.uniform(-2, 6, size=1000)
    inputs["barrier_force_magnitude"] = np.column_stack([s, dhat**2, kappa])
    inputs["edge_edge_mollifier_scalar"] = mollifier_scalar_inputs(rng, 2000)
    ee = edge_edge_configs(rng, 1400)
    inputs["edge_edge_mollifier"] = mollifier_inputs(rng, ee)
    inputs["friction_mollifier"] = friction_mollifier_inputs(rng, 4000)
    for name, n in [("friction_point_point", 400), ("friction_point_edge", 600),
                    ("friction_point_triangle", 1000), ("friction_edge_edge", 1000)]:
        inputs[name] = friction_inputs(rng, name, n)
    for name in ("contact_barrier_point_triangle", "contact_barrier_edge_edge"):
        inputs[name] = contact_barrier_inputs(rng, name, 1000)
    for name in ("accd_point_triangle", "accd_edge_edge"):
        inputs[name] = accd_inputs(rng, name, 1000)
    return inputs, extra


def references(program, inputs, extra, grip):
    ref = {}
    for name in DISTANCES:
        ref[name] = reference_distance(name, extra[name], grip[name])
    ref["barrier"] = np.array([[ipctk.barrier(d, h), ipctk.barrier_first_derivative(d, h),
                                ipctk.barrier_second_derivative(d, h)]
                               for d, h in inputs["barrier"]])
    log_barrier = ipctk.ClampedLogBarrier()
    ref["barrier_force_magnitude"] = np.array(
        [[ipctk.barrier_force_magnitude(s, log_barrier, math.sqrt(h2), k)]
         for s, h2, k in inputs["barrier_force_magnitude"]])
    ref["edge_edge_mollifier_scalar"] = reference_mollifier_scalar(
        inputs["edge_edge_mollifier_scalar"])
    ref["edge_edge_mollifier"] = reference_mollifier(inputs["edge_edge_mollifier"])
    ref["friction_mollifier"] = reference_friction_mollifier(inputs["friction_mollifier"])
    for name in FRICTION:
        ref[name] = reference_friction(name, inputs[name])
    pairs = inputs["contact_barrier_point_triangle"][:, :12]
    types = run_grip(program, {"point_triangle_distance": pairs})["point_triangle_distance"][:, 0]
    ref["contact_barrier_point_triangle"] = reference_contact_barrier(
        "contact_barrier_point_triangle", inputs["contact_barrier_point_triangle"], types)
    ref["contact_barrier_edge_edge"] = reference_contact_barrier(
        "contact_barrier_edge_edge", inputs["contact_barrier_edge_edge"], np.zeros(len(pairs)))
    for name in ("accd_point_triangle", "accd_edge_edge"):
        ref[name] = reference_accd(name, inputs[name])
    return ref


def compare_all(report, inputs, extra, grip, ref):
    for name in DISTANCES:
        compare_distance(report, name, extra[name], grip[name], ref[name])
    compare_barrier(report, inputs["barrier"], grip["barrier"], ref["barrier"])
    s, h2, kappa = inputs["barrier_force_magnitude"].T
    report.compare("barrier_force_magnitude", "value", grip["barrier_force_magnitude"],
                   ref["barrier_force_magnitude"], kappa * h2 * 1e-6, RTOL["value"])
    compare_mollifier_scalar(report, inputs["edge_edge_mollifier_scalar"],
                             grip["edge_edge_mollifier_scalar"], ref["edge_edge_mollifier_scalar"])
    compare_mollifier(report, inputs["edge_edge_mollifier"], grip["edge_edge_mollifier"],
                      ref["edge_edge_mollifier"])
    compare_friction_mollifier(report, inputs["friction_mollifier"], grip["friction_mollifier"],
                               ref["friction_mollifier"])
    for name in FRICTION:
        compare_friction(report, name, inputs[name], grip[name], ref[name])
    for name in ("contact_barrier_point_triangle", "contact_barrier_edge_edge"):
        compare_contact_barrier(report, name, inputs[name], grip[name], ref[name])
    for name in ("accd_point_triangle", "accd_edge_edge"):
        compare_accd(report, name, inputs[name], grip[name], ref[name])


def self_check(inputs, extra, grip, ref):
    """Perturbations of grip's values that the comparison must catch: in every configuration,
    the largest entry of a Hessian (or a value) times 1 + 1e-6, or the largest gradient entry's
    sign flipped; and one time of impact moved into the rescaled gap. A configuration resolves
    a perturbation when it moves the entry by more than twice the tolerance band (rtol times
    the denominator of err; a squared distance 1e-12 of its coordinates' scale cannot resolve
    1e-6 of itself). Every resolving configuration must fail, and some must resolve it.
    Returns a line per perturbation and the perturbations not caught."""
    def scaled(name, start, stop=None, factor=1 + 1e-6):
        out = grip[name].copy()
        block = out[:, start:stop]
        col = np.argmax(np.abs(block), axis=1)
        entry = block[np.arange(len(block)), col]
        block[np.arange(len(block)), col] *= factor
        return out, np.abs(entry * (factor - 1))

    def later_toi(name):
        # ipctk's toi / 0.9 (where a head-on approach touches) in the first configuration where
        # that is inside the rescaled gap.
        out = grip[name].copy()
        both = np.flatnonzero((out[:, 1] > 0) & (ref[name][:, 1] > 0) & (ref[name][:, 0] > 0))
        row = next(i for i in both
                   if remaining_gap_ratio(name, inputs[name][i], ref[name][i, 0] / 0.9) < 0.5)
        out[row, 0] = ref[name][row, 0] / 0.9
        return out, None

    perturbations = [
        ("point_point_distance", "value", "value * (1 + 1e-6)",
         scaled("point_point_distance", 0, 1)),
        ("point_edge_distance", "gradient", "gradient sign",
         scaled("point_edge_distance", 2, 11, -1.0)),
        ("point_triangle_distance", "hessian", "hessian entry * (1 + 1e-6)",
         scaled("point_triangle_distance", 14)),
        ("edge_edge_distance", "hessian", "hessian entry * (1 + 1e-6)",
         scaled("edge_edge_distance", 14)),
        ("barrier", "b''", "b'' * (1 + 1e-6)", scaled("barrier", 2, 3)),
        ("edge_edge_mollifier", "hessian", "hessian entry * (1 + 1e-6)",
         scaled("edge_edge_mollifier", 15)),
        ("friction_mollifier", "f1", "f1 * (1 + 1e-6)", scaled("friction_mollifier", 1, 2)),
        ("friction_point_triangle", "gradient", "gradient sign",
         scaled("friction_point_triangle", 9, 21, -1.0)),
        ("friction_edge_edge", "hessian", "hessian entry * (1 + 1e-6)",
         scaled("friction_edge_edge", 21)),
        ("contact_barrier_point_triangle", "hessian", "hessian entry * (1 + 1e-6)",
         scaled("contact_barrier_point_triangle", 13)),
        ("contact_barrier_edge_edge", "hessian", "hessian entry * (1 + 1e-6)",
         scaled("contact_barrier_edge_edge", 13)),
        ("accd_point_triangle", None, "toi inside the rescaled gap", later_toi("accd_point_triangle")),
        ("accd_edge_edge", None, "toi inside the rescaled gap", later_toi("accd_edge_edge")),
    ]
    lines, uncaught = [], []
    original = Report()
    compare_all(original, inputs, extra, grip, ref)
    for name, quantity, label, (perturbed, change) in perturbations:
        report = Report()
        compare_all(report, inputs, extra, {**grip, name: perturbed}, ref)
        if quantity is None:
            caught = any(f.startswith(name) for f in report.failures)
            lines.append(f"{name} {label}: {'caught' if caught else 'NOT caught'}")
        else:
            rtol = RTOL.get(quantity, RTOL["value"])
            resolving = change > 2 * rtol * original.sizes[(name, quantity)]
            failing = report.errors[(name, quantity)] > rtol
            caught = resolving.any() and failing[resolving].all()
            lines.append(f"{name} {label}: resolved by {resolving.sum()} of {len(change)} "
                         f"configurations, caught in {(failing & resolving).sum()}")
        if not caught:
            uncaught.append(f"{name} {label}")
    return lines, uncaught


def main():
    if len(sys.argv) != 2:
        print(__doc__.splitlines()[2], file=sys.stderr)
        return 2
    ipctk.set_logger_level(ipctk.LoggerLevel.off)
    rng = np.random.default_rng(SEED)
    inputs, extra = build_inputs(rng)
    grip = run_grip(sys.argv[1], inputs)
    ref = references(sys.argv[1], inputs, extra, grip)
    report = Report()
    compare_all(report, inputs, extra, grip, ref)
    print(f"ipc-toolkit oracle: grip's kernels against ipctk {ipctk.__version__} (seed {SEED})")
    report.print()
    lines, uncaught = self_check(inputs, extra, grip, ref)
    print("  self-check, perturbations of grip's values:")
    for line in lines:
        print(f"    {line}")
    for label in uncaught:
        report.failures.append(f"self-check: perturbation not caught: {label}")
    if report.failures:
        print("FAIL:")
        for failure in report.failures:
            print(f"  {failure}")
        return 1
    print("PASS: grip's kernels agree with ipc-toolkit")
    return 0


if __name__ == "__main__":
    sys.exit(main())
