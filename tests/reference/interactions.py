#!/usr/bin/env python3
"""Reference force, torques and mutual potential energy of two homogeneous bodies.

Writes tests/reference/interactions.json (next to this script). Provenance and measured accuracy:
tests/reference/README.md (section "interactions.json").

Conventions (those of surfgrav-potentials): Phi = -G int rho dV / |r - r'| (negative),
a = -grad Phi, homogeneous bodies, body frame with the centroid at the origin, spheroid symmetry
axis and ellipsoid c axis along z, disk in the x-y plane. Pose: A's centroid at the origin with
rotation vector rotation_a, B's centroid at position_b with rotation vector rotation_b (axis times
angle in radians; the rotation takes body-frame vectors to world-frame vectors,
r_world = R r_body + centroid). All results are in the world frame:

    force on A        F_A = int_A rho_A a_B dV
    torque on A       M_A = int_A rho_A (r - c_A) x a_B dV     (about A's centroid)
    torque on B       M_B = int_B rho_B (r - c_B) x a_A dV     (about B's centroid)
    potential energy  V   = int_A rho_A Phi_B dV                (negative)

For a uniform disk (lamina, sigma = m / (pi R^2)) the volume integrals are area integrals.

Route (independent of the surface-integral method and of the closed forms under test):

* Volume integration over one body of the other body's field. Solids in ellipsoidal-spherical
  coordinates r = (a s sin(theta) cos(phi), b s sin(theta) sin(phi), c s cos(theta)),
  dV = abc s^2 ds d(cos theta) d(phi): Gauss-Legendre in s on [0, 1] and in cos(theta) on
  [-1, 1], the periodic trapezoid rule in phi. Disks in polar coordinates, dA = R^2 s ds d(phi).
  Each rule's integrand is analytic on the closed interval (after the phi average it is a smooth
  function of s^2 and of cos(theta)), so every rule converges geometrically; the orders are set
  from the gap between the bodies and confirmed by repeating the whole computation at 1.5 times
  (and if needed 2.25 times) the orders in every dimension, including the field quadratures.

* The field of a solid (semi-axes a_1, a_2, a_3) from the Dirichlet integral
      Phi       = -(3 G M / 4) int_lam^inf (1 - sum_i x_i^2 / (a_i^2 + u)) du / Delta(u),
      dPhi/dx_i =  (3 G M / 2) x_i int_lam^inf du / ((a_i^2 + u) Delta(u)),
      Delta(u)  = sqrt((a_1^2 + u)(a_2^2 + u)(a_3^2 + u)),
  lam the largest root of sum_i x_i^2 / (a_i^2 + lam) = 1 (Newton from a point left of the root,
  where the convex decreasing residual makes the iteration monotone). The substitution
  a_i^2 + u = P_i(t) / t^2, P_i = L + d_i t^2, L = lam + k, k = min a_i^2, d_i = a_i^2 - k maps
  [lam, inf) onto t in (0, 1] with du / Delta = 2 L dt / sqrt(P_1 P_2 P_3): an analytic
  integrand whose nearest singularities are t = +-i sqrt(L / d_i); Gauss-Legendre in t with the
  order chosen from that distance (Bernstein-ellipse bound).

* The field of a uniform disk (radius R) at cylindrical (rho, z) of its frame from the ring
  decomposition (K, E complete elliptic integrals of parameter m):
      Phi     = -G sigma int_0^R 4 s K(m) / sqrt(Q) ds,     Q = (rho + s)^2 + z^2, m = 4 rho s / Q,
      dPhi/dz =  G sigma z int_0^R 4 s E(m) / (((rho - s)^2 + z^2) sqrt(Q)) ds
  (the z derivative of the ring kernel, using dK/dm = (E - (1 - m) K) / (2 m (1 - m))), and the
  in-plane gradient from the divergence theorem in the plane (a rim line integral)
      (dPhi/dx, dPhi/dy) = G sigma R int_0^{2 pi} (cos p, sin p) dp / |r - R (cos p, sin p, 0)|,
  Gauss-Legendre in s (order from the distance of the poles s = +-rho +- i z to [0, R]) and the
  trapezoid rule in p (order from the distance of the point to the rim). K is evaluated from
  1 - m = ((rho - s)^2 + z^2) / Q computed directly (scipy.special.ellipkm1), so no precision is
  lost where m is close to 1.

* Sums are compensated (math.fsum). Gauss-Legendre nodes are polished by Newton's method in
  extended precision.

* Cases in which one body is a sphere use Newton's theorem instead (exact): the other body's
  field is harmonic in the ball, so for a homogeneous sphere S of mass m_S at c_S in the field of
  body O, F_S = m_S a_O(c_S), the energy is m_S Phi_O(c_S), the torque on S about its centre is
  zero, and the torque on O follows from angular-momentum balance, M_O = -(c_O - c_S) x F_O. The
  one-point field is evaluated with mpmath at 30 digits. For these cases the volume route is run
  as well and its agreement is recorded (it validates the whole volume pipeline).

Checks (the script stops if one fails): rotation matrices against scipy's Rotation and a hand
case; Gauss-Legendre rules; the numpy Dirichlet field and disk field against mpmath at 30 digits;
the disk field against a direct 2-D area integral in mpmath; the volume pipeline against the
exact sphere cases; coplanar disks against the Hankel-transform form of the energy and force
(on a rotated contour, k = i t; mpmath.quadosc on the real axis where it converges) and against
tests/reference/disk_pair.json; force and torques against five-point derivatives of the energy
on four cases (signs and frames); for every case Newton's third law, the symmetry of the energy
and the angular-momentum balance between the two independent volume integrations (recorded in
the estimate); no overlap (dense surface samples).

Usage: python3 tests/reference/interactions.py [--quick]   (one core, about 2 minutes)
"""

import os

# One core: the machine is shared. Must be set before numpy is imported.
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import mpmath  # noqa: E402
import numpy as np  # noqa: E402
import scipy.special as sps  # noqa: E402
from mpmath import mp, mpf  # noqa: E402
from scipy.spatial import cKDTree  # noqa: E402
from scipy.spatial.transform import Rotation  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
OUT_PATH = os.path.join(HERE, "interactions.json")

# Target of the geometric-convergence bounds used to pick 1-D rule orders (relative).
RULE_TARGET = 1e-18
# A level is accepted when two consecutive resolutions agree to this (relative).
ACCEPT = 2e-14
# Resolution factors tried in turn.
LEVELS = (1.0, 1.5, 2.25, 3.375)
# The smallest accuracy claimed for a double-precision result (about one rounding).
EST_FLOOR = 2.2e-16
# Points per chunk in the vectorised field evaluation.
CHUNK = 8192

T0 = time.time()


def log(msg):
    print(f"[{time.time() - T0:7.1f}s] {msg}", flush=True)


# --------------------------------------------------------------------------------------------
# Rotations


def rotation_matrix(rv):
    """Rodrigues: rotation by |rv| about rv / |rv| (body -> world)."""
    rv = np.asarray(rv, dtype=float)
    th = math.sqrt(float(rv @ rv))
    if th == 0.0:
        return np.eye(3)
    k = rv / th
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + math.sin(th) * kx + (1.0 - math.cos(th)) * (kx @ kx)


def check_rotations():
    worst = 0.0
    r = rotation_matrix([0.0, 0.0, math.pi / 2])
    worst = max(worst, float(np.abs(r @ [1.0, 0.0, 0.0] - [0.0, 1.0, 0.0]).max()))
    r = rotation_matrix([math.pi / 2, 0.0, 0.0])
    worst = max(worst, float(np.abs(r @ [0.0, 0.0, 1.0] - [0.0, -1.0, 0.0]).max()))
    rng = np.random.default_rng(7)
    for _ in range(50):
        rv = rng.normal(size=3) * rng.uniform(0.0, 3.0)
        r = rotation_matrix(rv)
        worst = max(worst, float(np.abs(r - Rotation.from_rotvec(rv).as_matrix()).max()))
        worst = max(worst, float(np.abs(r @ r.T - np.eye(3)).max()))
        worst = max(worst, abs(np.linalg.det(r) - 1.0))
        worst = max(worst, float(np.abs(r @ rv - rv).max()))  # the axis is fixed
    if worst > 1e-14:
        raise SystemExit(f"rotation check failed: {worst}")
    return worst


# --------------------------------------------------------------------------------------------
# Quadrature rules

_GL = {}


def gauss_legendre(n):
    """n-point Gauss-Legendre on [-1, 1], Newton-polished in extended precision."""
    if n in _GL:
        return _GL[n]
    x0, _ = np.polynomial.legendre.leggauss(n)
    x = x0.astype(np.longdouble)
    for _ in range(3):
        p0 = np.ones_like(x)
        p1 = x.copy()
        for k in range(2, n + 1):
            p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
        dp = n * (x * p1 - p0) / (x * x - 1)
        x = x - p1 / dp
    p0 = np.ones_like(x)
    p1 = x.copy()
    for k in range(2, n + 1):
        p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
    dp = n * (x * p1 - p0) / (x * x - 1)
    w = 2 / ((1 - x * x) * dp * dp)
    rule = (x.astype(float), w.astype(float))
    _GL[n] = rule
    return rule


def gl01(n):
    x, w = gauss_legendre(n)
    return 0.5 * (x + 1.0), 0.5 * w


