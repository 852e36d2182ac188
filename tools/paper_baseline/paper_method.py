#!/usr/bin/env python3
"""Baseline timing of the founding paper's own method (Wold & Conway, "The planar two-body problem
for spheroids and disks"), on the machine this runs on.

What the paper did, and what this script does the same way:

* Force on spheroid A from spheroid B (paper's Eq. force_eqn):
      F_A = rho_A  int_{-c}^{c} int_0^{2 pi}  Phi_B(r + r_AB)  dS(phi, z)  dphi dz,
      r(phi, z)  = ( (a/c) s cos phi, (b/c) s sin phi, z ),   s = sqrt(c^2 - z^2),
      dS(phi, z) = ( (b/c) s cos phi, (a/c) s sin phi, (a b / c^2) z )          (paper's Eq. 12),
  with r_AB = R_A - R_B the vector from B's centroid to A's (the bodies share their orientation:
  planar motion of spheroids with a common equatorial plane). One call of
  scipy.integrate.dblquad per Cartesian component, phi inner (0 .. 2 pi), z outer (-c .. c), at
  dblquad's default tolerances epsabs = epsrel = 1.49e-8. No symmetry is used (the paper used
  none): F_y and F_z are integrated even where they vanish.
* Mutual energy (paper's Eq. pot_energy), one more dblquad where it is needed (energy diagnostic):
      U = (rho_A / 3) int int [ r Phi_B(r + r_AB) - (1/2) |r|^2 g_B(r + r_AB) ] . dS,
  r measured from A's centroid, g_B = grad Phi_B.
* Phi_B: MacMillan's exterior potential of a homogeneous oblate spheroid (semi-axes a > c, mass M),
  kappa the largest root of (x^2 + y^2) / (a^2 + kappa) + z^2 / (c^2 + kappa) = 1.
* Motion: classical fourth-order Runge-Kutta at a fixed step in the inertial frame, state
  (R_A, R_B, V_A, V_B), accelerations F_A / m_A and -F_A / m_B (Newton's third law, as in the
  paper): one force evaluation (three dblquads) per RK4 stage, four per step.

Sign conventions. The paper's Phi is positive (Phi = G int rho dV / |r - r'|), its field is
g = grad Phi (pointing toward the body) and F = rho int Phi dS points toward B. surfgrav's
potential is the negative of this (Phi_sg = -Phi, a_sg = -grad Phi_sg = g), so surfgrav's
force_on_a equals this F_A, and surfgrav's potential_energy (negative) equals -U. Everything this
script prints and writes is in surfgrav's convention: force toward B, energy negative.

The potential, in the form used here. With e^2 = a^2 - c^2, s0 = sqrt(c^2 + kappa),
t = e / s0 (so that arcsin sqrt((a^2 - c^2) / (a^2 + kappa)) = arctan t), R^2 = x^2 + y^2, and
(3/4) G M = pi G rho a^2 c, the Dirichlet integral
      Phi = pi G rho a^2 c int_kappa^inf (1 - R^2/(a^2+u) - z^2/(c^2+u)) du / ((a^2+u) sqrt(c^2+u))
evaluates (u = s^2 - c^2) to
      Phi   = (3 G M / 4 e^3) [ 2 e^2 arctan t - t^3 (R^2 g1(t) + 2 z^2 g2(t)) ],
      g_x,y = -(3 G M / 2 e^3) t^3 g1(t) (x, y),      g_z = -(3 G M / e^3) t^3 g2(t) z,
      g1(t) = (arctan t - t / (1 + t^2)) / t^3 = sum_{n>=1} (-1)^(n+1) 2n/(2n+1) t^(2n-2),
      g2(t) = (t - arctan t) / t^3            = sum_{n>=1} (-1)^(n+1) 1/(2n+1)  t^(2n-2).
This is MacMillan's expression (the paper's Eq. Eqn_phi_spheroid, whose potential part is printed
correctly) regrouped: the closed forms of g1 and g2 lose about 1/t^2 of their digits to
cancellation, and far from B, where t ~ e / r, MacMillan's grouping loses (r / e)^2 of them
(1e-8 relative at r = 1e4), so g1 and g2 are summed as series below t = 0.1 (nine terms, the first
omitted term < 1e-18). kappa is the quadratic's root written without cancellation:
      kappa^2 + b kappa + C = 0,  b = a^2 + c^2 - R^2 - z^2,  C = a^2 c^2 - R^2 c^2 - z^2 a^2,
      b^2 - 4C = (a^2 - c^2 - R^2 + z^2)^2 + 4 R^2 z^2    (a sum of squares),
      kappa = (sqrt(b^2 - 4C) - b) / 2  if b < 0,   else  -2C / (b + sqrt(b^2 - 4C))  (C < 0).
The cost per call is that of MacMillan's form (one inverse trigonometric function, two square
roots, a few products).

Typos of the paper's printed gradient, corrected here (checked against a numerical gradient by
this script): the prefactor is 2 pi rho a^2 c (printed c^2); f_1 = sqrt(c^2 + kappa) / (e^2
(a^2 + kappa)) (printed without the square root); f_2 = arcsin(sqrt(e^2 / (a^2 + kappa))) / e^3
(printed with kappa^2); G = 1 is implicit throughout. The paper's Eq. 1 writes U negative and its
Eq. pot_energy positive; see above for the convention used here.

Implementation choices that favour the baseline (so the speed-up measured against it is not
inflated): scalar math-module functions in the integrands (no numpy scalars), one closure per
component, an integrand-call counter that costs about 0.02 us per call (1-2 % of a call). The
integrands are otherwise written as a direct transcription of the paper's formulas. Beyond
r ~ 10 from B (t < 0.1) the series makes a call 15-25 % dearer than MacMillan's form; nearer, it is
cheaper (potential_microseconds_per_call in the output).

Run:  python3 tools/paper_baseline/paper_method.py --out tools/paper_baseline/baseline.json
      python3 tools/paper_baseline/paper_method.py --quick --json      (a few seconds)
See tools/paper_baseline/README.md for the output schema.
"""

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import datetime  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import platform  # noqa: E402
import statistics  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from math import atan, asin, cos, pi, sin, sqrt  # noqa: E402

