#!/usr/bin/env python3
"""High-precision reference values for the homogeneous cube, read by
crates/potentials/tests/polyhedron.rs through tests/reference/polyhedron_cube.json.

Body: the cube [-1, 1]^3 (side 2), mass 1 (density 1/8), G = 1. Conventions of the crate:
Phi = -G rho int dV / |x - p| (negative), acceleration = -grad Phi.

Route (independent of the Werner-Scheeres face/edge sums in the Rust code): the cube's potential
is a triple integral of 1/r over a box, hence an alternating sum over the eight corners of an
antiderivative F with d^3 F / du dv dw = 1/r (u, v, w the corner's offsets from the field point):

    F(u, v, w) = v w ln(u + r) + w u ln(v + r) + u v ln(w + r)
                 - u^2/2 atan(v w / (u r)) - v^2/2 atan(w u / (v r)) - w^2/2 atan(u v / (w r)),

    int_box dV / |x - p| = sum_corners (-1)^(number of lower limits) F(corner - p),

and the acceleration component along x is (F_u differs from dF/du by terms that the corner sum
cancels; the check is d^2 F_u / dv dw = 1/r)
    a_x = -dPhi/dp_x = G rho d/dp_x int = -G rho sum_corners (-1)^(...) F_u(corner - p),
    F_u = w ln(v + r) + v ln(w + r) - u atan(v w / (u r)),
and cyclically. The script does not trust these formulas: it checks d^3F/du dv dw = 1/r and
d^2F_u/dv dw = 1/r by mpmath's numerical differentiation at two points, the acceleration's corner
sum against numerical differentiation of the potential's at two points, and the whole corner sum
against a brute-force triple integral (a 48^3-point Gauss-Legendre product rule) at one
outside point. Limits:
a term whose prefactor vanishes (u = 0 in u^2 atan, u w ln(v + r) with u w = 0) is 0, its limit.
ln(u + r) for u < 0 is evaluated as ln((v^2 + w^2) / (r - u)) (no cancellation).

Precision: mpmath at DPS = 80 digits. The corner sum cancels about 3 log10(distance) + 1 digits
(19 at 1e6 body radii); the script re-evaluates every case at DPS + 20 and records the largest
relative change as the estimated accuracy (it is below 1e-40 for every case).

Usage: python3 tests/reference/polyhedron_cube.py
"""

import json
import os
import time

import mpmath
from mpmath import mp, mpf

DPS = 80


def log_u_plus_r(u, v, w, r):
    if u >= 0:
        return mpmath.log(u + r)
    return mpmath.log((v * v + w * w) / (r - u))


def antiderivative(u, v, w):
    r = mpmath.sqrt(u * u + v * v + w * w)
    total = mpf(0)
    for (a, b, c) in ((u, v, w), (v, w, u), (w, u, v)):
        # b c ln(a + r) and -a^2/2 atan(b c / (a r)), with their limits.
        if b * c != 0:
            total += b * c * log_u_plus_r(a, b, c, r)
        if a != 0:
            total -= a * a / 2 * mpmath.atan(b * c / (a * r))
    return total


def antiderivative_du(u, v, w):
    r = mpmath.sqrt(u * u + v * v + w * w)
    total = mpf(0)
    if w != 0:
        total += w * log_u_plus_r(v, w, u, r)
    if v != 0:
        total += v * log_u_plus_r(w, u, v, r)
    if u != 0:
        total -= u * mpmath.atan(v * w / (u * r))
    return total


def corner_sum(fun, p, perm=(0, 1, 2)):
    total = mpf(0)
    for cx in (-1, 1):
        for cy in (-1, 1):
            for cz in (-1, 1):
                sign = (-1) ** ((cx < 0) + (cy < 0) + (cz < 0))
                d = (mpf(cx) - p[0], mpf(cy) - p[1], mpf(cz) - p[2])
                total += sign * fun(d[perm[0]], d[perm[1]], d[perm[2]])
    return total


RHO = mpf(1) / 8
G = mpf(1)


def field_potential(p):
    return -G * RHO * corner_sum(antiderivative, p)


def field(p):
    """Phi and a at p (a list of three mpf)."""
    phi = -G * RHO * corner_sum(antiderivative, p)
    acc = []
    for axis, perm in ((0, (0, 1, 2)), (1, (1, 2, 0)), (2, (2, 0, 1))):
        acc.append(-G * RHO * corner_sum(antiderivative_du, p, perm))
    return phi, acc


def gauss_legendre(n):
    """Nodes and weights of the n-point Gauss-Legendre rule on [-1, 1] (Newton on P_n)."""
    out = []
    for k in range(1, n + 1):
        x = mpmath.cos(mpmath.pi * (k - mpf(1) / 4) / (n + mpf(1) / 2))
        for _ in range(100):
            p0, p1 = mpf(1), x
            for j in range(2, n + 1):
                p0, p1 = p1, ((2 * j - 1) * x * p1 - (j - 1) * p0) / j
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < mpf(10) ** (-mp.dps + 2):
                break
        out.append((x, 2 / ((1 - x * x) * dp * dp)))
    return out