def check_gauss_legendre():
    worst = 0.0
    for n in (8, 33, 80, 200):
        x, w = gauss_legendre(n)
        worst = max(worst, abs(math.fsum(w) - 2.0))
        worst = max(worst, abs(math.fsum(w * x**6) - 2.0 / 7.0))
        worst = max(worst, abs(math.fsum(w * np.exp(x)) - (math.e - 1.0 / math.e)))
        if n >= 33:
            worst = max(worst, abs(math.fsum(w / (1.2 - x)) - math.log(2.2 / 0.2)))
        worst = max(worst, abs(math.fsum(w * np.cos(x)) - 2 * math.sin(1.0)))
    if worst > 2e-15:
        raise SystemExit(f"Gauss-Legendre check failed: {worst}")
    return worst


def bernstein_order(wstar, target=RULE_TARGET):
    """Gauss-Legendre order n with rho^(-2n) <= target, rho the Bernstein-ellipse parameter of
    the nearest singularity wstar (complex array, interval mapped to [-1, 1])."""
    wstar = np.asarray(wstar, dtype=complex)
    r1 = wstar + np.sqrt(wstar - 1) * np.sqrt(wstar + 1)
    rho = np.maximum(np.abs(r1), 1.0 / np.maximum(np.abs(r1), 1e-300))
    rho = float(np.min(rho))
    if rho <= 1.0 + 1e-9:
        raise ValueError("singularity on the interval")
    return int(math.ceil(-math.log(target) / (2.0 * math.log(rho))))


# --------------------------------------------------------------------------------------------
# Bodies


class Body:
    def __init__(self, kind, mass, **dims):
        self.kind = kind
        self.mass = float(mass)
        self.dims = {k: float(v) for k, v in dims.items()}
        if kind == "sphere":
            r = self.dims["radius"]
            self.axes = np.array([r, r, r])
        elif kind == "spheroid":
            a, c = self.dims["equatorial_radius"], self.dims["polar_radius"]
            self.axes = np.array([a, a, c])
        elif kind == "ellipsoid":
            self.axes = np.array([self.dims["a"], self.dims["b"], self.dims["c"]])
        elif kind == "disk":
            self.axes = np.array([self.dims["radius"], self.dims["radius"], 0.0])
        else:
            raise ValueError(kind)
        self.size = float(self.axes.max())

    def to_json(self):
        d = {"kind": self.kind}
        d.update(self.dims)
        d["mass"] = self.mass
        return d

    def describe(self):
        return f"{self.kind}({', '.join(repr(v) for v in self.dims.values())}; m={self.mass!r})"


# --------------------------------------------------------------------------------------------
# Fields in the body frame (numpy, vectorised). Return (Phi, acceleration (3, N)).


def confocal_lambda_np(p, axes2):
    """Largest root of sum p_i^2/(a_i^2 + lam) = 1 for points outside the ellipsoid."""
    x2 = p * p
    r2 = x2.sum(axis=0)
    if np.any((x2 / axes2[:, None]).sum(axis=0) <= 1.0):
        raise ValueError("point inside or on a solid body: the bodies overlap")
    lam = np.maximum(0.0, r2 - axes2.max())
    for _ in range(200):
        q = axes2[:, None] + lam
        f = (x2 / q).sum(axis=0) - 1.0
        fp = (x2 / (q * q)).sum(axis=0)
        step = f / fp
        lam_new = lam + step
        done = np.all(np.abs(step) <= 4e-15 * (lam_new + axes2.max()))
        lam = lam_new
        if done:
            break
    else:
        raise RuntimeError("confocal lambda did not converge")
    # one more step at full precision (quadratic convergence: roundoff-limited afterwards)
    q = axes2[:, None] + lam
    lam = lam + ((x2 / q).sum(axis=0) - 1.0) / (x2 / (q * q)).sum(axis=0)
    return lam


def solid_field(body, g, p, res):
    """Dirichlet integral field of a homogeneous solid at body-frame points p (3, N) outside."""
    axes2 = body.axes**2
    k = axes2.min()
    d = axes2 - k
    lam = confocal_lambda_np(p, axes2)
    L = lam + k
    dmax = d.max()
    if dmax > 0.0:
        tau = math.sqrt(float(L.min()) / dmax)
        n = bernstein_order(np.array([-1.0 + 2j * tau]))
    else:
        n = 4
    n = max(6, int(math.ceil(res * n)) + 2)
    t, w = gl01(n)
    t2 = t * t
    P = [L[:, None] + d[i] * t2[None, :] for i in range(3)]
    base = (2.0 * w)[None, :] * L[:, None] / np.sqrt(P[0] * P[1] * P[2])
    frac = [t2[None, :] / P[i] for i in range(3)]
    J = [(base * frac[i]).sum(axis=1) for i in range(3)]
    inner = 1.0 - (p[0, :, None] ** 2 * frac[0] + p[1, :, None] ** 2 * frac[1]
                   + p[2, :, None] ** 2 * frac[2])
    I0 = (base * inner).sum(axis=1)
    gm = g * body.mass
    phi = -0.75 * gm * I0
    acc = np.array([-1.5 * gm * p[i] * J[i] for i in range(3)])
    return phi, acc


def disk_field(body, g, p, res):
    """Ring-integral field of a uniform disk (x-y plane of its frame) at points p (3, N)."""
    R = body.dims["radius"]
    sigma = body.mass / (math.pi * R * R)
    x, y, z = p
    rho = np.hypot(x, y)
    az = np.abs(z)
    # distance to the lamina must not vanish
    dist = np.where(rho <= R, az, np.hypot(rho - R, az))
    if np.any(dist <= 0.0):
        raise ValueError("point on the disk: the bodies overlap")
    # ring integral in s on [0, R]: singular points s = +-rho +- i z, mapped to [-1, 1]
    wst = np.concatenate([(2.0 * (rho + 1j * az) - R) / R, (2.0 * (-rho + 1j * az) - R) / R])
    n = bernstein_order(wst)
    n = max(8, int(math.ceil(res * n)) + 4)
    s, w = gl01(n)
    s = R * s
    w = R * w
    S = s[None, :]
    rr = rho[:, None]
    zz2 = (z * z)[:, None]
    Q = (rr + S) ** 2 + zz2
    D = (rr - S) ** 2 + zz2  # = (1 - m) Q
    m1 = D / Q
    m = 4.0 * rr * S / Q
    sq = np.sqrt(Q)
    K = sps.ellipkm1(m1)
    E = sps.ellipe(m)
    phi = -g * sigma * ((4.0 * w)[None, :] * S * K / sq).sum(axis=1)
    dphidz = g * sigma * z * ((4.0 * w)[None, :] * S * E / (D * sq)).sum(axis=1)
    # rim integral: trapezoid, error ~ exp(-N alpha), cosh(alpha) = (rho^2 + R^2 + z^2)/(2 rho R)
    with np.errstate(divide="ignore"):
        ratio = (rho * rho + R * R + z * z) / (2.0 * rho * R)
    # (the trapezoid rule is applied to (cos p, sin p) / D, whose nearest singularity in p is
    # at imaginary part alpha)
    alpha = float(np.min(np.arccosh(np.minimum(ratio, 1e300))))
    nr = int(math.ceil(res * (-math.log(RULE_TARGET) + 2.0) / alpha)) + 8
    nr = max(16, nr + (nr % 2))
    ang = 2.0 * math.pi * (np.arange(nr) + 0.5) / nr
    c, sn = np.cos(ang), np.sin(ang)
    # 1/D - 1/D0 with D0^2 = rho^2 + R^2 + z^2, D0^2 - D^2 = 2 R (x cos p + y sin p): the
    # constant 1/D0 integrates to zero against cos p and sin p, and the difference is formed
    # without cancellation (matters far from the disk).
    d0sq = (rho * rho + R * R + z * z)[:, None]
    d0 = np.sqrt(d0sq)
    lin = 2.0 * R * (x[:, None] * c[None, :] + y[:, None] * sn[None, :])
    dd = np.sqrt((x[:, None] - R * c[None, :]) ** 2 + (y[:, None] - R * sn[None, :]) ** 2 + zz2)
    inv = lin / (dd * d0 * (dd + d0))
    h = 2.0 * math.pi / nr
    dphidx = g * sigma * R * h * (inv * c[None, :]).sum(axis=1)
    dphidy = g * sigma * R * h * (inv * sn[None, :]).sum(axis=1)
    return phi, -np.array([dphidx, dphidy, dphidz])


def body_field(body, g, p, res):
    if body.kind == "disk":
        return disk_field(body, g, p, res)
    return solid_field(body, g, p, res)


# --------------------------------------------------------------------------------------------
# The same fields in mpmath (MP_DPS digits), by the original variables: the Dirichlet integral in
# u (no substitution), the ring integrals with mpmath's K and E, the rim integral by tanh-sinh.

MP_DPS = 30
mp.dps = MP_DPS  # comparisons between mpmath results are made at this precision


def mp_solid_field(axes, mass, g, point):
    """(Phi, [a_x, a_y, a_z], quadrature error estimate) of a solid at a body-frame point."""
    return _mp_solid_field_mp(axes, mass, g, [mpf(float(v)) for v in point])