import numpy  # noqa: E402
import scipy  # noqa: E402
from scipy.integrate import dblquad  # noqa: E402

SCHEMA = "surfgrav-paper-baseline/1"
HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))
REFERENCE = os.path.join(REPO, "tests", "reference", "interactions.json")
POTENTIAL_REFERENCE = os.path.join(REPO, "tests", "reference", "potentials.json")

# The paper's 2S model and initial conditions.
PAPER_A, PAPER_C, PAPER_M, PAPER_G = 1.0, 0.25, 1.0, 1.0
PAPER_INITIAL = {
    "R_A": [-3.5, 0.0, 0.0],
    "R_B": [3.5, 0.0, 0.0],
    "V_A": [0.0, 0.2, 0.0],
    "V_B": [0.0, -0.2, 0.0],
}
PAPER_DT = 0.1
PAPER_T_END = 300.0
SEPARATIONS = [2.1, 2.55, 3.0, 7.0, 30.0]

SERIES_BELOW = 0.1


class Spheroid:
    """Homogeneous oblate spheroid, equatorial radius a, polar radius c < a, mass m, constant G."""

    def __init__(self, a, c, mass, g=1.0):
        if not (a > c > 0.0 and mass > 0.0 and g > 0.0):
            raise ValueError("need a > c > 0 (oblate), mass > 0 and G > 0")
        self.a, self.c, self.mass, self.g = a, c, mass, g
        self.rho = mass / (4.0 / 3.0 * pi * a * a * c)
        self.e2 = a * a - c * c
        self.e = sqrt(self.e2)


def kappa_root(a2, c2, r2, z2):
    """Largest root of r2/(a2+k) + z2/(c2+k) = 1 (0 for points on or inside the surface)."""
    b = a2 + c2 - r2 - z2
    p = a2 - c2 - r2 + z2
    sq = sqrt(p * p + 4.0 * r2 * z2)
    if b < 0.0:
        return 0.5 * (sq - b)
    cc = a2 * c2 - r2 * c2 - z2 * a2
    if cc >= 0.0:
        return 0.0
    return -2.0 * cc / (b + sq)


def _series_g1(u):
    """g1 at t^2 = u < 0.01: 2/3 - 4/5 u + 6/7 u^2 - ... (9 terms; the 10th < 1e-18)."""
    return 2/3 - u * (4/5 - u * (6/7 - u * (8/9 - u * (10/11 - u * (12/13 - u * (
        14/15 - u * (16/17 - u * (18/19))))))))


def _series_g2(u):
    """g2 at t^2 = u < 0.01: 1/3 - 1/5 u + 1/7 u^2 - ... (9 terms; the 10th < 1e-18)."""
    return 1/3 - u * (1/5 - u * (1/7 - u * (1/9 - u * (1/11 - u * (1/13 - u * (
        1/15 - u * (1/17 - u * (1/19))))))))


def _g1_g2(t):
    if t < SERIES_BELOW:
        u = t * t
        return _series_g1(u), _series_g2(u)
    at = atan(t)
    t3 = t * t * t
    return (at - t / (1.0 + t * t)) / t3, (t - at) / t3


def make_potential(body):
    """Paper-convention (positive) exterior potential of `body` at a point of its own frame."""
    a2, c2, e, e2 = body.a * body.a, body.c * body.c, body.e, body.e2
    k0 = 0.75 * body.g * body.mass / (e2 * e)

    def potential(x, y, z):
        r2 = x * x + y * y
        z2 = z * z
        t = e / sqrt(c2 + kappa_root(a2, c2, r2, z2))
        if t < SERIES_BELOW:
            u = t * t
            g1 = _series_g1(u)
            g2 = _series_g2(u)
            at = atan(t)
        else:
            at = atan(t)
            t3 = t * t * t
            g1 = (at - t / (1.0 + t * t)) / t3
            g2 = (t - at) / t3
        return k0 * (2.0 * e2 * at - t * t * t * (r2 * g1 + 2.0 * z2 * g2))

    return potential


