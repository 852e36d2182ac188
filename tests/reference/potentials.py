#!/usr/bin/env python3
"""High-precision reference values for the single-body potentials of surfgrav-potentials.

Writes tests/reference/potentials.json (next to this file), read by
crates/potentials/tests/reference_values.rs. See tests/reference/README.md for provenance.

Conventions (those of the crate): Phi = -G * integral(rho dV / |r - r'|) (negative),
acceleration = -grad Phi, homogeneous bodies, centroid at the origin, spheroid symmetry axis and
ellipsoid c axis along z, disk in the x-y plane.

The values are computed by routes independent of the closed forms in the Rust code:

* Solids (sphere, spheroid, ellipsoid, semi-axes a_1, a_2, a_3 along x, y, z): the Dirichlet
  integral representation (Kellogg, Foundations of Potential Theory, ch. VII; Chandrasekhar,
  Ellipsoidal Figures of Equilibrium, ch. 3)

      Phi   = -pi G rho a1 a2 a3 * int_lam^inf (1 - sum_i x_i^2/(a_i^2+u)) du / Delta(u),
      dPhi/dx_i = 2 pi G rho a1 a2 a3 * x_i * int_lam^inf du / ((a_i^2+u) Delta(u)),
      Delta(u) = sqrt((a1^2+u)(a2^2+u)(a3^2+u)),

  lam the largest root of sum_i x_i^2/(a_i^2+lam) = 1 outside, lam = 0 inside; pi rho a1 a2 a3 =
  3 M / 4. The substitution a_i^2 + u = P_i(t)/t^2, P_i(t) = L + d_i t^2, L = lam + k,
  k = min a_i^2, d_i = a_i^2 - k >= 0, maps [lam, inf) onto t in (0, 1] with
  du / Delta = 2 L dt / sqrt(P_1 P_2 P_3): a bounded, smooth integrand for every lam (including
  lam ~ 1e16 at 1e8 body radii). Where d_i >> L the integrand changes regime at
  t* = sqrt(L / d_i); the range is split geometrically around each t*. mpmath.quad (tanh-sinh)
  at DPS digits, with its own error estimate checked against a bound on every integral.

* Uniform disk (radius R, sigma = M / (pi R^2)), at cylindrical (rho, z):
      Phi = -G sigma int_0^R 4 s K(m) / sqrt((rho+s)^2+z^2) ds,   m = 4 rho s / ((rho+s)^2+z^2)
  (ring decomposition, K the complete elliptic integral of the first kind, parameter m);
      dPhi/drho = G sigma R int_0^{2 pi} cos(phi) dphi / sqrt(rho^2 + R^2 - 2 rho R cos(phi) + z^2)
  (divergence theorem in the plane: grad over the field point of a uniform lamina's potential is
  a line integral over the rim; exact for z != 0 and, by continuity of the tangential field, on
  the lamina); and
      dPhi/dz = G sigma z int_0^R 4 s E(m) / (((rho-s)^2+z^2) sqrt((rho+s)^2+z^2)) ds.
  On the lamina inside the rim (z = 0, rho < R) the normal field jumps from -2 pi G sigma to
  +2 pi G sigma; the reference gives the mean of the two one-sided limits, 0 (region "surface").

* Point mass: Phi = -G M / r, a = -G M r / r^3 in DPS-digit arithmetic.

Validation (recorded in the JSON under "validation"): each representation is checked against a
genuinely different route on a handful of points: brute-force volume integrals (3-D Gauss-Legendre
product in ellipsoidal-spherical coordinates, and a 2-D ring-reduced mpmath integral for a
spheroid), the sphere's elementary closed forms, direct angular integration of the ring kernels,
five-point differences of the disk potential, and a 2-D area integral over the disk.

Usage: python3 tests/reference/potentials.py [--jobs N]   (N <= 2 on the shared machine)
"""

import argparse
import json
import os
import time
from multiprocessing import Pool

import mpmath
from mpmath import mp, mpf

DPS = 40
# Every quadrature's own error estimate must be below this, relative to the quantity it feeds.
QUAD_REL_BOUND = mpf("1e-32")
# Significant digits written for each value.
OUT_DIGITS = 30

mp.dps = DPS


class QuadratureNotConverged(RuntimeError):
    pass


def quad_rel(f, points, what, scale=None):
    """mpmath.quad of f over consecutive `points`, returning (value, relative error estimate).

    mpmath's tanh-sinh error estimate is absolute (a level-to-level difference floored near
    10^-dps), so the integrand is normalised to make the integral of order one: a first pass
    with the given `scale` (or 1) measures the magnitude, a second pass is run with that
    magnitude if it is far from one. The relative error estimate must be below QUAD_REL_BOUND."""
    s = mpf(1) if scale is None else mpf(scale)
    for _ in range(3):
        value, err = mpmath.quad(lambda t: f(t) / s, points, error=True, maxdegree=10)
        if value != 0 and mpf("1e-3") < abs(value) < mpf("1e3"):
            break
        if value == 0:
            raise QuadratureNotConverged(f"{what}: integral is zero")
        s = s * abs(value)
    rel = err / abs(value)
    if rel > QUAD_REL_BOUND:
        raise QuadratureNotConverged(f"{what}: relative error estimate {mpmath.nstr(rel, 3)}")
    return value * s, rel