def validate():
    checks = []
    for (u, v, w) in ((mpf("0.3"), mpf("-0.7"), mpf("1.1")), (mpf("-2.5"), mpf("0.4"), mpf("0.9"))):
        r = mpmath.sqrt(u * u + v * v + w * w)
        d3 = mpmath.diff(antiderivative, (u, v, w), (1, 1, 1))
        d2 = mpmath.diff(antiderivative_du, (u, v, w), (0, 1, 1))
        checks.append({"check": "d3F/du dv dw = 1/r", "rel_diff": float(abs(d3 * r - 1))})
        checks.append({"check": "d2F_u/dv dw = 1/r", "rel_diff": float(abs(d2 * r - 1))})
    # The acceleration's corner sum against numerical differentiation of the potential's.
    for p in ((mpf("1.3"), mpf("-0.6"), mpf("0.45")), (mpf("0.3"), mpf("-0.2"), mpf("0.5"))):
        phi, acc = field(list(p))
        for axis in range(3):
            def shifted(t, axis=axis):
                q = list(p)
                q[axis] += t
                return field_potential(q)
            numeric = -mpmath.diff(shifted, 0)
            checks.append({"check": f"a_{'xyz'[axis]} = -dPhi/dp at {[str(x) for x in p]}",
                           "rel_diff": float(abs(numeric - acc[axis]) / abs(acc[axis]))})
    # Brute force at one outside point: a 48-point Gauss-Legendre rule per axis on the box
    # (the integrand is analytic there, 0.7 from the nearest face).
    with mp.workdps(30):
        p = (mpf("1.7"), mpf("0.4"), mpf("-0.9"))
        nodes, weights = zip(*gauss_legendre(48))
        brute = mpf(0)
        for x, wx in zip(nodes, weights):
            for y, wy in zip(nodes, weights):
                for z, wz in zip(nodes, weights):
                    brute += wx * wy * wz / mpmath.sqrt((x - p[0]) ** 2 + (y - p[1]) ** 2 + (z - p[2]) ** 2)
        closed = corner_sum(antiderivative, p)
        checks.append({"check": "corner sum vs 48^3 Gauss-Legendre at (1.7, 0.4, -0.9)",
                       "rel_diff": float(abs(brute - closed) / abs(closed))})
    return checks


def points():
    s3 = mpmath.sqrt(3)
    out = []
    # Outside near the face x = +1 (a generic lateral position), the edge x = y = 1 and the
    # vertex (1, 1, 1).
    for gap in ("1e-12", "1e-9", "1e-6", "1e-3", "0.1"):
        g = float(gap)
        out.append((f"face gap {gap}", (1 + g, 0.31, -0.57), "outside"))
        out.append((f"edge gap {gap}", (1 + g, 1 + g, 0.23), "outside"))
        out.append((f"vertex gap {gap}", (1 + g, 1 + g / 2, 1 + g / 3), "outside"))
    # On the surface: a face, an edge, a vertex (the limits of the corner sum).
    out.append(("on face", (1.0, 0.31, -0.57), "surface"))
    out.append(("on edge", (1.0, 1.0, 0.23), "surface"))
    out.append(("at vertex", (1.0, 1.0, 1.0), "surface"))
    # Inside.
    out.append(("inside centre", (0.0, 0.0, 0.0), "inside"))
    out.append(("inside generic", (0.3, -0.2, 0.5), "inside"))
    out.append(("inside 1e-9 below a face", (1 - 1e-9, 0.31, -0.57), "inside"))
    out.append(("inside near a vertex", (-0.999, 0.998, -0.997), "inside"))
    # Far, in a generic direction, in units of the circumscribing radius sqrt(3).
    d = [2.0, -3.0, 6.0]
    n = sum(x * x for x in d) ** 0.5
    for k in ("1.2", "2", "4", "7.9", "8.1", "16", "100", "1e3", "1e4", "1e5", "1e6"):
        scale = float(k) * 3 ** 0.5 / n
        out.append((f"far {k} radii", tuple(x * scale for x in d), "outside"))
    # Far along an axis and a diagonal (where symmetric cancellations are strongest).
    for k in ("3", "1e3", "1e6"):
        out.append((f"far {k} radii on x", (float(k) * 3 ** 0.5, 0.0, 0.0), "outside"))
        out.append((f"far {k} radii on diagonal", (float(k), float(k), float(k)), "outside"))
    del s3
    return out


def main():
    mp.dps = DPS
    start = time.time()
    checks = validate()
    cases = []
    worst = 0.0
    for label, p, region in points():
        pm = [mpf(x) for x in p]
        phi, acc = field(pm)
        with mp.workdps(DPS + 20):
            phi2, acc2 = field(pm)
        a_scale = max([abs(x) for x in acc2] + [mpf(10) ** -30])
        change = max([abs((phi2 - phi) / phi)] +
                     [abs(a2 - a) / a_scale for a, a2 in zip(acc, acc2)])
        worst = max(worst, float(change))
        cases.append({
            "label": label,
            "region": region,
            "point": [repr(float(x)) for x in p],
            "potential": mpmath.nstr(phi, 30),
            "acceleration": [mpmath.nstr(a, 30) for a in acc],
        })
    doc = {
        "generator": "tests/reference/polyhedron_cube.py",
        "body": {"vertices": "the cube [-1, 1]^3", "mass": "1", "g": "1"},
        "mpmath_dps": DPS,
        "estimated_relative_accuracy": f"{worst:.1e} (largest change at DPS + 20; outputs have 30 digits)",
        "validation": checks,
        "runtime_seconds": round(time.time() - start, 1),
        "cases": cases,
    }
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "polyhedron_cube.json")
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    print(json.dumps({k: doc[k] for k in ("estimated_relative_accuracy", "validation", "runtime_seconds")}, indent=1))


if __name__ == "__main__":
    main()