def make_field(body):
    """Paper-convention field g = grad Phi (points toward the body) at a point of its own frame."""
    a2, c2, e, e2 = body.a * body.a, body.c * body.c, body.e, body.e2
    k1 = 1.5 * body.g * body.mass / (e2 * e)

    def field(x, y, z):
        t = e / sqrt(c2 + kappa_root(a2, c2, x * x + y * y, z * z))
        g1, g2 = _g1_g2(t)
        t3 = t * t * t
        return (-k1 * t3 * g1 * x, -k1 * t3 * g1 * y, -2.0 * k1 * t3 * g2 * z)

    return field


def make_macmillan_potential(body):
    """The paper's Eq. Eqn_phi_spheroid as printed (with G), kappa by the plain quadratic formula.

    Used to check the regrouped form and to compare the cost per call of the two."""
    a2, c2, e2, e = body.a ** 2, body.c ** 2, body.e2, body.e
    pref = pi * body.g * body.rho * a2 * body.c

    def potential(x, y, z):
        r2, z2 = x * x + y * y, z * z
        b = a2 + c2 - r2 - z2
        cc = a2 * c2 - r2 * c2 - z2 * a2
        k = max(0.0, 0.5 * (-b + sqrt(b * b - 4.0 * cc)))
        arc = asin(sqrt(e2 / (a2 + k)))
        return (
            2.0 * pref / e * (1.0 - (r2 - 2.0 * z2) / (2.0 * e2)) * arc
            + pref * sqrt(c2 + k) / e2 * r2 / (a2 + k)
            - pref / e2 * 2.0 * z2 / sqrt(c2 + k)
        )

    return potential


def macmillan_potential(body, x, y, z):
    return make_macmillan_potential(body)(x, y, z)


def potential_cost(body, calls=100000):
    """Seconds per call of the potential alone: the form used here and MacMillan's as printed."""
    pts = [(3.0 + 0.3 * math.cos(k), 0.7 * math.sin(k), 0.1 * math.cos(3 * k)) for k in range(100)]
    far = [(30.0 + x, y, z) for x, y, z in pts]
    out = {}
    for name, fn in (("used_form", make_potential(body)),
                     ("macmillan_as_printed", make_macmillan_potential(body))):
        for label, sample in (("near_r3", pts), ("far_r30", far)):
            reps = calls // len(sample)
            w = time.perf_counter()
            for _ in range(reps):
                for x, y, z in sample:
                    fn(x, y, z)
            out[f"{name}_{label}"] = 1e6 * (time.perf_counter() - w) / (reps * len(sample))
    return out


def macmillan_field(body, x, y, z, printed=False):
    """Paper gradient via f1, f2, f3; printed=True keeps its typos (c^2, no root, kappa^2)."""
    a2, c2, e2 = body.a ** 2, body.c ** 2, body.e2
    r2, z2 = x * x + y * y, z * z
    k = kappa_root(a2, c2, r2, z2)
    if printed:
        pref = 2.0 * pi * body.g * body.rho * a2 * c2
        f1 = (c2 + k) / (e2 * (a2 + k))
        f2 = asin(sqrt(e2 / (a2 + k * k))) / e2 ** 1.5
    else:
        pref = 2.0 * pi * body.g * body.rho * a2 * body.c
        f1 = sqrt(c2 + k) / (e2 * (a2 + k))
        f2 = asin(sqrt(e2 / (a2 + k))) / e2 ** 1.5
    f3 = 1.0 / (e2 * sqrt(c2 + k))
    return (pref * x * (f1 - f2), pref * y * (f1 - f2), pref * 2.0 * z * (f2 - f3))


class Counter:
    def __init__(self):
        self.n = 0


def force_on_a(body_a, body_b, r_ab, counter):
    """F_A = rho_A int int Phi_B dS: three dblquads (x, y, z), phi inner, z outer.

    Returns (force, abserr estimates, integrand calls per component)."""
    a, b, c = body_a.a, body_a.a, body_a.c
    rho = body_a.rho
    dx, dy, dz = r_ab
    phi_b = make_potential(body_b)

    def fx(phi, z):
        counter.n += 1
        s = sqrt(c * c - z * z)
        return phi_b(a / c * s * cos(phi) + dx, b / c * s * sin(phi) + dy, z + dz) * (
            b / c * s * cos(phi)
        )

    def fy(phi, z):
        counter.n += 1
        s = sqrt(c * c - z * z)
        return phi_b(a / c * s * cos(phi) + dx, b / c * s * sin(phi) + dy, z + dz) * (
            a / c * s * sin(phi)
        )

    def fz(phi, z):
        counter.n += 1
        s = sqrt(c * c - z * z)
        return phi_b(a / c * s * cos(phi) + dx, b / c * s * sin(phi) + dy, z + dz) * (
            a * b / (c * c) * z
        )

    out, errs, calls = [], [], []
    for integrand in (fx, fy, fz):
        n0 = counter.n
        val, err = dblquad(integrand, -c, c, 0.0, 2.0 * pi)
        out.append(rho * val)
        errs.append(rho * err)
        calls.append(counter.n - n0)
    return out, errs, calls