def _mp_solid_field_mp(axes, mass, g, point):
    with mp.workdps(MP_DPS + 10):
        a2 = [mpf(float(a)) ** 2 for a in axes]
        x = list(point)
        x2 = [v * v for v in x]

        def f(lam):
            return sum(xi / (ai + lam) for xi, ai in zip(x2, a2)) - 1

        def fp(lam):
            return -sum(xi / (ai + lam) ** 2 for xi, ai in zip(x2, a2))

        if f(mpf(0)) <= 0:
            raise ValueError("point inside")
        lam = max(mpf(0), sum(x2) - max(a2))
        for _ in range(500):
            step = -f(lam) / fp(lam)
            lam += step
            if abs(step) <= mpf(10) ** (-(MP_DPS + 8)) * (lam + max(a2)):
                break
        else:
            raise RuntimeError("mp lambda")

        def delta(u):
            return mpmath.sqrt((a2[0] + u) * (a2[1] + u) * (a2[2] + u))

        # u = lam + S (1/v^2 - 1), v in (0, 1]: the algebraic tail becomes an analytic
        # integrand at v = 0 (a different map from the numpy code's).
        S = max(a2) + lam
        vb = sorted(set([mpf(0), mpf(1) / 8, mpf(1) / 2, mpf(1)]
                        + [1 / mpmath.sqrt(1 + min(a2) / (j * S)) for j in (1, 8, 64)]))

        def in_v(h, power):
            # normalised by S^power so that the integral is of order one (mpmath's error
            # estimate is absolute)
            c = 2 * S * S**power
            return lambda v: h(lam + S * (1 / (v * v) - 1)) * c / v**3 if v > 0 else mpf(0)

        gm = mpf(float(g)) * mpf(float(mass))
        i0, e0 = mpmath.quad(in_v(lambda u: (1 - sum(xi / (ai + u) for xi, ai in zip(x2, a2)))
                                  / delta(u), mpf(1) / 2), vb, error=True)
        i0, e0 = i0 / mpmath.sqrt(S), e0 / mpmath.sqrt(S)
        phi = -mpf(3) / 4 * gm * i0
        acc = []
        err = e0 / abs(i0)
        for i in range(3):
            ji, ei = mpmath.quad(in_v(lambda u: 1 / ((a2[i] + u) * delta(u)), mpf(3) / 2), vb,
                                 error=True)
            ji, ei = ji / S**1.5, ei / S**1.5
            acc.append(-mpf(3) / 2 * gm * x[i] * ji)
            err = max(err, ei / abs(ji))
        return phi, acc, err


def mp_disk_field(radius, mass, g, point):
    """Ring-integral field of a disk at a body-frame point, mpmath (the same formulas)."""
    return _mp_disk_field_mp(radius, mass, g, [mpf(float(v)) for v in point])


def _mp_disk_field_mp(radius, mass, g, point):
    with mp.workdps(MP_DPS + 10):
        R = mpf(float(radius))
        sigma = mpf(float(mass)) / (mpmath.pi * R * R)
        gs = mpf(float(g)) * sigma
        x, y, z = point
        rho = mpmath.sqrt(x * x + y * y)
        brk = [mpf(0), R] if not (0 < rho < R) else [mpf(0), rho, R]

        def kern_phi(s):
            Q = (rho + s) ** 2 + z * z
            return 4 * s * mpmath.ellipk(4 * rho * s / Q) / mpmath.sqrt(Q)

        def kern_z(s):
            Q = (rho + s) ** 2 + z * z
            return 4 * s * mpmath.ellipe(4 * rho * s / Q) / (((rho - s) ** 2 + z * z)
                                                             * mpmath.sqrt(Q))

        i0, e0 = mpmath.quad(kern_phi, brk, error=True)
        phi = -gs * i0
        if z != 0:
            iz, ez = mpmath.quad(kern_z, brk, error=True)
            az = -gs * z * iz
            err = max(e0 / abs(i0), ez / abs(iz))
        else:
            az = mpf(0)
            err = e0 / abs(i0)
        p0 = mpmath.atan2(y, x)

        def rim(c):
            return lambda p: c(p) / mpmath.sqrt((x - R * mpmath.cos(p)) ** 2
                                                + (y - R * mpmath.sin(p)) ** 2 + z * z)

        pb = [p0 - mpmath.pi, p0, p0 + mpmath.pi]
        ix, ex = mpmath.quad(rim(mpmath.cos), pb, error=True)
        iy, ey = mpmath.quad(rim(mpmath.sin), pb, error=True)
        acc = [-gs * R * ix, -gs * R * iy, az]
        norm = mpmath.sqrt(sum(t * t for t in acc))
        err = max(err, gs * R * max(ex, ey) / norm)
        return phi, acc, err


def mp_disk_field_direct(radius, mass, g, point, dps=18):
    """Disk field by the direct 2-D area integral in polar coordinates (a different route)."""
    with mp.workdps(dps):
        R = mpf(float(radius))
        sigma = mpf(float(mass)) / (mpmath.pi * R * R)
        gs = mpf(float(g)) * sigma
        x, y, z = (mpf(float(v)) for v in point)
        p0 = mpmath.atan2(y, x)
        pb = [p0 - mpmath.pi, p0, p0 + mpmath.pi]
        rho = mpmath.sqrt(x * x + y * y)
        sb = [mpf(0), R] if not (0 < rho < R) else [mpf(0), rho, R]

        def integral(which):
            def inner(p):
                cp, sp = mpmath.cos(p), mpmath.sin(p)

                def f(s):
                    dx, dy = x - s * cp, y - s * sp
                    d2 = dx * dx + dy * dy + z * z
                    d = mpmath.sqrt(d2)
                    num = (1, dx, dy, z)[which]
                    return s * num / (d if which == 0 else d * d2)
                return mpmath.quad(f, sb)
            return mpmath.quad(inner, pb)

        phi = -gs * integral(0)
        acc = [-gs * integral(i) for i in (1, 2, 3)]
        return phi, acc


def mp_rel_vec_diff(u, v):
    n = max(mpmath.norm(u), mpmath.norm(v))
    return float(mpmath.norm([p - q for p, q in zip(u, v)]) / n) if n > 0 else 0.0


def rel_vec_diff(u, v):
    u = np.asarray([float(t) for t in u])
    v = np.asarray([float(t) for t in v])
    n = max(np.linalg.norm(u), np.linalg.norm(v))
    return float(np.linalg.norm(u - v) / n) if n > 0 else 0.0


def validate_fields():
    """numpy fields vs mpmath at MP_DPS digits; disk ring formulas vs the direct area integral."""
    records = []
    solid_cases = [
        ("sphere R=1", Body("sphere", 1.0, radius=1.0), [(1.3, 0.4, -0.2), (30.0, 1.0, 2.0)]),
        ("oblate (1, 0.25)", Body("spheroid", 1.0, equatorial_radius=1.0, polar_radius=0.25),
         [(1.05, 0.0, 0.0), (1.0004, 0.02, 0.0), (0.3, 0.2, 0.2600001), (0.6, -0.5, 0.2),
          (2.0, 1.0, 0.5), (28.0, -3.0, 1.5)]),
        ("prolate (0.25, 1)", Body("spheroid", 1.0, equatorial_radius=0.25, polar_radius=1.0),
         [(0.26, 0.0, 0.1), (0.1, 0.05, 1.01), (1.5, 0.2, 0.4)]),
        ("near-sphere (1, 0.99)", Body("spheroid", 1.0, equatorial_radius=1.0,
                                       polar_radius=0.99), [(0.7, 0.3, 0.7), (4.0, 1.0, -2.0)]),
        ("triaxial (1, 0.7, 0.4)", Body("ellipsoid", 1.0, a=1.0, b=0.7, c=0.4),
         [(1.02, 0.03, -0.01), (0.5, 0.62, 0.1), (0.1, 0.1, 0.45), (2.0, -1.0, 0.7)]),
        ("Earth-size spheroid", Body("spheroid", 5.97e24, equatorial_radius=6.378e6,
                                     polar_radius=6.357e6),
         [(3.52e8, 0.0, 1.53e8), (6.4e6, 1.0e5, 2.0e5)]),
    ]
    worst = 0.0
    for name, body, pts in solid_cases:
        g = 6.674e-11 if body.mass > 1e20 else 1.0
        p = np.array(pts, dtype=float).T
        phi, acc = solid_field(body, g, p, 1.0)
        for j, pt in enumerate(pts):
            mphi, macc, err = mp_solid_field(body.axes, body.mass, g, pt)
            if err > 1e-28:
                raise SystemExit(f"mpmath Dirichlet quadrature error {err} at {pt}")
            e_phi = float(abs(phi[j] - float(mphi)) / abs(float(mphi)))
            e_acc = rel_vec_diff(acc[:, j], macc)
            worst = max(worst, e_phi, e_acc)
            records.append((name, pt, e_phi, e_acc))
    if worst > 2e-15:
        for r in records:
            print(r)
        raise SystemExit(f"Dirichlet field vs mpmath: {worst}")
    out = [{"check": "numpy Dirichlet field (solids) vs mpmath Dirichlet integral in u, 30 digits",
            "points": len(records), "max_rel_diff_potential": max(r[2] for r in records),
            "max_rel_diff_acceleration": max(r[3] for r in records)}]
    log(f"  Dirichlet field: {len(records)} points, worst {worst:.2e}")

    disk = Body("disk", 1.0, radius=1.0)
    dpts = [(0.0, 0.0, 1.5), (0.3, -0.2, 1.25), (1.1, 0.0, 0.0), (2.05, 0.3, 0.0), (1.3, 0.9, 0.8),
            (0.2, 0.1, 0.3), (-0.7, 0.4, -0.25), (9.0, 1.0, 0.0), (0.9, 0.2, 0.05)]
    p = np.array(dpts, dtype=float).T
    phi, acc = disk_field(disk, 1.0, p, 1.0)
    rec = []
    for j, pt in enumerate(dpts):
        mphi, macc, err = mp_disk_field(1.0, 1.0, 1.0, pt)
        if err > 1e-28:
            raise SystemExit(f"mpmath disk quadrature error {err} at {pt}")
        rec.append((pt, float(abs(phi[j] - float(mphi)) / abs(float(mphi))),
                    rel_vec_diff(acc[:, j], macc)))
    w2 = max(max(r[1], r[2]) for r in rec)
    if w2 > 2e-15:
        for r in rec:
            print(r)
        raise SystemExit(f"disk field vs mpmath: {w2}")
    out.append({"check": "numpy disk ring/rim field vs the same integrals in mpmath, 30 digits",
                "points": len(rec), "max_rel_diff_potential": max(r[1] for r in rec),
                "max_rel_diff_acceleration": max(r[2] for r in rec)})
    log(f"  disk field: {len(rec)} points, worst {w2:.2e}")

    rec = []
    for pt in [(0.3, -0.2, 1.25), (1.1, 0.0, 0.0), (1.3, 0.9, 0.8), (0.2, 0.1, 0.3)]:
        mphi, macc, _ = mp_disk_field(1.0, 1.0, 1.0, pt)
        dphi, dacc = mp_disk_field_direct(1.0, 1.0, 1.0, pt)
        rec.append((pt, float(abs(mphi - dphi) / abs(mphi)), mp_rel_vec_diff(macc, dacc)))
    w3 = max(max(r[1], r[2]) for r in rec)
    if w3 > 1e-15:
        for r in rec:
            print(r)
        raise SystemExit(f"disk ring formulas vs direct area integral: {w3}")
    out.append({"check": "disk ring/rim formulas (mpmath) vs direct 2-D area integral of the "
                "kernels 1/|r-r'| and (r-r')/|r-r'|^3 (mpmath, 18 digits)",
                "points": len(rec), "max_rel_diff_potential": max(r[1] for r in rec),
                "max_rel_diff_acceleration": max(r[2] for r in rec)})
    log(f"  disk formulas vs direct area integral: {len(rec)} points, worst {w3:.2e}")
    return out