def geometric_splits(centre, scale, lo, hi, decades=20):
    """Points centre +- scale * 10^j (j = 0..decades) strictly inside (lo, hi)."""
    pts = []
    if scale <= 0:
        return pts
    for j in range(decades + 1):
        h = scale * mpf(10) ** j
        for p in (centre - h, centre + h):
            if lo < p < hi:
                pts.append(p)
        if h > hi - lo:
            break
    return pts


def merge_points(lo, hi, interior):
    """Sorted, de-duplicated integration breakpoints lo < ... < hi."""
    pts = sorted(set([lo, hi] + [p for p in interior if lo < p < hi]))
    tiny = mpf(10) ** (-(mp.dps - 5)) * max(abs(lo), abs(hi))
    out = [pts[0]]
    for p in pts[1:-1]:
        if p - out[-1] > tiny and hi - p > tiny:
            out.append(p)
    out.append(pts[-1])
    return out


# --------------------------------------------------------------------------------------------
# Solids: Dirichlet integral


def confocal_lambda(x, axes2):
    """Largest root of sum x_i^2/(a_i^2 + lam) = 1 for an outside point (lam > 0), to the
    working precision. The residual cancels (sum ~ 1), so it is solved 20 digits deeper."""
    target = mpf(10) ** (-(mp.dps + 3))
    with mp.workdps(mp.dps + 20):
        s = lambda lam: sum(xi * xi / (ai + lam) for xi, ai in zip(x, axes2)) - 1
        ds = lambda lam: -sum(xi * xi / (ai + lam) ** 2 for xi, ai in zip(x, axes2))
        # s is convex and decreasing on lam > -min a_i^2. Newton from the right of the root
        # (s(r^2) <= 0) lands left of it (halving if it would go negative); from the left it
        # converges monotonically.
        lam = sum(xi * xi for xi in x)
        for _ in range(1000):
            new = lam - s(lam) / ds(lam)
            if new <= 0:
                new = lam / 2
            done = abs(new - lam) <= target * abs(new)
            lam = new
            if done:
                break
        else:
            raise RuntimeError(f"confocal lambda did not converge for {x}")
        if not lam > 0:
            raise RuntimeError(f"confocal lambda not positive for {x}")
    return +lam  # rounded to the working precision


def solid_field(axes, mass, g, point):
    """Dirichlet-integral Phi and acceleration of a homogeneous ellipsoid with semi-axes
    `axes` (along x, y, z), at `point`. All inputs are Python floats (exact doubles).
    Returns (Phi, [a_x, a_y, a_z], "outside" | "inside", worst quadrature relative error)."""
    a = [mpf(v) for v in axes]
    x = [mpf(v) for v in point]
    M, G = mpf(mass), mpf(g)
    a2 = [ai * ai for ai in a]
    inside_measure = sum(xi * xi / ai for xi, ai in zip(x, a2))
    if inside_measure > 1:
        lam = confocal_lambda(x, a2)
        region = "outside"
    elif inside_measure < 1:
        lam = mpf(0)
        region = "inside"
    else:
        raise ValueError("point exactly on the surface")
    k = min(a2)
    d = [ai - k for ai in a2]
    L = lam + k

    # Breakpoints: t* 10^j (j = -3 .. 11) below 1, around each regime change t* = sqrt(L/d_i),
    # so that every piece is smooth on its own scale (power laws between t* and 1).
    splits = []
    for di in d:
        if di > 0:
            tstar = mpmath.sqrt(L / di)
            for j in range(-3, 12):
                p = tstar * mpf(10) ** j
                if p < 1:
                    splits.append(p)
    pts = merge_points(mpf(0), mpf(1), splits)

    def P(t):
        t2 = t * t
        return [L + di * t2 for di in d]

    def weight(t):
        p = P(t)
        return p, 2 * L / mpmath.sqrt(p[0] * p[1] * p[2])

    def f_phi(t):
        p, w = weight(t)
        t2 = t * t
        return (1 - t2 * sum(xi * xi / pi for xi, pi in zip(x, p))) * w

    def f_i(i):
        def f(t):
            p, w = weight(t)
            return t * t / p[i] * w

        return f

    # Scale guesses (the exact values for a sphere far away): J ~ 2/sqrt(L), I_i ~ 2/(3 L^1.5).
    sqrt_l = mpmath.sqrt(L)
    I_phi, rel = quad_rel(f_phi, pts, "solid phi", scale=4 / (3 * sqrt_l))
    potential = -mpf(3) / 4 * G * M * I_phi
    acc = []
    for i in range(3):
        if x[i] == 0:
            acc.append(mpf(0))
            continue
        Ii, rel_i = quad_rel(f_i(i), pts, f"solid I_{i}", scale=2 / (3 * L * sqrt_l))
        rel = max(rel, rel_i)
        acc.append(-mpf(3) / 2 * G * M * x[i] * Ii)
    return potential, acc, region, rel


# --------------------------------------------------------------------------------------------
# Uniform disk: ring decomposition and rim line integral


def ellip_k(m1):
    """K(m) from the complementary parameter m1 = 1 - m: pi / (2 agm(1, sqrt(m1)))."""
    return mpmath.pi / (2 * mpmath.agm(1, mpmath.sqrt(m1)))