def energy_u(body_a, body_b, r_ab, counter):
    """Paper's U = (rho_A/3) int int [r Phi_B - |r|^2 g_B / 2] . dS (positive); one dblquad."""
    a, b, c = body_a.a, body_a.a, body_a.c
    rho = body_a.rho
    dx, dy, dz = r_ab
    phi_b = make_potential(body_b)
    g_b = make_field(body_b)

    def fu(phi, z):
        counter.n += 1
        s = sqrt(c * c - z * z)
        x = a / c * s * cos(phi)
        y = b / c * s * sin(phi)
        sx = b / c * s * cos(phi)
        sy = a / c * s * sin(phi)
        sz = a * b / (c * c) * z
        p = phi_b(x + dx, y + dy, z + dz)
        gx, gy, gz = g_b(x + dx, y + dy, z + dz)
        h = 0.5 * (x * x + y * y + z * z)
        return (x * p - h * gx) * sx + (y * p - h * gy) * sy + (z * p - h * gz) * sz

    n0 = counter.n
    val, err = dblquad(fu, -c, c, 0.0, 2.0 * pi)
    return rho * val / 3.0, rho * err / 3.0, counter.n - n0


# ----------------------------------------------------------------------------- checks


def _rel(x, y):
    return abs(x - y) / abs(y)


def _norm(v):
    return math.sqrt(sum(t * t for t in v))


def _vrel(v, w):
    return _norm([p - q for p, q in zip(v, w)]) / _norm(w)


def run_checks(body, log):
    """Verify the potential before anything is timed. Returns a list of check records."""
    checks = []

    def record(name, value, limit, note):
        ok = value <= limit
        checks.append({"name": name, "value": value, "limit": limit, "passed": ok, "note": note})
        log(f"  check {name}: {value:.3e} (limit {limit:.1e}) {'ok' if ok else 'FAILED'}")

    pot = make_potential(body)
    fld = make_field(body)
    gm = body.g * body.mass
    e2 = body.e2

    # 1. Far field against a point mass, with and without the quadrupole term.
    worst_quad, worst_plain4, worst_plain5, worst_field = 0.0, 0.0, 0.0, 0.0
    for r in (1e4, 1e5):
        for ux, uy, uz in ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0), (2.0 / 7.0, -3.0 / 7.0, 6.0 / 7.0)):
            x, y, z = r * ux, r * uy, r * uz
            cos2 = uz * uz
            exact = gm / r * (1.0 + e2 / (10.0 * r * r) * (1.0 - 3.0 * cos2))
            v = pot(x, y, z)
            if r == 1e4:
                worst_quad = max(worst_quad, _rel(v, exact))
                worst_plain4 = max(worst_plain4, _rel(v, gm / r))
                # gradient of GM/r + (GM e^2/10)(1/r^3 - 3 z^2/r^5)
                q5 = gm * e2 / 10.0 / r**5
                exact_g = [-gm * q / r**3 + q5 * (-3.0 * q + 15.0 * z * z * q / (r * r))
                           for q in (x, y, z)]
                exact_g[2] -= q5 * 6.0 * z
                worst_field = max(worst_field, _vrel(fld(x, y, z), exact_g))
            else:
                worst_plain5 = max(worst_plain5, _rel(v, gm / r))
    record(
        "far_field_quadrupole_r1e4", worst_quad, 1e-13,
        "max |Phi/(GM/r (1 + e^2 (1 - 3 cos^2 theta)/(10 r^2))) - 1| at r = 1e4, 3 directions; "
        "next multipole term ~ (e/r)^4 = 1e-16",
    )
    record(
        "far_field_point_mass_r1e5", worst_plain5, 1e-10,
        "max |Phi r/(GM) - 1| at r = 1e5 (quadrupole 1.9e-11 along the pole)",
    )
    checks.append({
        "name": "far_field_point_mass_r1e4_info", "value": worst_plain4, "limit": None,
        "passed": True,
        "note": "max |Phi r/(GM) - 1| at r = 1e4: the physical quadrupole e^2/(5 r^2) = 1.9e-9 "
                "along the pole, so 1/r alone cannot be met to 1e-10 there; see the check above",
    })
    log(f"  info  |Phi r/GM - 1| at r = 1e4 (quadrupole, physical): {worst_plain4:.3e}")
    record(
        "far_field_gradient_quadrupole_r1e4", worst_field, 1e-13,
        "|g - grad(point mass + quadrupole)| / |g| at r = 1e4, same 3 directions",
    )

    # 2. Numerical gradient (five-point central differences, h = 1e-3) near and far.
    pts = [
        (1.05, 0.0, 0.0), (1.2, 0.3, 0.1), (0.3, -0.2, 0.3), (2.1, 0.0, 0.0), (3.0, 1.0, -0.2),
        (-1.9, 0.7, 0.25), (7.0, 0.0, 0.0), (0.05, 0.05, 0.4), (30.0, 2.0, 1.0),
    ]
    worst_num, worst_printed = 0.0, 0.0
    for p in pts:
        h = 2e-4 * max(1.0, _norm(p))
        num = []
        for i in range(3):
            def shifted(d, i=i):
                q = list(p)
                q[i] += d
                return pot(*q)
            num.append((-shifted(2 * h) + 8 * shifted(h) - 8 * shifted(-h) + shifted(-2 * h))
                       / (12 * h))
        worst_num = max(worst_num, _vrel(fld(*p), num))
        worst_printed = max(worst_printed, _vrel(macmillan_field(body, *p, printed=True), num))
    record(
        "gradient_vs_five_point_difference", worst_num, 1e-10,
        "|g - D5 Phi| / |D5 Phi|, h = 2e-4 max(1, r), 9 points from gap 0.05 to r = 30 "
        "(difference error "
        "h^4 Phi^(5)/30 ~ 2e-12 at gap 0.05, rounding eps Phi / h ~ 2e-12)",
    )
    checks.append({
        "name": "printed_gradient_vs_five_point_difference_info", "value": worst_printed,
        "limit": None, "passed": True,
        "note": "the paper's f1, f2, f3 and prefactor exactly as printed, same points: the typos "
                "(c^2 prefactor, f1 without sqrt, kappa^2 in f2) give an O(1) error",
    })
    log(f"  info  paper's gradient as printed vs numerical gradient: {worst_printed:.3e}")

    # 3. Corrected gradient formula (f1, f2, f3) and MacMillan's grouping vs the form used here,
    #    on A's surface at the timed separations.
    worst_mac_pot, worst_mac_fld = 0.0, 0.0
    for d in SEPARATIONS:
        for j in range(7):
            zz = body.c * math.cos(pi * (j + 0.5) / 7)
            s = math.sqrt(body.c**2 - zz**2)
            for k in range(12):
                ph = 2 * pi * k / 12
                x = body.a / body.c * s * math.cos(ph) - d
                y = body.a / body.c * s * math.sin(ph)
                worst_mac_pot = max(worst_mac_pot, _rel(macmillan_potential(body, x, y, zz),
                                                        pot(x, y, zz)))
                worst_mac_fld = max(worst_mac_fld, _vrel(macmillan_field(body, x, y, zz),
                                                         fld(x, y, zz)))
    record(
        "macmillan_closed_form_vs_used_form", worst_mac_pot, 1e-12,
        "paper's printed potential (quadratic-formula kappa, arcsin) vs the regrouped form, 84 "
        "points on A's surface at each separation 2.1 .. 30; MacMillan's grouping itself loses "
        "about (r/e)^2 eps = 2e-13 at r = 31",
    )
    record(
        "corrected_f1_f2_f3_vs_used_form", worst_mac_fld, 1e-12,
        "paper's gradient with the typos corrected vs the regrouped form, same points (same "
        "cancellation in f1 - f2 and f2 - f3)",
    )

    # 4. Independent high-precision values (mpmath, Dirichlet integral) from surfgrav's tests.
    if os.path.exists(POTENTIAL_REFERENCE):
        with open(POTENTIAL_REFERENCE) as f:
            ref = json.load(f)
        worst_p, worst_g, n = 0.0, 0.0, 0
        for case in ref["cases"]:
            prm = case["params"]
            if case["body"] != "spheroid" or case["region"] != "outside":
                continue
            if float(prm["equatorial_radius"]) != body.a or float(prm["polar_radius"]) != body.c:
                continue
            if float(prm["mass"]) != body.mass or float(prm["g"]) != body.g:
                continue
            x, y, z = (float(q) for q in case["point"])
            # surfgrav: Phi_sg = -Phi, a_sg = g.
            worst_p = max(worst_p, _rel(-pot(x, y, z), float(case["potential"])))
            worst_g = max(worst_g, _vrel(fld(x, y, z), [float(q) for q in case["acceleration"]]))
            n += 1
        record(
            f"potential_vs_potentials_json_{n}_points", worst_p, 1e-13,
            "exterior points of the (1, 0.25) spheroid in tests/reference/potentials.json, gaps "
            "1e-12 .. 1e8 radii (mpmath Dirichlet integral, 1e-29)",
        )
        record(
            f"field_vs_potentials_json_{n}_points", worst_g, 1e-13,
            "same points, |g - a_ref| / |a_ref|",
        )
    return checks