# --------------------------------------------------------------------------------------------
# Volume (area) rules and the interaction integrals


def scaled(n, res, even=False, minimum=4):
    m = max(minimum, int(math.ceil(res * n)))
    if even and m % 2:
        m += 1
    return m


def body_rule(body, orders, res):
    """Nodes (3, N) in the body frame and mass elements (N,) of a product rule on the body."""
    if body.kind == "disk":
        ns, nphi = scaled(orders[0], res), scaled(orders[2], res, even=True)
        s, ws = gl01(ns)
        ang = 2.0 * math.pi * (np.arange(nphi) + 0.5) / nphi
        R = body.dims["radius"]
        S, A = np.meshgrid(s, ang, indexing="ij")
        W = np.repeat((body.mass / math.pi) * s * ws * (2.0 * math.pi / nphi), nphi)
        p = np.array([R * S.ravel() * np.cos(A.ravel()), R * S.ravel() * np.sin(A.ravel()),
                      np.zeros(S.size)])
        return p, W
    ns, nmu, nphi = (scaled(orders[0], res), scaled(orders[1], res, even=True),
                     scaled(orders[2], res, even=True))
    s, ws = gl01(ns)
    mu, wmu = gauss_legendre(nmu)
    ang = 2.0 * math.pi * (np.arange(nphi) + 0.5) / nphi
    S, MU, A = np.meshgrid(s, mu, ang, indexing="ij")
    W = (3.0 * body.mass / (4.0 * math.pi)) * (s * s * ws)[:, None, None] * wmu[None, :, None] \
        * (2.0 * math.pi / nphi) * np.ones((1, 1, nphi))
    st = np.sqrt(1.0 - MU * MU)
    a1, a2, a3 = body.axes
    p = np.array([(a1 * S * st * np.cos(A)).ravel(), (a2 * S * st * np.sin(A)).ravel(),
                  (a3 * S * MU).ravel()])
    return p, W.ravel()


def integrate_over(X, rot_x, cx, Y, rot_y, cy, g, orders, res):
    """Mass-weighted integrals over X of Y's field: (force, torque about c_X, energy, nodes)."""
    p, dm = body_rule(X, orders, res)
    if abs(math.fsum(dm) - X.mass) > 1e-14 * X.mass:
        raise RuntimeError("mass of the rule")
    Rx, Ry = rotation_matrix(rot_x), rotation_matrix(rot_y)
    T = Ry.T @ Rx
    o = Ry.T @ (np.asarray(cx, float) - np.asarray(cy, float))
    parts = [[] for _ in range(7)]
    for i0 in range(0, p.shape[1], CHUNK):
        pc = p[:, i0:i0 + CHUNK]
        w = dm[i0:i0 + CHUNK]
        q = T @ pc + o[:, None]
        phi, acc = body_field(Y, g, q, res)
        aw = Ry @ acc
        rw = Rx @ pc
        tq = np.cross(rw.T, aw.T).T
        for k in range(3):
            parts[k].append(w * aw[k])
            parts[3 + k].append(w * tq[k])
        parts[6].append(w * phi)
    sums = [math.fsum(np.concatenate(v).tolist()) for v in parts]
    return np.array(sums[0:3]), np.array(sums[3:6]), sums[6], p.shape[1]


# --------------------------------------------------------------------------------------------
# Geometry: surface samples, overlap, gaps, and the rule orders


def surface_samples(body, n_mu=240, n_phi=480):
    """Dense sample of the closed surface (solids: rings in cos(theta), plus the poles; disks:
    the whole lamina, which is its own surface), body frame (3, N)."""
    if body.kind == "disk":
        R = body.dims["radius"]
        s = np.sqrt(np.linspace(0.0, 1.0, n_mu))
        ang = np.linspace(0.0, 2.0 * math.pi, n_phi, endpoint=False)
        S, A = np.meshgrid(s[1:], ang, indexing="ij")
        p = np.array([R * (S * np.cos(A)).ravel(), R * (S * np.sin(A)).ravel(),
                      np.zeros(S.size)])
        return np.concatenate([np.zeros((3, 1)), p], axis=1)  # the centre once (k-d tree)
    th = np.linspace(0.0, math.pi, n_mu)[1:-1]
    ang = np.linspace(0.0, 2.0 * math.pi, n_phi, endpoint=False)
    TH, A = np.meshgrid(th, ang, indexing="ij")
    a1, a2, a3 = body.axes
    p = np.array([(a1 * np.sin(TH) * np.cos(A)).ravel(), (a2 * np.sin(TH) * np.sin(A)).ravel(),
                  (a3 * np.cos(TH)).ravel()])
    poles = np.array([[0.0, 0.0], [0.0, 0.0], [a3, -a3]])  # once each (k-d tree)
    return np.concatenate([p, poles], axis=1)


def singular_samples(body, n_r=60, n_t=720):
    """Sample of the set on which the body's exterior field, continued inwards, is singular
    (conservatively: a sphere's centre; a solid's filled focal ellipse or segment; a disk's
    lamina), body frame (3, N)."""
    if body.kind == "disk":
        return surface_samples(body, n_r, n_t)
    a2 = body.axes**2
    k = a2.min()
    f = np.sqrt(np.maximum(a2 - k, 0.0))
    if f.max() == 0.0:
        return np.zeros((3, 1))
    j = int(np.argmin(a2))
    others = [i for i in range(3) if i != j]
    u = np.linspace(0.0, 1.0, n_r)
    t = np.linspace(0.0, 2.0 * math.pi, n_t, endpoint=False)
    U, T = np.meshgrid(u[1:], t, indexing="ij")
    p = np.zeros((3, U.size + 1))  # the centre once (k-d tree): last column stays zero
    p[others[0], :-1] = f[others[0]] * (U * np.cos(T)).ravel()
    p[others[1], :-1] = f[others[1]] * (U * np.sin(T)).ravel()
    if f[others[1]] == 0.0:  # a focal segment (prolate): drop repeated points
        p = np.unique(p.T, axis=0).T
    return p


def to_frame(p, rot_from, c_from, rot_to, c_to):
    Rf, Rt = rotation_matrix(rot_from), rotation_matrix(rot_to)
    return (Rt.T @ Rf) @ p + (Rt.T @ (np.asarray(c_from, float) - np.asarray(c_to, float)))[:, None]


def inside_measure(body, q):
    """> 1 outside a solid (ellipsoidal radius squared); for a disk the distance to it."""
    if body.kind == "disk":
        R = body.dims["radius"]
        rho = np.hypot(q[0], q[1])
        return np.where(rho <= R, np.abs(q[2]), np.hypot(rho - R, q[2]))
    return ((q / body.axes[:, None]) ** 2).sum(axis=0)