def ellip_e(m, m1):
    """E(m) by the arithmetic-geometric mean (Abramowitz & Stegun 17.6), given both m and
    m1 = 1 - m computed without cancellation: E = K (1 - sum_n 2^(n-1) c_n^2), c_0^2 = m."""
    a, b = mpf(1), mpmath.sqrt(m1)
    total = m / 2
    power = mpf(1) / 2
    # Once c_n < 10^-(dps/2 + 3), a_n has converged and later terms are below 10^-dps.
    eps = mpf(10) ** (-(mp.dps // 2 + 3))
    for _ in range(60):
        c = (a - b) / 2
        a, b = (a + b) / 2, mpmath.sqrt(a * b)
        power *= 2
        total += power * c * c
        if abs(c) <= eps * a:
            break
    else:
        raise RuntimeError("AGM did not converge")
    return mpmath.pi / (2 * a) * (1 - total)


def disk_field(radius, mass, g, point):
    """Phi and acceleration of a uniform disk of `radius` in the x-y plane, at `point`.
    Returns (Phi, [a_x, a_y, a_z], "outside" | "surface", worst quadrature relative error)."""
    R = mpf(radius)
    M, G = mpf(mass), mpf(g)
    x, y, z = (mpf(v) for v in point)
    sigma = M / (mpmath.pi * R * R)
    rho = mpmath.sqrt(x * x + y * y)
    az_abs = abs(z)

    # The kernels are sharp at the point of [0, R] nearest to rho, on the scale of the distance
    # from the field point to that ring: split geometrically there (exactly at s = rho for a point
    # on the lamina, where K has an integrable log singularity).
    centre = min(rho, R)
    width = mpmath.sqrt((rho - centre) ** 2 + z * z)
    splits = [centre] + geometric_splits(centre, width, mpf(0), R)
    pts = merge_points(mpf(0), R, splits)

    def ring_k(s):
        q = (rho + s) ** 2 + z * z
        m1 = ((rho - s) ** 2 + z * z) / q  # complementary parameter 1 - m, without cancellation
        if m1 == 0:
            # A tanh-sinh node that rounded onto the log singularity s = rho of an in-plane
            # point: its weight is below 10^-dps, so its (integrable) value does not matter.
            return mpf(0)
        return 4 * s * ellip_k(m1) / mpmath.sqrt(q)

    I_phi, rel = quad_rel(ring_k, pts, "disk phi")
    potential = -G * sigma * I_phi

    # Normal component.
    if z == 0:
        a_z = mpf(0)
        region = "surface" if rho < R else "outside"
    else:
        region = "outside"

        def ring_e(s):
            q = (rho + s) ** 2 + z * z
            d2 = (rho - s) ** 2 + z * z
            return 4 * s * ellip_e(4 * rho * s / q, d2 / q) / (d2 * mpmath.sqrt(q))

        I_z, rel_z = quad_rel(ring_e, pts, "disk a_z")
        rel = max(rel, rel_z)
        a_z = -G * sigma * z * I_z

    # Radial component from the rim line integral. The rim distance is
    # D(phi) = sqrt(rho^2 + R^2 - 2 rho R cos(phi) + z^2); since int cos(phi) / D0 dphi = 0 for
    # the constant D0 = sqrt(rho^2 + R^2 + z^2), the integrand cos(phi) / D is replaced by
    # cos(phi) (1/D - 1/D0) = 2 rho R cos^2(phi) / (D D0 (D + D0)) >= 0: no cancellation, even
    # at 1e8 radii where the plain form cancels to 1e-8.
    if rho == 0:
        a_x = a_y = mpf(0)
    else:
        d0 = mpmath.sqrt(rho * rho + R * R + z * z)

        def rim(phi):
            c = mpmath.cos(phi)
            dist = mpmath.sqrt((rho - R) ** 2 + 4 * rho * R * mpmath.sin(phi / 2) ** 2 + z * z)
            return 2 * rho * R * c * c / (dist * d0 * (dist + d0))

        eps = mpmath.sqrt((rho - R) ** 2 + z * z) / R
        psplits = geometric_splits(mpf(0), eps, mpf(0), mpmath.pi) if eps > 0 else []
        ppts = merge_points(mpf(0), mpmath.pi, psplits)
        I_r, rel_r = quad_rel(rim, ppts, "disk a_rho")
        rel = max(rel, rel_r)
        # Integrand even in phi: the integral over [0, 2 pi] is twice that over [0, pi].
        dphi_drho = G * sigma * R * 2 * I_r
        a_rho = -dphi_drho
        a_x = a_rho * x / rho
        a_y = a_rho * y / rho
    return potential, [a_x, a_y, a_z], region, rel


# --------------------------------------------------------------------------------------------
# Point mass


def point_field(mass, g, point):
    M, G = mpf(mass), mpf(g)
    x = [mpf(v) for v in point]
    r = mpmath.sqrt(sum(v * v for v in x))
    return -G * M / r, [-G * M * v / r**3 for v in x], "outside", mpf(0)


# --------------------------------------------------------------------------------------------
# Cases

GAPS = [1e-12, 1e-9, 1e-6, 1e-3, 0.1]
G_SI, MASS_SI, RADIUS_SI = 6.674e-11, 6e24, 6.4e6

# Directions (need not be unit vectors; (2, -3, 6)/7 and (3, 4, 0)/5 are).
DIR_GENERIC = (2.0, -3.0, 6.0)
DIR_GENERIC2 = (1.0, 1.0, 1.0)
DIR_EQUATORIAL = (3.0, 4.0, 0.0)


def g_str(v):
    """Short label form of a number: 1e-09 -> 1e-9."""
    return f"{v:g}".replace("e-0", "e-").replace("e+0", "e").replace("e+", "e")


def fmt_float(v):
    return repr(float(v))


def to_double(v):
    """Correctly rounded double of an mpf (mpmath rounds to nearest)."""
    return float(v)


def surface_distance(direction, axes):
    """Distance t such that t * direction (direction normalised) lies on the ellipsoid."""
    d = [mpf(v) for v in direction]
    n = mpmath.sqrt(sum(v * v for v in d))
    d = [v / n for v in d]
    return d, 1 / mpmath.sqrt(sum(v * v / mpf(ai) ** 2 for v, ai in zip(d, axes)))


def scaled_point(direction, axes, factor):
    d, t = surface_distance(direction, axes)
    return tuple(to_double(v * t * mpf(factor)) for v in d)


def along(direction, distance):
    d = [mpf(v) for v in direction]
    n = mpmath.sqrt(sum(v * v for v in d))
    return tuple(to_double(v / n * mpf(distance)) for v in d)


def solid_points(axes, triaxial=False, reduced=False):
    """(label, point) pairs for a solid with semi-axes `axes`."""
    out = []
    dirs = [("equatorial x", (1.0, 0.0, 0.0)), ("polar z", (0.0, 0.0, 1.0)), ("generic", DIR_GENERIC)]
    if triaxial:
        dirs.insert(1, ("axis y", (0.0, 1.0, 0.0)))
    for name, d in dirs:
        for gap in GAPS:
            out.append((f"near-surface gap {g_str(gap)} {name}", scaled_point(d, axes, 1 + gap)))
    big = max(axes)
    far = [10, 30, 1e3, 1e5, 1e8]
    for n in far:
        out.append((f"far {g_str(n)} radii generic", along(DIR_GENERIC, n * big)))
    out.append(("interior 0.5 generic", scaled_point(DIR_GENERIC, axes, 0.5)))
    out.append(("interior 0.9 equatorial x", scaled_point((1.0, 0.0, 0.0), axes, 0.9)))
    out.append(("interior 0.999999 generic", scaled_point(DIR_GENERIC2, axes, 0.999999)))
    if reduced:
        return out
    out.append(("on-axis 1.5 polar", scaled_point((0.0, 0.0, 1.0), axes, 1.5)))
    out.append(("on-axis 3 polar below", scaled_point((0.0, 0.0, -1.0), axes, 3.0)))
    out.append(("equatorial plane 1.5", scaled_point(DIR_EQUATORIAL, axes, 1.5)))
    out.append(("equatorial plane 4", scaled_point((-1.0, 2.0, 0.0), axes, 4.0)))
    out.append(("generic 2 (1,1,1)", scaled_point(DIR_GENERIC2, axes, 2.0)))
    out.append(("far 1e3 radii polar", along((0.0, 0.0, 1.0), 1e3 * big)))
    out.append(("far 1e5 radii equatorial", along(DIR_EQUATORIAL, 1e5 * big)))
    out.append(("interior 0.3 polar", scaled_point((0.0, 0.0, 1.0), axes, 0.3)))
    out.append(("interior 1e-3 (1,1,1)", scaled_point(DIR_GENERIC2, axes, 1e-3)))
    return out


def disk_points(R, reduced=False):
    out = []
    for gap in GAPS:
        out.append((f"above lamina z = {g_str(gap)} R at rho = 0.5 R", (0.5 * R, 0.0, gap * R)))
        out.append((f"in plane outside rim rho = (1 + {g_str(gap)}) R", (R * (1 + gap), 0.0, 0.0)))
    out.append(("near rim rho = (1 - 1e-9) R in plane", (R * (1 - 1e-9), 0.0, 0.0)))
    out.append(("near rim rho = R, z = 1e-9 R", (R, 0.0, 1e-9 * R)))
    out.append(("just above lamina z = 1e-12 R on axis", (0.0, 0.0, 1e-12 * R)))
    for n in [10, 30, 1e3, 1e5, 1e8]:
        out.append((f"far {g_str(n)} radii generic", along(DIR_GENERIC, n * R)))
    out.append(("in plane inside rho = 0.5 R (3,4,0)", (0.3 * R, 0.4 * R, 0.0)))
    if reduced:
        return out
    out.append(("near rim rho = (1 + 1e-9) R, z = 1e-9 R", (R * (1 + 1e-9), 0.0, 1e-9 * R)))
    out.append(("near rim rho = (1 - 1e-9) R, z = -1e-9 R", (R * (1 - 1e-9), 0.0, -1e-9 * R)))
    out.append(("just below lamina z = -1e-12 R at rho = 0.5 R", (0.0, -0.5 * R, -1e-12 * R)))
    out.append(("just above lamina z = 1e-12 R at rho = 0.9 R", (0.9 * R, 0.0, 1e-12 * R)))
    out.append(("above lamina z = 1e-9 R at rho = 0.3 R", (0.0, 0.3 * R, 1e-9 * R)))
    for rho in [0.3, 0.9, 0.999]:
        out.append((f"in plane inside rho = {g_str(rho)} R", (rho * R, 0.0, 0.0)))
    for rho in [1.5, 3.0]:
        out.append((f"in plane outside rho = {g_str(rho)} R (3,4,0)", (0.6 * rho * R, 0.8 * rho * R, 0.0)))
    for zz in [1e-6, 1e-3, 0.1, 1.0, 10.0, -2.0]:
        out.append((f"on axis z = {g_str(zz)} R", (0.0, 0.0, zz * R)))
    out.append(("generic (0.3, 0.4, 0.5) R", (0.3 * R, 0.4 * R, 0.5 * R)))
    out.append(("generic (-1.2, 0.7, 0.3) R", (-1.2 * R, 0.7 * R, 0.3 * R)))
    out.append(("generic (0.6, 0, 0.2) R", (0.6 * R, 0.0, 0.2 * R)))
    out.append(("generic (2, 1, -1) R", (2.0 * R, 1.0 * R, -1.0 * R)))
    out.append(("far 1e3 radii in plane", (1e3 * R * 0.6, 1e3 * R * 0.8, 0.0)))
    out.append(("far 1e8 radii in plane", (1e8 * R, 0.0, 0.0)))
    out.append(("far 1e5 radii on axis", (0.0, 0.0, 1e5 * R)))
    return out


def build_cases():
    cases = []

    def add(body, params, shape, pts):
        for label, p in pts:
            cases.append({"body": body, "params": params, "label": f"{shape}: {label}", "point": p})

    # Sphere.
    add("sphere", {"radius": 1.0, "mass": 1.0, "g": 1.0}, "sphere R=1", solid_points((1.0, 1.0, 1.0)))
    add(
        "sphere",
        {"radius": RADIUS_SI, "mass": MASS_SI, "g": G_SI},
        "sphere SI",
        solid_points((RADIUS_SI,) * 3, reduced=True),
    )
    # Spheroids: equatorial radius 1, polar radius c/a.
    for ratio, name in [
        (1e-4, "1e-4"),
        (0.01, "0.01"),
        (0.25, "0.25"),
        (0.99, "0.99"),
        (1 - 1e-9, "1-1e-9"),
        (1.0, "1"),
        (1 + 1e-9, "1+1e-9"),
        (1.01, "1.01"),
        (4.0, "4"),
        (100.0, "100"),
        (1e4, "1e4"),
    ]:
        params = {"equatorial_radius": 1.0, "polar_radius": ratio, "mass": 1.0, "g": 1.0}
        add("spheroid", params, f"spheroid c/a={name}", solid_points((1.0, 1.0, ratio)))
    for polar, name in [(0.25 * RADIUS_SI, "SI c/a=0.25"), (6.378e6 * (1 - 1 / 298.257), "SI Earth-like")]:
        eq = RADIUS_SI if "0.25" in name else 6.378e6
        params = {"equatorial_radius": eq, "polar_radius": polar, "mass": MASS_SI, "g": G_SI}
        add("spheroid", params, f"spheroid {name}", solid_points((eq, eq, polar), reduced=True))
    # Triaxial ellipsoids.
    for axes, name in [
        ((3.0, 2.0, 1.0), "(3,2,1)"),
        ((1.0, 2.0, 3.0), "(1,2,3)"),
        ((2.0, 1.0, 3.0), "(2,1,3)"),
        ((1.0, 1 + 1e-7, 1 - 1e-7), "(1,1+1e-7,1-1e-7)"),
        ((1.0, 0.5, 1e-3), "(1,0.5,1e-3)"),
        ((1e-3, 2e-3, 1.0), "(1e-3,2e-3,1)"),
    ]:
        params = {"a": axes[0], "b": axes[1], "c": axes[2], "mass": 1.0, "g": 1.0}
        add("ellipsoid", params, f"ellipsoid {name}", solid_points(axes, triaxial=True))
    # Uniform disk.
    add("disk", {"radius": 1.0, "mass": 1.0, "g": 1.0}, "disk R=1", disk_points(1.0))
    add("disk", {"radius": RADIUS_SI, "mass": MASS_SI, "g": G_SI}, "disk SI", disk_points(RADIUS_SI, reduced=True))
    # Point mass.
    add(
        "point",
        {"mass": 1.0, "g": 1.0},
        "point M=1",
        [
            ("unit x", (1.0, 0.0, 0.0)),
            ("generic", (0.3, -0.4, 1.2)),
            ("close 1e-3", (1e-3, 2e-3, -2e-3)),
            ("far 1e8", (1e8, -2e8, 3e8)),
            ("close 1e-8", (0.0, -1e-8, 0.0)),
            ("far 1e12", (0.0, 1e12, 1e12)),
        ],
    )
    add(
        "point",
        {"mass": MASS_SI, "g": G_SI},
        "point SI",
        [
            ("surface", (RADIUS_SI, 0.0, 0.0)),
            ("LEO", (4.0e6, 5.0e6, 2.0e6)),
            ("Moon distance", (3.844e8, 0.0, 1.0e7)),
            ("1 au", (1.496e11, -2.0e9, 0.0)),
        ],
    )
    return cases


def axes_of(case):
    p = case["params"]
    if case["body"] == "sphere":
        return (p["radius"],) * 3
    if case["body"] == "spheroid":
        return (p["equatorial_radius"], p["equatorial_radius"], p["polar_radius"])
    return (p["a"], p["b"], p["c"])


def evaluate(case, dps=DPS):
    """Phi, acceleration, region and quadrature relative error estimate of one case."""
    with mp.workdps(dps):
        p = case["params"]
        if case["body"] == "disk":
            return disk_field(p["radius"], p["mass"], p["g"], case["point"])
        if case["body"] == "point":
            return point_field(p["mass"], p["g"], case["point"])
        return solid_field(axes_of(case), p["mass"], p["g"], case["point"])


def evaluate_worker(args):
    case, dps = args
    t0 = time.time()
    try:
        phi, acc, region, rel = evaluate(case, dps)
    except Exception as exc:
        raise RuntimeError(f"case {case['label']!r} at {dps} digits: {exc}") from exc
    # Full working precision, so that runs at different precisions can be compared.
    return (
        mpmath.nstr(phi, dps),
        [mpmath.nstr(v, dps) for v in acc],
        region,
        float(rel),
        time.time() - t0,
    )


def rel_diff(x, y):
    x, y = mpf(x), mpf(y)
    if x == y:
        return mpf(0)
    return abs(x - y) / max(abs(x), abs(y))


def vec_rel_diff(u, v):
    u = [mpf(t) for t in u]
    v = [mpf(t) for t in v]
    num = mpmath.sqrt(sum((a - b) ** 2 for a, b in zip(u, v)))
    den = mpmath.sqrt(sum(b * b for b in v))
    return num / den if den != 0 else num


def out_str(v):
    """Decimal string of OUT_DIGITS significant digits that str::parse::<f64> reads."""
    v = mpf(v)
    if v == 0:
        return "0.0"
    return mpmath.nstr(v, OUT_DIGITS, min_fixed=1, max_fixed=0, strip_zeros=False)


# --------------------------------------------------------------------------------------------
# Validation of the representations by independent routes


def validate():
    import numpy as np

    records = []

    def record(what, value, limit, note=""):
        """Records one agreement; the generator refuses to write if it exceeds `limit` (the
        accuracy the independent route itself can reach)."""
        records.append(
            {"check": what, "max_rel_diff": f"{float(value):.2e}", "required": f"{limit:.0e}", "note": note}
        )
        print(f"  validation: {what}: {float(value):.2e} (required <= {limit:.0e}) {note}", flush=True)
        if not value <= limit:
            raise SystemExit(f"validation failed: {what}: {float(value):.2e} > {limit:.0e}")

    # (1) Solids against brute-force volume integrals: Gauss-Legendre product in
    # ellipsoidal-spherical coordinates r' = (a xi sin th cos ph, b xi sin th sin ph, c xi cos th),
    # dV = a b c xi^2 sin th dxi dth dph, for outside points (smooth integrand), double precision.
    def gl_volume(axes, mass, point, n):
        xg, wg = np.polynomial.legendre.leggauss(n)
        xi = 0.5 * (xg + 1)
        wxi = 0.5 * wg
        th = 0.5 * np.pi * (xg + 1)
        wth = 0.5 * np.pi * wg
        ph = np.pi * (xg + 1)
        wph = np.pi * wg
        XI, TH, PH = np.meshgrid(xi, th, ph, indexing="ij")
        W = (wxi[:, None, None] * wth[None, :, None] * wph[None, None, :]) * XI**2 * np.sin(TH)
        a, b, c = axes
        rho = mass / (4.0 / 3.0 * np.pi * a * b * c)
        X = a * XI * np.sin(TH) * np.cos(PH)
        Y = b * XI * np.sin(TH) * np.sin(PH)
        Z = c * XI * np.cos(TH)
        dx, dy, dz = X - point[0], Y - point[1], Z - point[2]
        dist = np.sqrt(dx * dx + dy * dy + dz * dz)
        jac = a * b * c * rho
        phi = -jac * np.sum(W / dist)
        acc = [jac * np.sum(W * d / dist**3) for d in (dx, dy, dz)]
        return phi, acc

    worst_phi = worst_acc = 0.0
    worst_conv = 0.0
    for axes, point in [
        ((1.0, 1.0, 0.25), (1.5, 0.2, 0.4)),
        ((1.0, 1.0, 0.25), (0.0, 0.0, 0.8)),
        ((1.0, 1.0, 4.0), (1.2, -0.5, 3.0)),
        ((3.0, 2.0, 1.0), (2.0, 2.0, 1.5)),
        ((3.0, 2.0, 1.0), (-4.0, 1.0, -0.5)),
        ((1.0, 2.0, 3.0), (0.5, -2.5, 2.0)),
        ((1.0, 1.0, 0.01), (0.6, 0.2, 0.3)),
        ((1e-3, 2e-3, 1.0), (0.3, 0.1, 0.4)),
    ]:
        phi_n, acc_n = gl_volume(axes, 1.0, point, 72)
        phi_m, acc_m = gl_volume(axes, 1.0, point, 96)
        worst_conv = max(worst_conv, abs(phi_n - phi_m) / abs(phi_m))
        phi_r, acc_r, region, _ = solid_field(axes, 1.0, 1.0, point)
        assert region == "outside"
        worst_phi = max(worst_phi, float(rel_diff(phi_m, phi_r)))
        worst_acc = max(worst_acc, float(vec_rel_diff(acc_m, acc_r)))
    record(
        "solids: Dirichlet integral vs 3-D Gauss-Legendre volume integral (96^3 nodes), Phi",
        worst_phi,
        1e-12,
        f"8 outside points on spheroids c/a=0.25, 4, 0.01 and ellipsoids (3,2,1), (1,2,3), "
        f"(1e-3,2e-3,1); "
        f"72^3 vs 96^3 volume-rule change {worst_conv:.1e}",
    )
    record("solids: same, acceleration (vector norm)", worst_acc, 1e-11)

    # (2) Spheroid, ring-reduced 2-D volume integral in mpmath (a different route again, and the
    # only one here valid inside): Phi = -G rho int dz' int_0^{s(z')} 4 s K(m)/sqrt((r+s)^2+dz^2) ds.
    def ring_volume(a, c, mass, rr, zz):
        with mp.workdps(20):
            a, c, rr, zz = mpf(a), mpf(c), mpf(rr), mpf(zz)
            dens = mpf(mass) / (4 * mpmath.pi / 3 * a * a * c)

            def inner(zp):
                smax = a * mpmath.sqrt(1 - (zp / c) ** 2)
                dz2 = (zz - zp) ** 2

                def kern(s):
                    q = (rr + s) ** 2 + dz2
                    return 4 * s * ellip_k(((rr - s) ** 2 + dz2) / q) / mpmath.sqrt(q)

                pts = [mpf(0), smax]
                if 0 < rr < smax:
                    pts = [mpf(0), rr, smax]
                return mpmath.quad(kern, pts)

            zpts = [-c, c]
            if -c < zz < c:
                zpts = [-c, zz, c]
            return -dens * mpmath.quad(inner, zpts)

    worst = mpf(0)
    for a, c, rr, zz in [(1.0, 0.25, 0.5, 0.1), (1.0, 0.25, 1.3, 0.2), (1.0, 4.0, 0.3, -2.0)]:
        ref = ring_volume(a, c, 1.0, rr, zz)
        phi_r, _, region, _ = solid_field((a, a, c), 1.0, 1.0, (rr, 0.0, zz))
        worst = max(worst, rel_diff(ref, phi_r))
    record(
        "spheroids: Dirichlet integral vs ring-reduced 2-D volume integral (mpmath, 20 digits), Phi",
        worst,
        1e-17,
        "c/a=0.25 inside and outside, c/a=4 inside",
    )

    # (3) Sphere: elementary closed forms, on every sphere case (exercises the quadrature at
    # near-surface, far and interior points).
    worst = mpf(0)
    for case in build_cases():
        if case["body"] != "sphere":
            continue
        p = case["params"]
        R, M, G = mpf(p["radius"]), mpf(p["mass"]), mpf(p["g"])
        x = [mpf(v) for v in case["point"]]
        r = mpmath.sqrt(sum(v * v for v in x))
        if r > R:
            phi_e = -G * M / r
            acc_e = [-G * M * v / r**3 for v in x]
        else:
            phi_e = -G * M * (3 * R * R - r * r) / (2 * R**3)
            acc_e = [-G * M * v / R**3 for v in x]
        phi_r, acc_r, _, _ = solid_field((p["radius"],) * 3, p["mass"], p["g"], case["point"])
        worst = max(worst, rel_diff(phi_e, phi_r), vec_rel_diff(acc_r, acc_e))
    record("sphere: Dirichlet integral vs -GM/r and -GM(3R^2-r^2)/(2R^3), Phi and acceleration", worst,
           1e-35, "all sphere cases, at the generator's precision")

    # (4) Disk: the ring identities by direct angular integration.
    worst = mpf(0)
    for rr, s, zz in [(mpf("0.7"), mpf("0.4"), mpf("0.3")), (mpf("0.2"), mpf("0.9"), mpf("-0.05"))]:
        A = rr * rr + s * s + zz * zz
        B = 2 * rr * s
        direct_k = mpmath.quad(lambda f: 1 / mpmath.sqrt(A - B * mpmath.cos(f)), [0, mpmath.pi, 2 * mpmath.pi])
        direct_e = mpmath.quad(lambda f: (A - B * mpmath.cos(f)) ** -1.5, [0, mpmath.pi, 2 * mpmath.pi])
        m = 2 * B / (A + B)
        worst = max(
            worst,
            rel_diff(direct_k, 4 * ellip_k(1 - m) / mpmath.sqrt(A + B)),
            rel_diff(direct_e, 4 * ellip_e(m, (A - B) / (A + B)) / ((A - B) * mpmath.sqrt(A + B))),
        )
    record("disk: ring kernels 4K(m)/sqrt(A+B) and 4E(m)/((A-B)sqrt(A+B)) vs direct phi integral", worst, 1e-35)

    # (5) Disk: acceleration (rim integral, E kernel) vs a numerical derivative of the ring-K
    # potential: five-point central differences at 60 digits, step h = 1e-7 (truncation
    # ~ h^4 f^(5) / 30 ~ 1e-29, rounding ~ 1e-55 / h ~ 1e-48).
    worst = mpf(0)
    for point in [(0.6, 0.0, 0.2), (1.3, 0.0, -0.4), (0.2, 0.0, 2.0)]:
        _, acc, _, _ = disk_field(1.0, 1.0, 1.0, point)
        with mp.workdps(60):
            h = mpf("1e-7")

            def five_point(fun, t):
                return (fun(t - 2 * h) - 8 * fun(t - h) + 8 * fun(t + h) - fun(t + 2 * h)) / (12 * h)

            r0, z0 = mpf(point[0]), mpf(point[2])
            d_rho = five_point(lambda t: disk_field(1.0, 1.0, 1.0, (t, 0.0, z0))[0], r0)
            d_z = five_point(lambda t: disk_field(1.0, 1.0, 1.0, (r0, 0.0, t))[0], z0)
            worst = max(worst, vec_rel_diff(acc, [-d_rho, 0, -d_z]))
    record("disk: acceleration (rim line integral, E-kernel integral) vs derivative of Phi", worst,
           1e-25, "3 off-plane points, five-point differences of the ring-K potential at 60 digits, h = 1e-7")

    # (6) Disk: direct 2-D area integral in polar coordinates (mpmath, 20 digits).
    worst_phi = worst_acc = mpf(0)
    for point in [(0.6, 0.0, 0.2), (1.5, 0.0, 0.3), (0.0, 0.0, 0.5)]:
        with mp.workdps(20):
            x0, y0, z0 = (mpf(v) for v in point)
            sigma = 1 / mpmath.pi

            def area(fun):
                return mpmath.quad(lambda s: mpmath.quad(lambda f: fun(s, f), [0, mpmath.pi, 2 * mpmath.pi]) * s,
                                   [0, 1])

            def dvec(s, f):
                return (s * mpmath.cos(f) - x0, s * mpmath.sin(f) - y0, -z0)

            def dist(s, f):
                d = dvec(s, f)
                return mpmath.sqrt(d[0] ** 2 + d[1] ** 2 + d[2] ** 2)

            phi_a = -sigma * area(lambda s, f: 1 / dist(s, f))
            acc_a = [sigma * area(lambda s, f, i=i: dvec(s, f)[i] / dist(s, f) ** 3) for i in range(3)]
        phi_r, acc_r, _, _ = disk_field(1.0, 1.0, 1.0, point)
        worst_phi = max(worst_phi, rel_diff(phi_a, phi_r))
        worst_acc = max(worst_acc, vec_rel_diff(acc_a, acc_r))
    record("disk: ring/rim representation vs direct 2-D area integral (mpmath, 20 digits), Phi", worst_phi,
           1e-17, "3 off-plane points")
    record("disk: same, acceleration", worst_acc, 1e-17)
    return records


# --------------------------------------------------------------------------------------------


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--jobs", type=int, default=2, help="worker processes (<= 2 here)")
    parser.add_argument("--verify-every", type=int, default=5,
                        help="recompute every N-th case at 60 digits to measure the accuracy")
    parser.add_argument("--output", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "potentials.json"))
    args = parser.parse_args()
    t_start = time.time()

    cases = build_cases()
    labels = [c["label"] for c in cases]
    assert len(set(labels)) == len(labels), "labels must be unique"
    counts = {}
    for c in cases:
        counts[c["body"]] = counts.get(c["body"], 0) + 1
    print(f"{len(cases)} cases: {counts}", flush=True)

    verify_idx = list(range(0, len(cases), args.verify_every)) if args.verify_every > 0 else []
    jobs = [(c, DPS) for c in cases] + [(cases[i], 60) for i in verify_idx]
    with Pool(args.jobs) as pool:
        results = pool.map(evaluate_worker, jobs, chunksize=1)
    main_results = results[: len(cases)]
    check_results = results[len(cases):]
    t_cases = time.time() - t_start

    worst_quad = max(r[3] for r in main_results)
    worst_check = mpf(0)
    for i, r60 in zip(verify_idx, check_results):
        r40 = main_results[i]
        worst_check = max(worst_check, rel_diff(r40[0], r60[0]), vec_rel_diff(r40[1], r60[1]))
    print(f"cases done in {t_cases:.0f} s; worst quadrature error estimate {worst_quad:.1e}; "
          f"worst {DPS}- vs 60-digit difference over {len(verify_idx)} cases {float(worst_check):.1e}",
          flush=True)
    slowest = max(range(len(cases)), key=lambda i: main_results[i][4])
    print(f"slowest case: {cases[slowest]['label']} ({main_results[slowest][4]:.1f} s)", flush=True)

    t_val = time.time()
    validation = validate()
    t_val = time.time() - t_val

    out_cases = []
    for case, r in zip(cases, main_results):
        out_cases.append(
            {
                "body": case["body"],
                "params": {k: fmt_float(v) for k, v in case["params"].items()},
                "point": [fmt_float(v) for v in case["point"]],
                "region": r[2],
                "label": case["label"],
                "potential": out_str(r[0]),
                "acceleration": [out_str(v) for v in r[1]],
            }
        )
    accuracy = max(mpf(worst_quad), worst_check, mpf(10) ** (1 - OUT_DIGITS))
    doc = {
        "generator": "tests/reference/potentials.py",
        "mpmath_dps": DPS,
        "estimated_relative_accuracy": (
            f"about 1e-29 relative in Phi and in the acceleration vector norm (limited by the "
            f"{OUT_DIGITS} significant digits written): worst quadrature error estimate "
            f"{worst_quad:.1e}; worst difference between the {DPS}-digit values and a 60-digit "
            f"recomputation of {len(verify_idx)} cases {float(worst_check):.1e}"
        ),
        "conventions": "Phi = -G int rho dV/|r-r'| (negative), acceleration = -grad Phi, body frame, "
        "homogeneous bodies; disk on the lamina inside the rim (region 'surface'): a_z = 0, the mean "
        "of the one-sided limits. All numbers are decimal strings; inputs are exact doubles "
        "(Python repr), outputs have " + str(OUT_DIGITS) + " significant digits.",
        "runtime_seconds": {"cases": round(t_cases), "validation": round(t_val), "jobs": args.jobs},
        "counts": counts,
        "validation": validation,
        "cases": out_cases,
    }
    assert accuracy < mpf("1e-25"), accuracy
    with open(args.output, "w") as fh:
        json.dump(doc, fh, indent=1)
        fh.write("\n")
    print(f"wrote {args.output}: {len(out_cases)} cases in {time.time() - t_start:.0f} s total", flush=True)


if __name__ == "__main__":
    main()