# ----------------------------------------------------------------------------- measurements


def load_reference():
    if not os.path.exists(REFERENCE):
        return {}
    with open(REFERENCE) as f:
        data = json.load(f)
    out = {}
    for case in data["cases"]:
        a, b = case["a"], case["b"]
        if not (a.get("kind") == b.get("kind") == "spheroid"):
            continue
        same = all(
            s.get("equatorial_radius") == PAPER_A and s.get("polar_radius") == PAPER_C
            and s.get("mass") == PAPER_M for s in (a, b)
        )
        pos = case["position_b"]
        if (same and case["g"] == PAPER_G and pos[1] == 0.0 and pos[2] == 0.0
                and not any(case["rotation_a"]) and not any(case["rotation_b"])):
            out[pos[0]] = {
                "label": case["label"],
                "force_on_a": [float(q) for q in case["force_on_a"]],
                "potential_energy": float(case["potential_energy"]),
            }
    return out


def time_separation(body, d, angle, repeats, min_seconds, with_energy, reference):
    """Force on A at the origin from B at d (cos angle, sin angle, 0): r_AB = -that."""
    counter = Counter()
    walls, cpus = [], []
    ca, sa = math.cos(angle), math.sin(angle)
    r_ab = (-d * ca, -d * sa, 0.0)
    force = errs = calls = None
    start = time.perf_counter()
    while len(walls) < repeats or (time.perf_counter() - start < min_seconds and len(walls) < 50):
        c0 = time.process_time()
        w0 = time.perf_counter()
        force, errs, calls = force_on_a(body, body, r_ab, counter)
        walls.append(time.perf_counter() - w0)
        cpus.append(time.process_time() - c0)
    n_calls = sum(calls)
    med = statistics.median(walls)
    rec = {
        "separation": d,
        "direction_angle_rad": angle,
        "force_on_a": force,
        "dblquad_abserr_estimate": errs,
        "evaluations_timed": len(walls),
        "seconds_per_force_evaluation_median": med,
        "seconds_per_force_evaluation_min": min(walls),
        "cpu_seconds_per_force_evaluation_median": statistics.median(cpus),
        "integrand_calls_per_force_evaluation": n_calls,
        "integrand_calls_per_component": calls,
        "microseconds_per_integrand_call": 1e6 * med / n_calls,
    }
    ref = reference.get(d)
    if ref:
        fr = ref["force_on_a"]  # B on the +x axis; the pair is axisymmetric: rotate about z
        fr = [fr[0] * ca - fr[1] * sa, fr[0] * sa + fr[1] * ca, fr[2]]
        rec["reference_force_on_a"] = fr
        rec["force_relative_error"] = _vrel(force, fr)
    if with_energy:
        ew = time.perf_counter()
        u, uerr, ucalls = energy_u(body, body, r_ab, counter)
        ew = time.perf_counter() - ew
        rec["potential_energy"] = -u
        rec["energy_dblquad_abserr_estimate"] = uerr
        rec["energy_integrand_calls"] = ucalls
        rec["seconds_per_energy_evaluation"] = ew
        if ref:
            rec["reference_potential_energy"] = ref["potential_energy"]
            rec["energy_relative_error"] = _rel(-u, ref["potential_energy"])
    return rec