def check_no_overlap(A, B, pos, ra, rb):
    """Raise if the bodies intersect. Returns the sampled surface-to-surface gap."""
    za = np.zeros(3)
    if A.kind == "disk" and B.kind == "disk":
        # exact: the range of heights of disk A above B's plane is h_c +- R_A |n_A x n_B|
        # (and vice versa): if either disk lies strictly on one side of the other's plane,
        # they cannot meet
        na = rotation_matrix(ra)[:, 2]
        nb = rotation_matrix(rb)[:, 2]
        sine = float(np.linalg.norm(np.cross(na, nb)))
        h_a = float(nb @ (za - np.asarray(pos)))  # A's centre above B's plane
        h_b = float(na @ (np.asarray(pos) - za))  # B's centre above A's plane
        if sine == 0.0 and h_a == 0.0:  # coplanar
            if np.linalg.norm(pos) <= A.dims["radius"] + B.dims["radius"]:
                raise SystemExit("coplanar disks overlap")
        elif abs(h_a) <= A.dims["radius"] * sine and abs(h_b) <= B.dims["radius"] * sine:
            raise SystemExit("disk-disk pose not supported by the overlap check")
    else:
        sa = surface_samples(A)
        sb = surface_samples(B)
        qa = to_frame(sa, ra, za, rb, pos)
        qb = to_frame(sb, rb, pos, ra, za)
        ma = inside_measure(B, qa) if B.kind != "disk" else np.full(1, 2.0)
        mb = inside_measure(A, qb) if A.kind != "disk" else np.full(1, 2.0)
        if ma.min() <= 1.0 or mb.min() <= 1.0:
            raise SystemExit("the bodies overlap")
    wa = to_frame(surface_samples(A), ra, za, za, za)
    wb = to_frame(surface_samples(B), rb, pos, za, za)
    gap, _ = cKDTree(wb.T, balanced_tree=False, compact_nodes=False).query(wa.T, k=1)
    return float(gap.min())


def sing_distance(X, rot_x, cx, Y, rot_y, cy):
    """Distances from X's surface, and from its polar caps (|cos theta| > 0.7 of a solid), to
    Y's singular set (sampled)."""
    px = surface_samples(X, 120, 240)
    sx = to_frame(px, rot_x, cx, rot_y, cy)
    tree = cKDTree(singular_samples(Y).T, balanced_tree=False, compact_nodes=False)
    d, _ = tree.query(sx.T, k=1)
    if X.kind == "disk":
        return float(d.min()), float(d.min())
    cap = np.abs(px[2] / X.axes[2]) > 0.7
    return float(d.min()), float(d[cap].min())


VOL_TARGET = 1e-16


def point_alpha(X, rot_x, cx, Y, rot_y, cy):
    """For a sphere Y (a point singularity at its centre q): the imaginary part alpha of the
    nearest singularity in X's azimuth, cosh(alpha) = 1 + d^2 / (2 r_perp rho_q), d the distance
    in the meridian half-plane between a point of X's surface (distance r_perp from X's axis)
    and q (distance rho_q from it); minimised over a sample of X's surface."""
    px = surface_samples(X, 120, 240)
    q = to_frame(np.zeros((3, 1)), rot_y, cy, rot_x, cx).ravel()
    rp = np.hypot(px[0], px[1])
    rq = math.hypot(q[0], q[1])
    ok = rp > 0
    d2 = (rp[ok] - rq) ** 2 + (px[2][ok] - q[2]) ** 2
    if rq == 0.0:
        return math.inf
    return float(np.arccosh(1.0 + d2 / (2.0 * rp[ok] * rq)).min())


def vol_orders(X, delta, delta_pole, alpha=math.inf):
    """Base orders (n_s, n_mu, n_phi) of X's rule for singularities at distance delta outside
    X (delta_pole from its polar caps): Bernstein-ellipse bounds for a singularity at
    s = 1 + delta / size beyond the end of the radial interval, at cos(theta) = i delta / c
    (near the equator) and 1 + (delta_pole / size)^2 / 2 (above a pole), at s = i delta / size
    (a disk's centre), and the trapezoid bound exp(-N sqrt(2 delta / size)) in phi. Heuristic:
    the orders are confirmed by the resolution study."""
    size = X.size
    e = delta / size
    tgt = VOL_TARGET
    ns = bernstein_order(np.array([1.0 + 2.0 * e]), tgt)
    nphi = int(math.ceil(-math.log(tgt) / min(math.sqrt(2.0 * e), alpha)))
    if X.kind == "disk":
        ns = max(ns, bernstein_order(np.array([-1.0 + 2j * e]), tgt))
        return (max(8, ns), 0, max(16, nphi))
    c = X.axes[2]
    nmu = max(bernstein_order(np.array([1j * delta / c]), tgt),
              bernstein_order(np.array([1.0 + 0.5 * (delta_pole / size) ** 2]), tgt))
    return (max(8, ns), max(8, nmu), max(16, nphi))


# --------------------------------------------------------------------------------------------
# Exact routes: a sphere in any field (Newton's theorem), coplanar disks (Hankel transform)