def rk4_run(body, t_end, dt, energy_every_step, log, every=10):
    """The paper's 2S run: classical RK4, fixed step, inertial frame (bodies A and B identical)."""
    m_a = m_b = body.mass
    counter = Counter()
    ra, rb = list(PAPER_INITIAL["R_A"]), list(PAPER_INITIAL["R_B"])
    va, vb = list(PAPER_INITIAL["V_A"]), list(PAPER_INITIAL["V_B"])

    def deriv(state):
        ra_, rb_, va_, vb_ = state
        f, _, _ = force_on_a(body, body, [p - q for p, q in zip(ra_, rb_)], counter)
        return (va_, vb_, [q / m_a for q in f], [-q / m_b for q in f])

    def axpy(state, k, h):
        return tuple([p + h * q for p, q in zip(s, kk)] for s, kk in zip(state, k))

    def total_energy(state):
        ra_, rb_, va_, vb_ = state
        u, _, n = energy_u(body, body, [p - q for p, q in zip(ra_, rb_)], counter)
        kin = 0.5 * m_a * sum(q * q for q in va_) + 0.5 * m_b * sum(q * q for q in vb_)
        return kin - u, n

    def ang_mom(state):
        ra_, rb_, va_, vb_ = state
        lz = m_a * (ra_[0] * va_[1] - ra_[1] * va_[0]) + m_b * (rb_[0] * vb_[1] - rb_[1] * vb_[0])
        return lz

    steps = int(round(t_end / dt))
    state = (ra, rb, va, vb)
    energy_seconds = 0.0
    energy_calls = 0
    energies = []
    if energy_every_step:
        w = time.perf_counter()
        e0, n = total_energy(state)
        energy_seconds += time.perf_counter() - w
        energy_calls += n
        energies.append(e0)
    l0 = ang_mom(state)
    step_calls, step_walls = [], []
    min_sep = _norm([p - q for p, q in zip(ra, rb)])
    cpu0 = time.process_time()
    force_seconds = 0.0
    for i in range(steps):
        n0 = counter.n
        w = time.perf_counter()
        k1 = deriv(state)
        k2 = deriv(axpy(state, k1, 0.5 * dt))
        k3 = deriv(axpy(state, k2, 0.5 * dt))
        k4 = deriv(axpy(state, k3, dt))
        state = tuple(
            [p + dt / 6.0 * (q1 + 2.0 * q2 + 2.0 * q3 + q4) for p, q1, q2, q3, q4 in
             zip(s, a1, a2, a3, a4)]
            for s, a1, a2, a3, a4 in zip(state, k1, k2, k3, k4)
        )
        step_walls.append(time.perf_counter() - w)
        step_calls.append(counter.n - n0)
        force_seconds += step_walls[-1]
        min_sep = min(min_sep, _norm([p - q for p, q in zip(state[0], state[1])]))
        if energy_every_step:
            w = time.perf_counter()
            e, n = total_energy(state)
            energy_seconds += time.perf_counter() - w
            energy_calls += n
            energies.append(e)
        if (i + 1) % every == 0 or i + 1 == steps:
            log(f"  step {i + 1}/{steps}: t = {(i + 1) * dt:.1f}, "
                f"{step_calls[-1]} integrand calls, {step_walls[-1] * 1e3:.1f} ms")
    cpu = time.process_time() - cpu0
    total_steps_paper = int(round(PAPER_T_END / dt))
    per_step = force_seconds / steps
    rec = {
        "integrator": "classical RK4, fixed step, inertial frame",
        "dt": dt,
        "t_end": steps * dt,
        "steps": steps,
        "initial": PAPER_INITIAL,
        "final_positions": {"R_A": state[0], "R_B": state[1]},
        "final_velocities": {"V_A": state[2], "V_B": state[3]},
        "final_separation": _norm([p - q for p, q in zip(state[0], state[1])]),
        "min_separation_at_steps": min_sep,
        "angular_momentum_z_relative_change": abs(ang_mom(state) - l0) / abs(l0),
        "wall_seconds_forces": force_seconds,
        "cpu_seconds_forces_and_energy": cpu,
        "seconds_per_step": per_step,
        "seconds_per_step_median": statistics.median(step_walls),
        "integrand_calls_per_step_mean": sum(step_calls) / steps,
        "integrand_calls_per_step_min": min(step_calls),
        "integrand_calls_per_step_max": max(step_calls),
        "microseconds_per_integrand_call": 1e6 * force_seconds / sum(step_calls),
        "extrapolated_full_run": {
            "t_end": PAPER_T_END,
            "steps": total_steps_paper,
            "seconds_forces_only": per_step * total_steps_paper,
            "method": f"linear in the number of steps from this {steps}-step run "
                      f"(t = 0 .. {steps * dt:g}); not a measurement of the whole run",
        },
    }
    if energy_every_step:
        rec["energy_every_step"] = {
            "wall_seconds": energy_seconds,
            "integrand_calls_per_energy_evaluation_mean": energy_calls / len(energies),
            "seconds_per_energy_evaluation": energy_seconds / len(energies),
            "initial_total_energy": energies[0],
            "max_abs_relative_energy_change": max(abs(e - energies[0]) / abs(energies[0])
                                                  for e in energies),
            "max_abs_relative_step_to_step_change": max(
                abs(energies[i + 1] - energies[i]) / abs(energies[0])
                for i in range(len(energies) - 1)),
        }
        rec["extrapolated_full_run"]["seconds_with_energy_every_step"] = (
            (force_seconds + energy_seconds) / steps * total_steps_paper)
    return rec