def mp_rotation(rv):
    v = [mpf(float(t)) for t in rv]
    th = mpmath.sqrt(sum(t * t for t in v))
    eye = mpmath.eye(3)
    if th == 0:
        return eye
    k = [t / th for t in v]
    kx = mpmath.matrix([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return eye + mpmath.sin(th) * kx + (1 - mpmath.cos(th)) * (kx * kx)


def mp_cross(u, v):
    return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]


def exact_sphere_case(A, B, g, pos, ra, rb):
    """Newton's theorem for a pair with a sphere: (F_A, M_A, M_B, V) in mpmath, error estimate."""
    with mp.workdps(MP_DPS + 10):
        cb = [mpf(float(t)) for t in pos]
        if A.kind == "sphere":
            Rb = mp_rotation(rb)
            q = Rb.T * mpmath.matrix([-t for t in cb])
            qf = [q[i] for i in range(3)]
            phi, acc, err = mp_field_at(B, g, qf)
            aw = Rb * mpmath.matrix(acc)
            fa = [mpf(float(A.mass)) * aw[i] for i in range(3)]
            energy = mpf(float(A.mass)) * phi
            ma = [mpf(0)] * 3
            mb = mp_cross(cb, fa) if B.kind != "sphere" else [mpf(0)] * 3
        else:
            Ra = mp_rotation(ra)
            q = Ra.T * mpmath.matrix(cb)
            qf = [q[i] for i in range(3)]
            phi, acc, err = mp_field_at(A, g, qf)
            aw = Ra * mpmath.matrix(acc)
            fa = [-mpf(float(B.mass)) * aw[i] for i in range(3)]
            energy = mpf(float(B.mass)) * phi
            mb = [mpf(0)] * 3
            ma = mp_cross(cb, fa)
        return fa, ma, mb, energy, err


def mp_field_at(body, g, q):
    """mpmath field at a body-frame point given in mpmath numbers (kept exact: the sphere's
    centre in the other body's frame is not a double)."""
    if body.kind == "disk":
        return _mp_disk_field_mp(body.dims["radius"], body.mass, g, q)
    return _mp_solid_field_mp(body.axes, body.mass, g, q)


def hankel_coplanar_disks(ra, rb, ma, mb, g, d, dps=25):
    """V and dV/dd of two coplanar uniform disks, centres d > ra + rb apart:
        V = -G m_A m_B int_0^inf [2 J1(k a)/(k a)] [2 J1(k b)/(k b)] J0(k d) dk.
    J0 = Re H0^(1); f_A f_B H0^(1)(k d) decays in the upper half plane when d > a + b, so the
    contour turns onto k = i t:  int = (2/pi) int_0^inf [2 I1(t a)/(t a)] [2 I1(t b)/(t b)]
    K0(t d) dt, a positive integrand decaying like exp(-(d - a - b) t) (and the d-derivative
    with -t K1(t d)). Returns (V, dV/dd, error estimate)."""
    with mp.workdps(dps):
        a, b, r = mpf(float(ra)), mpf(float(rb)), mpf(float(d))

        def sh(t, R):
            return 2 * mpmath.besseli(1, t * R) / (t * R) if t != 0 else mpf(1)

        om = r - a - b
        tb = sorted(set([mpf(0)] + [mpf(4) ** j / om for j in range(-3, 6)] + [mpmath.inf]))
        i0, e0 = mp.quad(lambda t: sh(t, a) * sh(t, b) * mpmath.besselk(0, t * r), tb, error=True)
        i1, e1 = mp.quad(lambda t: sh(t, a) * sh(t, b) * t * mpmath.besselk(1, t * r), tb,
                         error=True)
        gm = mpf(float(g)) * mpf(float(ma)) * mpf(float(mb))
        return -gm * 2 / mp.pi * i0, gm * 2 / mp.pi * i1, max(e0 / i0, e1 / i1)


def hankel_quadosc(ra, rb, d, dps=25):
    """The same energy integral on the real axis by mpmath.quadosc (slow; used where it
    converges, d well above ra + rb): returns int_0^inf f_A f_B J0(k d) dk."""
    with mp.workdps(dps):
        a, b, r = mpf(float(ra)), mpf(float(rb)), mpf(float(d))

        def f(k):
            if k == 0:
                return mpf(1)
            return (2 * mpmath.besselj(1, k * a) / (k * a)) * (2 * mpmath.besselj(1, k * b)
                                                               / (k * b)) * mpmath.besselj(0, k * r)
        return mp.quadosc(f, [0, mpmath.inf], period=2 * mp.pi / r)


# --------------------------------------------------------------------------------------------
# Cases


def oblate(m=1.0):
    return Body("spheroid", m, equatorial_radius=1.0, polar_radius=0.25)


def prolate(m=1.0):
    return Body("spheroid", m, equatorial_radius=0.25, polar_radius=1.0)


def tri_big(m=1.0):
    return Body("ellipsoid", m, a=1.0, b=0.7, c=0.4)


def tri_small(m=0.6):
    return Body("ellipsoid", m, a=0.8, b=0.5, c=0.3)


def disk(r=1.0, m=1.0):
    return Body("disk", m, radius=r)


def sphere(r, m):
    return Body("sphere", m, radius=r)


Z = [0.0, 0.0, 0.0]
CASES = [
    # label, A, B, G, position_b, rotation_a, rotation_b
    ("paper pair: oblate spheroids (1, 0.25), separation 2.05 (gap 0.05)",
     oblate(), oblate(), 1.0, [2.05, 0.0, 0.0], Z, Z),
    ("paper pair, separation 2.1", oblate(), oblate(), 1.0, [2.1, 0.0, 0.0], Z, Z),
    ("paper pair, separation 2.55", oblate(), oblate(), 1.0, [2.55, 0.0, 0.0], Z, Z),
    ("paper pair, separation 3", oblate(), oblate(), 1.0, [3.0, 0.0, 0.0], Z, Z),
    ("paper pair, separation 7", oblate(), oblate(), 1.0, [7.0, 0.0, 0.0], Z, Z),
    ("paper pair, separation 30", oblate(), oblate(), 1.0, [30.0, 0.0, 0.0], Z, Z),
    ("oblate pair, B tilted 0.5 rad about the line of centres, separation 2.55",
     oblate(), oblate(), 1.0, [2.55, 0.0, 0.0], Z, [0.5, 0.0, 0.0]),
    ("oblate pair, B tilted 0.7 rad about y, separation 3",
     oblate(), oblate(), 1.0, [3.0, 0.0, 0.0], Z, [0.0, 0.7, 0.0]),
    ("oblate pair, both rotated, B at (2.2, 1.1, 0.6)",
     oblate(), oblate(0.8), 1.0, [2.2, 1.1, 0.6], [0.3, -0.2, 0.1], [-0.4, 0.5, 0.25]),
    ("oblate pair, A tilted, B above at (1.3, 0.4, 1.1)",
     oblate(), oblate(0.5), 1.0, [1.3, 0.4, 1.1], [0.6, 0.0, 0.0], [0.0, -0.3, 0.0]),
    ("oblate A with prolate B (0.25, 1), B at (1.6, 0, 0)",
     oblate(), prolate(), 1.0, [1.6, 0.0, 0.0], Z, Z),
    ("oblate A with prolate B, both rotated, B at (1.5, 0.9, 0.7)",
     oblate(), prolate(0.7), 1.0, [1.5, 0.9, 0.7], [0.1, 0.2, -0.3], [0.9, 0.4, 0.0]),
    ("triaxial (1, 0.7, 0.4) with (0.8, 0.5, 0.3), both rotated, B at (2.2, 0.4, -0.3)",
     tri_big(), tri_small(), 1.0, [2.2, 0.4, -0.3], [0.2, 0.4, -0.1], [-0.5, 0.3, 0.8]),
    ("triaxial pair near contact, B at (1.9, 0, 0) turned 0.3 rad about z",
     tri_big(), tri_small(), 1.0, [1.9, 0.0, 0.0], Z, [0.0, 0.0, 0.3]),
    ("triaxial pair, G = 2.5, B at (0.5, 2.0, 1.0)",
     tri_big(2.0), tri_small(0.3), 2.5, [0.5, 2.0, 1.0], [1.0, -0.5, 0.4], [0.3, 0.9, -1.2]),
    ("near-sphere spheroid (1, 0.99) with tilted oblate B at (2.3, 0.5, 0.2)",
     Body("spheroid", 1.0, equatorial_radius=1.0, polar_radius=0.99), oblate(), 1.0,
     [2.3, 0.5, 0.2], Z, [0.4, 0.2, 0.0]),
    ("near-sphere spheroid (1, 0.99) tilted, triaxial B at (2.4, -0.3, 0.5)",
     Body("spheroid", 1.0, equatorial_radius=1.0, polar_radius=0.99), tri_big(0.5), 1.0,
     [2.4, -0.3, 0.5], [0.6, 0.0, 0.2], [0.0, 0.5, -0.4]),
    ("disk R = 1 at height 1.5 above an oblate spheroid (1, 0.25)",
     oblate(), disk(1.0, 0.5), 1.0, [0.0, 0.0, 1.5], Z, Z),
    ("tilted disk (0.5 rad about x) above an oblate spheroid, centre (0.3, 0.2, 1.5)",
     oblate(), disk(1.0, 0.5), 1.0, [0.3, 0.2, 1.5], Z, [0.5, 0.0, 0.0]),
    ("tilted disk A beside a rotated triaxial B at (2.3, 0.2, 0.4)",
     disk(1.0, 0.5), tri_big(), 1.0, [2.3, 0.2, 0.4], [0.2, 0.9, 0.0], [0.1, 0.2, 0.3]),
    ("disk A above a tilted prolate B at (0.4, 0, -1.6)",
     disk(1.0, 0.5), prolate(), 1.0, [0.4, 0.0, -1.6], Z, [0.3, 0.0, 0.0]),
    ("coplanar disks R = 1, d = 2.1", disk(), disk(), 1.0, [2.1, 0.0, 0.0], Z, Z),
    ("coplanar disks R = 1, d = 3", disk(), disk(), 1.0, [3.0, 0.0, 0.0], Z, Z),
    ("coplanar disks R = 1, d = 10", disk(), disk(), 1.0, [10.0, 0.0, 0.0], Z, Z),
    ("coplanar disks R = 1 and 0.5, B at (1.5, 0.8, 0)",
     disk(1.0, 1.0), disk(0.5, 0.3), 1.0, [1.5, 0.8, 0.0], Z, Z),
    ("disks in parallel planes, B at (1.5, 0.3, 0.8)",
     disk(1.0, 1.0), disk(1.0, 0.7), 1.0, [1.5, 0.3, 0.8], Z, Z),
    ("coaxial disks in parallel planes 1 apart", disk(1.0, 1.0), disk(1.0, 1.0), 1.0,
     [0.0, 0.0, 1.0], Z, Z),
    ("tilted disks, B (R = 0.8) at (2.2, 0.5, 1.2)",
     disk(1.0, 1.0), disk(0.8, 0.6), 1.0, [2.2, 0.5, 1.2], [0.3, 0.0, 0.0], [0.0, -0.6, 0.2]),
    ("two spheres R = 1 and 0.5, B at (2, 2, 1)",
     sphere(1.0, 1.0), sphere(0.5, 0.2), 1.0, [2.0, 2.0, 1.0], Z, [0.3, 0.1, 0.0]),
    ("sphere A (R = 0.5) with tilted oblate B at (1.6, 0.5, 0.3)",
     sphere(0.5, 0.3), oblate(), 1.0, [1.6, 0.5, 0.3], [0.2, 0.0, 0.0], [0.4, -0.3, 0.2]),
    ("tilted oblate A with sphere B (R = 0.4) at (1.3, 0.2, 0.5)",
     oblate(), sphere(0.4, 0.2), 1.0, [1.3, 0.2, 0.5], [0.5, 0.3, 0.0], Z),
    ("sphere A (R = 0.6) with tilted disk B at (0.5, 0.2, 1.2)",
     sphere(0.6, 0.4), disk(1.0, 0.5), 1.0, [0.5, 0.2, 1.2], Z, [0.4, 0.0, 0.1]),
    ("rotated triaxial A with sphere B (R = 0.3) at (-1.5, 1.2, 0.8)",
     tri_big(), sphere(0.3, 0.1), 1.0, [-1.5, 1.2, 0.8], [0.7, -0.2, 0.5], Z),
    ("SI: Earth-size spheroid (axis tilted 0.4091 rad) and Moon-size sphere at 3.84e8 m",
     Body("spheroid", 5.97e24, equatorial_radius=6.378e6, polar_radius=6.357e6),
     sphere(1.7374e6, 7.342e22), 6.674e-11, [3.84e8, 0.0, 0.0], [0.0, 0.4091, 0.0], Z),
]


# --------------------------------------------------------------------------------------------
# Running a case


def norm(v):
    return math.sqrt(math.fsum(float(t) ** 2 for t in v))


def rel(u, v, scale):
    return norm([float(p) - float(q) for p, q in zip(u, v)]) / scale


def run_case(case):
    label, A, B, g, pos, ra, rb = case
    pos = [float(t) for t in pos]
    gap = check_no_overlap(A, B, pos, ra, rb)
    da = sing_distance(A, ra, Z, B, rb, pos)
    db = sing_distance(B, rb, pos, A, ra, Z)
    al_a = point_alpha(A, ra, Z, B, rb, pos) if B.kind == "sphere" else math.inf
    al_b = point_alpha(B, rb, pos, A, ra, Z) if A.kind == "sphere" else math.inf
    oa, ob = vol_orders(A, *da, al_a), vol_orders(B, *db, al_b)
    levels = []
    conv = float("inf")
    for res in LEVELS:
        fa, ma, va, na = integrate_over(A, ra, Z, B, rb, pos, g, oa, res)
        fb, mb, vb, nb = integrate_over(B, rb, pos, A, ra, Z, g, ob, res)
        levels.append(dict(fa=fa, ma=ma, va=va, fb=fb, mb=mb, vb=vb, n=na + nb, res=res))
        if len(levels) >= 2:
            p, c = levels[-2], levels[-1]
            fs = norm(c["fa"])
            tau = fs * (norm(pos) + A.size + B.size)
            sa = max(norm(c["ma"]), 1e-13 * tau) if norm(c["ma"]) > 1e-13 * tau else tau
            sb = max(norm(c["mb"]), 1e-13 * tau) if norm(c["mb"]) > 1e-13 * tau else tau
            conv = max(rel(c["fa"], p["fa"], fs), rel(c["fb"], p["fb"], fs),
                       rel(c["ma"], p["ma"], sa), rel(c["mb"], p["mb"], sb),
                       abs(c["va"] - p["va"]) / abs(c["va"]), abs(c["vb"] - p["vb"]) / abs(c["va"]))
            if conv <= ACCEPT:
                break
    c = levels[-1]
    fs = norm(c["fa"])
    tau = fs * (norm(pos) + A.size + B.size)
    ca_minus_cb = [-t for t in pos]
    balance = np.asarray(c["ma"]) + np.asarray(c["mb"]) + np.cross(ca_minus_cb, c["fa"])
    bal_scale = max(norm(c["ma"]), norm(c["mb"]), norm(np.cross(ca_minus_cb, c["fa"])))
    if bal_scale <= 1e-13 * tau:  # every term vanishes by symmetry
        bal_scale = tau
    rec = {
        "label": label, "gap": gap, "orders_a": oa, "orders_b": ob, "levels": len(levels),
        "nodes_final": c["n"], "conv": conv,
        "third_law": rel(c["fa"], -c["fb"], fs),
        "energy_symmetry": abs(c["va"] - c["vb"]) / abs(c["va"]),
        "balance": norm(balance) / bal_scale,
        "balance_over_tau": norm(balance) / tau,
        "zero_ma": norm(c["ma"]) <= 1e-13 * tau, "zero_mb": norm(c["mb"]) <= 1e-13 * tau,
    }
    # the balance residual is relative to its largest term (it checks the larger torque and
    # the force; the smaller torque's accuracy is measured by the resolution study)
    est = max(conv, rec["third_law"], rec["energy_symmetry"], rec["balance"], EST_FLOOR)
    values = dict(fa=list(c["fa"]), ma=list(c["ma"]), mb=list(c["mb"]), v=c["va"],
                  zero_ma=rec["zero_ma"], zero_mb=rec["zero_mb"])
    route = "volume"
    if A.kind == "sphere" or B.kind == "sphere":
        efa, ema, emb, ev, eerr = exact_sphere_case(A, B, g, pos, ra, rb)
        with mp.workdps(MP_DPS + 10):
            rec["volume_vs_exact"] = {
                "force": mp_rel_vec_diff([mpf(t) for t in c["fa"]], efa),
                "torque_on_a": (float(mpmath.norm([mpf(float(p)) - q for p, q in
                                                   zip(c["ma"], ema)]) / mpmath.norm(ema))
                                if mpmath.norm(ema) > 0 else norm(c["ma"]) / tau),
                "torque_on_b": (float(mpmath.norm([mpf(float(p)) - q for p, q in
                                                   zip(c["mb"], emb)]) / mpmath.norm(emb))
                                if mpmath.norm(emb) > 0 else norm(c["mb"]) / tau),
                "energy": float(abs(mpf(c["va"]) - ev) / abs(ev)),
            }
        rec["exact_quadrature_error"] = float(eerr)
        values = dict(fa=efa, ma=ema, mb=emb, v=ev, zero_ma=A.kind == "sphere",
                      zero_mb=B.kind == "sphere")
        route = "exact"
        est_exact = max(float(eerr), 1e-19)
        rec["volume_route_estimate"] = est
        est = est_exact
        if A.kind == "sphere" and B.kind == "sphere":
            # F = G m_A m_B / d^2 along the line of centres
            with mp.workdps(MP_DPS + 10):
                cb = [mpf(t) for t in pos]
                d = mpmath.norm(cb)
                newton = [mpf(g) * mpf(A.mass) * mpf(B.mass) * t / d**3 for t in cb]
                rec["two_spheres_newton"] = mp_rel_vec_diff(values["fa"], newton)
                rec["two_spheres_energy"] = float(abs(values["v"] + mpf(g) * mpf(A.mass)
                                                      * mpf(B.mass) / d) / abs(values["v"]))
    rec["route"] = route
    rec["estimated_relative_accuracy"] = est
    return values, rec


def fmt(x):
    """20 significant digits, exponent form; x a float or an mpf."""
    from decimal import Decimal
    if isinstance(x, float):
        d = Decimal(x + 0.0)
    else:
        d = Decimal(mpmath.nstr(x, 30, min_fixed=1, max_fixed=0))
    if d == 0:
        return "0.0000000000000000000e+00"
    return format(d, ".19e")


def round_up(x):
    """x rounded up to two significant digits."""
    e = math.floor(math.log10(x)) - 1
    return float(f"{math.ceil(x / 10.0**e - 1e-9)}e{e}")


def fmt_vec(v, zero, est):
    if zero:
        return [fmt(0.0)] * 3
    with mp.workdps(MP_DPS + 10):
        vv = [mpf(t) if not isinstance(t, float) else mpf(t) for t in v]
        n = mpmath.norm(vv)
        return [fmt(0.0) if abs(t) < est * n else (fmt(t) if not isinstance(o, float)
                                                    else fmt(o))
                for t, o in zip(vv, v)]


# --------------------------------------------------------------------------------------------
# Coplanar-disk cross-checks


def coplanar_checks(results):
    """Volume route vs the Hankel form (contour-rotated, 25 digits) for the coplanar equal-disk
    cases, vs mpmath.quadosc on the real axis where it converges, and vs disk_pair.json."""
    out = []
    try:
        with open(os.path.join(HERE, "disk_pair.json")) as fh:
            pair = {c["separation"]: c for c in json.load(fh)["cases"]
                    if c["label"].startswith("equal radii")}
    except (OSError, ValueError, KeyError):
        pair = {}
    for values, rec, case in results:
        label, A, B, g, pos, ra, rb = case
        if not (A.kind == B.kind == "disk" and pos[1] == pos[2] == 0.0 and ra == rb == Z):
            continue
        d = pos[0]
        v, dv, err = hankel_coplanar_disks(A.dims["radius"], B.dims["radius"], A.mass, B.mass,
                                           g, d)
        item = {"case": label, "hankel_quadrature_error": float(err),
                "energy_vs_hankel": float(abs(mpf(values["v"]) - v) / abs(v)),
                # F_A = +dV/dd along x (B on the +x axis)
                "force_vs_hankel": rel(values["fa"], [dv, 0.0, 0.0], float(dv))}
        if d >= 3.0 and A.dims["radius"] == B.dims["radius"]:
            i0 = hankel_quadosc(A.dims["radius"], B.dims["radius"], d)
            vq = -mpf(g) * mpf(A.mass) * mpf(B.mass) * i0
            item["hankel_contour_vs_quadosc"] = float(abs(vq - v) / abs(v))
        key = repr(d)
        if key in pair and A.mass == B.mass == 1.0 and g == 1.0 and A.dims["radius"] == 1.0:
            item["energy_vs_disk_pair_json"] = float(
                abs(mpf(values["v"]) - mpf(pair[key]["potential_energy"])) / abs(v))
            item["force_vs_disk_pair_json"] = float(
                abs(mpf(values["fa"][0]) - mpf(pair[key]["dv_dr"])) / abs(dv))
        out.append(item)
        log(f"  {label}: energy vs Hankel {item['energy_vs_hankel']:.1e}, force "
            f"{item['force_vs_hankel']:.1e}"
            + (f", contour vs quadosc {item['hankel_contour_vs_quadosc']:.1e}"
               if "hankel_contour_vs_quadosc" in item else "")
            + (f", vs disk_pair.json {item['energy_vs_disk_pair_json']:.1e} / "
               f"{item['force_vs_disk_pair_json']:.1e}" if "energy_vs_disk_pair_json" in item
               else ""))
        worst = max(item["energy_vs_hankel"], item["force_vs_hankel"],
                    item.get("energy_vs_disk_pair_json", 0.0),
                    item.get("force_vs_disk_pair_json", 0.0))
        if worst > 1e-14 or item.get("hankel_contour_vs_quadosc", 0.0) > 1e-18:
            raise SystemExit(f"coplanar disk check failed: {item}")
    return out


# --------------------------------------------------------------------------------------------
# Conventions check: force and torques as derivatives of the energy


DERIVATIVE_CHECK_CASES = (
    "triaxial (1, 0.7, 0.4) with (0.8, 0.5, 0.3), both rotated, B at (2.2, 0.4, -0.3)",
    "tilted disk A beside a rotated triaxial B at (2.3, 0.2, 0.4)",
    "tilted disks, B (R = 0.8) at (2.2, 0.5, 1.2)",
    "tilted oblate A with sphere B (R = 0.4) at (1.3, 0.2, 0.5)",
)


def energy_derivative_check(case, values, h=1e-3):
    """F_A = dV/d(position_b) (translating B by +e moves A by -e relative to it), M_A = -dV/dtheta
    for A turned by theta about a world axis through its centroid (rotation composed on the
    world side, R -> R(theta e) R), likewise M_B for B; five-point differences of the volume
    energy. Checks the signs and the frame conventions of the written vectors."""
    label, A, B, g, pos, ra, rb = case
    da = sing_distance(A, ra, Z, B, rb, pos)
    oa = vol_orders(A, *da)

    def energy(p, r_a, r_b):
        return integrate_over(A, r_a, Z, B, r_b, p, g, oa, 1.5)[2]

    def turned(rv, axis, th):
        rot = Rotation.from_rotvec(th * np.eye(3)[axis]) * Rotation.from_rotvec(rv)
        return list(rot.as_rotvec())

    def d5(f):
        return (f(-2 * h) - 8 * f(-h) + 8 * f(h) - f(2 * h)) / (12 * h)

    num_f, num_ma, num_mb = [], [], []
    for k in range(3):
        num_f.append(d5(lambda t: energy([p + t * (i == k) for i, p in enumerate(pos)], ra, rb)))
        num_ma.append(-d5(lambda t: energy(pos, turned(ra, k, t), rb)))
        num_mb.append(-d5(lambda t: energy(pos, ra, turned(rb, k, t))))
    tau = norm(values["fa"]) * (norm(pos) + A.size + B.size)

    def scale(v):  # a vanishing torque is compared with |F| times the lever arm
        return norm(v) if norm(v) > 1e-13 * tau else tau

    res = {"check": f"force and torques vs five-point derivatives of the energy (h = {h}), "
           f"case '{label}'",
           "rel_diff_force": rel([float(t) for t in values["fa"]], num_f, norm(values["fa"])),
           "rel_diff_torque_on_a": rel([float(t) for t in values["ma"]], num_ma,
                                       scale(values["ma"])),
           "rel_diff_torque_on_b": rel([float(t) for t in values["mb"]], num_mb,
                                       scale(values["mb"]))}
    worst = max(res["rel_diff_force"], res["rel_diff_torque_on_a"], res["rel_diff_torque_on_b"])
    log(f"  energy derivatives: force {res['rel_diff_force']:.1e}, torque on A "
        f"{res['rel_diff_torque_on_a']:.1e}, torque on B {res['rel_diff_torque_on_b']:.1e}")
    if worst > 1e-8:
        raise SystemExit(f"energy derivative check failed: {res}")
    return res


# --------------------------------------------------------------------------------------------
# Main


METHOD = (
    "Volume (disk: area) integration over each body of the other body's field: ellipsoidal-"
    "spherical coordinates, Gauss-Legendre in s and cos(theta), trapezoid in phi; solid fields "
    "from the Dirichlet 1-D integral (substitution a_i^2+u = (L + d_i t^2)/t^2, Gauss-Legendre "
    "in t), disk fields from the ring integral with K and E and the rim line integral; math.fsum "
    "sums. Every case is computed at 1, 1.5 (and if needed 2.25, 3.375) times its base orders "
    "in every dimension; the estimate is the largest of the last level-to-level change, the "
    "third-law residual |F_A + F_B|/|F_A|, the energy asymmetry |V_A - V_B|/|V| and the "
    "angular-momentum balance residual |M_A + M_B + (c_A - c_B) x F_A| relative to its largest "
    "term. Cases with a sphere: Newton's theorem (F on the sphere = m_sphere * field of the "
    "other body at its centre, evaluated in mpmath at 30 digits; torque on the sphere zero; "
    "torque on the other body from the angular-momentum balance), the volume route agreeing "
    "(see validation). A torque vector written as zeros vanishes by symmetry (|M| < 1e-13 |F_A| "
    "(|position_b| + sizes)); components below the estimated accuracy times the vector's "
    "norm are written as zero. Accuracy figures are relative to the norm of each vector and "
    "to |V|.")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="first 6 cases, no file written")
    args = ap.parse_args()
    log("checks: rotations, Gauss-Legendre")
    validation = []
    validation.append({"check": "rotation matrices (Rodrigues) vs scipy Rotation.from_rotvec, "
                       "hand cases, orthogonality, axis fixed", "max_abs_diff": check_rotations()})
    validation.append({"check": "Gauss-Legendre rules (8..200 points): weights sum, x^6, e^x, "
                       "1/(1.2-x)", "max_abs_err": check_gauss_legendre()})
    log("checks: fields vs mpmath")
    validation.extend(validate_fields())
    cases = CASES[:6] if args.quick else CASES
    results = []
    out_cases = []
    for i, case in enumerate(cases):
        t = time.time()
        values, rec = run_case(case)
        label, A, B, g, pos, ra, rb = case
        results.append((values, rec, case))
        est = rec["estimated_relative_accuracy"]
        extra = ""
        if "volume_vs_exact" in rec:
            ve = rec["volume_vs_exact"]
            extra = (f" | volume vs exact: F {ve['force']:.1e} M_A {ve['torque_on_a']:.1e} "
                     f"M_B {ve['torque_on_b']:.1e} V {ve['energy']:.1e}")
        log(f"case {i + 1}/{len(cases)} {label}: gap {rec['gap']:.3g}, levels {rec['levels']}, "
            f"nodes {rec['nodes_final']}, conv {rec['conv']:.1e}, 3rd law "
            f"{rec['third_law']:.1e}, balance {rec['balance']:.1e}, est {est:.1e}"
            f"{' [zero M_A]' if values['zero_ma'] else ''}"
            f"{' [zero M_B]' if values['zero_mb'] else ''}{extra} ({time.time() - t:.1f}s)")
        out_cases.append({
            "label": label, "a": A.to_json(), "b": B.to_json(), "g": g,
            "position_b": [float(t) for t in pos], "rotation_a": [float(t) for t in ra],
            "rotation_b": [float(t) for t in rb],
            "force_on_a": fmt_vec(values["fa"], False, est),
            "torque_on_a": fmt_vec(values["ma"], values["zero_ma"], est),
            "torque_on_b": fmt_vec(values["mb"], values["zero_mb"], est),
            "potential_energy": fmt(values["v"]) if isinstance(values["v"], float)
            else fmt(values["v"]),
            "estimated_relative_accuracy": round_up(est),
        })
    worst_volume = max((r["estimated_relative_accuracy"] for _, r, _ in results
                        if r["route"] == "volume"), default=0.0)
    if worst_volume > 1e-13:
        raise SystemExit(f"a volume case did not reach 1e-13: {worst_volume}")
    # the volume pipeline against the exact sphere cases
    ex = [r for _, r, _ in results if "volume_vs_exact" in r]
    if ex:
        item = {"check": "volume route vs Newton's theorem (exact, 30 digits) on the cases with "
                "a sphere", "cases": len(ex)}
        for key in ("force", "torque_on_a", "torque_on_b", "energy"):
            item["max_rel_diff_" + key] = max(r["volume_vs_exact"][key] for r in ex
                                              if not r["label"].startswith("SI"))
        si = [r for r in ex if r["label"].startswith("SI")]
        if si:
            item["si_case"] = si[0]["volume_vs_exact"]
        validation.append(item)
        worst = max(item["max_rel_diff_" + k] for k in ("force", "torque_on_a", "torque_on_b",
                                                          "energy"))
        log(f"  volume route vs exact sphere cases: worst {worst:.1e}")
        if worst > 1e-14:
            raise SystemExit("volume route disagrees with the exact sphere cases")
        two = [r for r in ex if "two_spheres_newton" in r]
        for r in two:
            validation.append({"check": "two spheres: F = G m_A m_B / d^2, V = -G m_A m_B / d",
                               "rel_diff_force": r["two_spheres_newton"],
                               "rel_diff_energy": r["two_spheres_energy"]})
            if r["two_spheres_newton"] > 1e-25 or r["two_spheres_energy"] > 1e-25:
                raise SystemExit("two spheres")
    log("checks: energy derivatives")
    for values, rec, case in results:
        if case[0] in DERIVATIVE_CHECK_CASES:
            validation.append(energy_derivative_check(case, values))
    log("checks: coplanar disks vs Hankel transform")
    validation.extend(coplanar_checks(results))
    per_case = [{"label": r["label"], "route": r["route"], "gap": r["gap"],
                 "levels": r["levels"], "nodes_final_level": r["nodes_final"],
                 "level_change": r["conv"], "third_law": r["third_law"],
                 "energy_symmetry": r["energy_symmetry"],
                 "angular_momentum_balance": r["balance"]} for _, r, _ in results]
    doc = {"generator": "tests/reference/interactions.py", "method": METHOD,
           "runtime_seconds": round(time.time() - T0, 1),
           "conventions": "Phi = -G int rho dV/|r-r'| (negative), a = -grad Phi; A's centroid at "
           "the origin with rotation vector rotation_a, B's centroid at position_b with "
           "rotation_b (axis x angle, body -> world); results in the world frame; torques about "
           "each body's own centroid; inputs are doubles (repr), outputs decimal strings with 20 "
           "significant digits.",
           "cases": out_cases, "validation": validation, "diagnostics": per_case}
    if args.quick:
        log("quick run: no file written")
        return
    with open(OUT_PATH, "w") as fh:
        json.dump(doc, fh, indent=1)
        fh.write("\n")
    log(f"wrote {OUT_PATH}: {len(out_cases)} cases")


if __name__ == "__main__":
    sys.exit(main())