def machine_description():
    model = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        load = list(os.getloadavg())
    except OSError:
        load = None
    return {
        "cpu_model": model,
        "logical_cpus": os.cpu_count(),
        "load_average_1_5_15_min_at_start": load,
        "platform": platform.platform(),
    }


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true",
                    help="checks, 3 force evaluations per separation (B on the x axis), a "
                         "10-step run (t = 1) without energy, no whole run: about a second")
    ap.add_argument("--json", action="store_true", help="print the result JSON on stdout")
    ap.add_argument("--out", help="write the result JSON to this file")
    ap.add_argument("--t-end", type=float, default=3.0,
                    help="length of the shortened paper-2s run (default 3, i.e. 30 steps)")
    ap.add_argument("--repeats", type=int, default=5,
                    help="force evaluations timed per separation (at least; default 5)")
    ap.add_argument("--no-full-run", action="store_true",
                    help="skip the whole paper-2s run (t = 300, 3000 steps, about a minute)")
    ap.add_argument("--no-energy", action="store_true",
                    help="skip the energy (pot_energy dblquad) at every RK4 step")
    args = ap.parse_args(argv)

    def log(msg):
        print(msg, file=sys.stderr, flush=True)

    t0 = time.perf_counter()
    body = Spheroid(PAPER_A, PAPER_C, PAPER_M, PAPER_G)
    result = {
        "schema": SCHEMA,
        "generator": "tools/paper_baseline/paper_method.py",
        "mode": "quick" if args.quick else "full",
        "date_utc": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "machine": machine_description(),
        "software": {"python": platform.python_version(), "numpy": numpy.__version__,
                     "scipy": scipy.__version__},
        "method": {
            "force": "F_A = rho_A int int Phi_B dS, dS of the paper's Eq. 12; one "
                     "scipy.integrate.dblquad per component (x, y, z), phi inner 0..2pi, z outer "
                     "-c..c, no symmetry used",
            "energy": "U = (rho_A/3) int int [r Phi_B - |r|^2 g_B / 2] . dS, one dblquad",
            "dblquad_epsabs": 1.49e-8,
            "dblquad_epsrel": 1.49e-8,
            "potential": "MacMillan's exterior potential of an oblate spheroid, regrouped "
                         "without cancellation (see the script's docstring)",
            "integrator": "classical RK4, fixed step, inertial frame",
            "sign_convention": "surfgrav's: force_on_a points toward B, potential_energy < 0",
        },
        "bodies": {"equatorial_radius": PAPER_A, "polar_radius": PAPER_C, "mass": PAPER_M,
                   "g": PAPER_G, "identical": True},
        "units": {
            "seconds_*": "s (wall clock, time.perf_counter) unless prefixed cpu_",
            "microseconds_per_integrand_call": "us",
            "force_on_a": "G m^2 / length^2 in the paper's unit-less system",
            "potential_energy": "G m^2 / length",
            "separation, positions": "length (paper units, a = 1)",
            "integrand_calls_*": "count of Python integrand evaluations",
        },
    }

    log("checks of the potential:")
    checks = run_checks(body, log)
    result["checks"] = checks
    failed = [c["name"] for c in checks if not c["passed"]]
    if failed:
        log(f"checks failed: {failed}; nothing timed, nothing written")
        return 1

    if not args.quick:
        cost = potential_cost(body)
        result["potential_microseconds_per_call"] = cost
        log("potential alone, us per call: "
            + ", ".join(f"{k} {v:.2f}" for k, v in cost.items()))

    reference = load_reference()
    log("force evaluations:")
    repeats = 3 if args.quick else max(1, args.repeats)
    min_seconds = 0.0 if args.quick else 1.0
    evals = []
    for angle, d in [(0.0, d) for d in SEPARATIONS] + [(1.0, d) for d in SEPARATIONS]:
        if args.quick and angle != 0.0:
            continue
        rec = time_separation(body, d, angle, repeats, min_seconds, not args.quick, reference)
        evals.append(rec)
        msg = (f"  d = {d:5}, angle {angle:g}: "
               f"{rec['seconds_per_force_evaluation_median'] * 1e3:8.2f} ms, "
               f"{rec['integrand_calls_per_force_evaluation']:6d} calls "
               f"{rec['integrand_calls_per_component']}, "
               f"{rec['microseconds_per_integrand_call']:.2f} us/call")
        if "force_relative_error" in rec:
            msg += f", |F - F_ref|/|F_ref| = {rec['force_relative_error']:.2e}"
        if "energy_relative_error" in rec:
            msg += f", energy rel. err. {rec['energy_relative_error']:.2e}"
        log(msg)
    result["force_evaluations"] = evals
    at3 = next(r for r in evals if r["separation"] == 3.0 and r["direction_angle_rad"] == 0.0)
    if "force_relative_error" in at3:
        ok = at3["force_relative_error"] <= 1e-7
        checks.append({
            "name": "force_at_separation_3_vs_interactions_json",
            "value": at3["force_relative_error"], "limit": 1e-7, "passed": ok,
            "note": "|F - F_ref| / |F_ref| against tests/reference/interactions.json (volume "
                    "integration, 2.2e-16); dblquad's tolerance is 1.49e-8",
        })
        if not ok:
            log("force at separation 3 disagrees with surfgrav's reference; nothing written")
            return 1
    else:
        log("  (tests/reference/interactions.json not found: no reference comparison)")

    log("shortened paper-2s run:")
    t_end = 1.0 if args.quick else args.t_end
    run = rk4_run(body, t_end, PAPER_DT, not (args.quick or args.no_energy), log)
    result["rk4_run"] = run
    ext = run["extrapolated_full_run"]
    log(f"  {run['steps']} steps: {run['seconds_per_step'] * 1e3:.1f} ms/step, "
        f"{run['integrand_calls_per_step_mean']:.0f} calls/step, "
        f"{run['microseconds_per_integrand_call']:.2f} us/call; extrapolated to t = 300: "
        f"{ext['seconds_forces_only']:.1f} s (forces only)")
    if not (args.no_full_run or args.quick):
        log("whole paper-2s run (t = 300):")
        full = rk4_run(body, PAPER_T_END, PAPER_DT, not args.no_energy, log, every=500)
        del full["extrapolated_full_run"]
        full["extrapolation_from_shortened_run_over_measured"] = (
            ext["seconds_forces_only"] / full["wall_seconds_forces"])
        result["rk4_full_run"] = full
        log(f"  measured: {full['wall_seconds_forces']:.1f} s (forces only), "
            f"{full['integrand_calls_per_step_mean']:.0f} calls/step; the shortened run's "
            f"extrapolation is {full['extrapolation_from_shortened_run_over_measured']:.3f} of it")
    result["summary"] = {
        "microseconds_per_integrand_call_in_run": run["microseconds_per_integrand_call"],
        "integrand_calls_per_rk4_step": run["integrand_calls_per_step_mean"],
        "seconds_per_rk4_step": run["seconds_per_step"],
        "extrapolated_paper_2s_seconds_forces_only": ext["seconds_forces_only"],
        "seconds_per_force_evaluation_at_separation": {
            str(r["separation"]): r["seconds_per_force_evaluation_median"] for r in evals
            if r["direction_angle_rad"] == 0.0},
        "integrand_calls_per_force_evaluation_at_separation": {
            str(r["separation"]): r["integrand_calls_per_force_evaluation"] for r in evals
            if r["direction_angle_rad"] == 0.0},
    }
    if "seconds_with_energy_every_step" in ext:
        result["summary"]["extrapolated_paper_2s_seconds_with_energy_every_step"] = (
            ext["seconds_with_energy_every_step"])
    if "rk4_full_run" in result:
        full = result["rk4_full_run"]
        result["summary"]["measured_paper_2s_seconds_forces_only"] = full["wall_seconds_forces"]
        if "energy_every_step" in full:
            result["summary"]["measured_paper_2s_seconds_with_energy_every_step"] = (
                full["wall_seconds_forces"] + full["energy_every_step"]["wall_seconds"])
    result["runtime_seconds"] = time.perf_counter() - t0
    try:
        result["machine"]["load_average_1_5_15_min_at_end"] = list(os.getloadavg())
    except OSError:
        pass
    text = json.dumps(result, indent=1)
    if args.out:
        with open(args.out, "w") as f:
            f.write(text + "\n")
        log(f"wrote {args.out}")
    if args.json:
        print(text)
    log(f"total {result['runtime_seconds']:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
