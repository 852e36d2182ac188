#!/usr/bin/env python3
"""Reference mutual potential energy and force of two coplanar uniform disks.

Writes tests/reference/disk_pair.json (next to this script) for
crates/potentials/tests/disk_pair.rs, which checks the closed form of Conway (2016) implemented in
crates/potentials/src/disk_pair.rs.

Route (independent of Conway's closed form): the lens-area convolution. For disks A (radius a,
surface density s_A = m_A / (pi a^2)) and B (radius b, s_B) in one plane with centres a distance
r >= a + b apart,

    V(r) = -G s_A s_B  int_A int_B dA dA' / |x - x'|
         = -G s_A s_B  int_{R^2} lens(|e|) / |c - e| d^2e            (e = c - (x' - x))
         = -G s_A s_B  int_0^{a+b} lens(L) L [4 K(m) / (r + L)] dL,  m = 4 r L / (r + L)^2,

where lens(L) is the area of the intersection of two disks of radii a and b whose centres are L
apart (pi min(a, b)^2 for L <= |a - b|, 0 for L >= a + b) and the angular integral
int_0^{2 pi} dphi / sqrt(r^2 + L^2 - 2 r L cos phi) = 4 K(m) / (r + L) (K with parameter m = k^2).
Differentiating under the integral sign,

    dV/dr = -G s_A s_B int_0^{a+b} lens(L) L 4 [ -(E - (1 - m) K) / (2 r (r - L)) - K / (r + L)^2 ] dL.

Both integrands are smooth inside the intervals [0, |a - b|] and [|a - b|, a + b] and have
integrable endpoint singularities (lens ~ (a + b - L)^{3/2}; K logarithmic near L = r, which
approaches the end point a + b at contact); mpmath's tanh-sinh quadrature handles them. The
script works with WORKING_DIGITS digits, asks mpmath for its error estimate and refuses to write
the file if any estimate exceeds 10^-(OUTPUT_DIGITS + 2) relative.

Cross-checks run before writing (the script stops on a mismatch):
- the Hankel-transform representation
  V = -G m_A m_B int_0^inf [2 J1(k a)/(k a)] [2 J1(k b)/(k b)] J0(k r) dk
  (Fourier transform of each disk, 2 pi / k for the plane kernel 1/|x|), by mpmath.quadosc at
  HANKEL_DIGITS digits, at three separations, to 1e-20;
- the far-field double series V = -G m_A m_B sum_n I_n sum_{i+j=n} c_i c_j a^{2i} b^{2j} with
  c_i = (-1)^i / (4^i i! (i+1)!) (Taylor coefficients of 2 J1(x)/x in x^2) and
  I_n = (-1)^n 4^n Gamma(n + 1/2)^2 / (pi r^{2n+1}) (the Mellin-regularised int k^{2n} J0(k r) dk),
  at r >= 100 (a + b), to 1e-22; it starts 1 + (a^2 + b^2) / (8 r^2);
- the lens integral against a brute-force double integral of the lens area (polar) at one L.

Inputs (radii, masses, G, separation) are doubles written as their shortest round-trip decimal
strings, and every number below is computed for exactly those doubles. The separations are
r = (a + b)(1 + gap) as doubles, from touching (gap 0) and gap 1e-9 to 1e8 radii sums. Outputs are
decimal strings with OUTPUT_DIGITS significant digits: V, dV/dr, and the shape factors
u = -V r / (G m_A m_B) and f = r^2 (dV/dr) / (G m_A m_B) (so the radial force on B is
F = -dV/dr = -G m_A m_B f / r^2).

Usage: python3 tests/reference/disk_pair.py   (needs mpmath; about 20 seconds)
"""

import json
import os

import mpmath
from mpmath import mp, mpf

WORKING_DIGITS = 40
OUTPUT_DIGITS = 25
ESTIMATED_RELATIVE_ACCURACY = "1e-25"
HANKEL_DIGITS = 25

# (label, a, b, m_A, m_B, G)
PAIRS = [
    ("equal radii", 1.0, 1.0, 1.0, 1.0, 1.0),
    ("radii 1 : 0.5", 1.0, 0.5, 3.0, 0.25, 1.0),
    ("radii 0.5 : 1 (swapped)", 0.5, 1.0, 0.25, 3.0, 1.0),
    ("radii 1 : 0.1", 1.0, 0.1, 1.0, 0.01, 1.0),
    ("radii 1 : 0.01", 1.0, 0.01, 1.0, 1e-4, 1.0),
    ("SI Earth-Moon sized", 6.371e6, 1.7374e6, 5.972e24, 7.342e22, 6.6743e-11),
]

# r = (a + b) (1 + gap).
GAPS = [0.0, 1e-9, 1e-7, 1e-5, 1e-3, 0.01, 0.03, 0.1, 0.25, 0.5, 1.0, 2.0, 4.0, 9.0,
        29.0, 99.0, 999.0, 9999.0, 99999.0, 999999.0, 1e8]
# Fewer separations for the extra pairs (the equal and 1 : 0.5 pairs get all of them).
SHORT_GAPS = [0.0, 1e-9, 1e-5, 0.01, 0.1, 1.0, 9.0, 99.0, 9999.0, 1e8]


def lens(L, a, b):
    """Area of the intersection of two disks of radii a, b with centres L apart."""
    if L >= a + b:
        return mpf(0)
    if L <= abs(a - b):
        return mp.pi * min(a, b) ** 2
    # Clamped: at 40 digits a node within 1e-40 of L = |a - b| can round the cosine past -1.
    t1 = a * a * mp.acos(max(-1, min(1, (L * L + a * a - b * b) / (2 * L * a))))
    t2 = b * b * mp.acos(max(-1, min(1, (L * L + b * b - a * a) / (2 * L * b))))
    t3 = mp.sqrt((-L + a + b) * (L + a - b) * (L - a + b) * (L + a + b)) / 2
    return t1 + t2 - t3


def breakpoints(a, b):
    return [mpf(0), abs(a - b), a + b] if a != b else [mpf(0), a + b]


def lens_integrals(r, a, b):
    """(int lens L 4K/(r+L) dL, its r-derivative, relative error estimates).

    The integrands are scaled by r and r^2 so that both integrals are O(1): mpmath's error
    estimate is absolute, with a floor near 10^-WORKING_DIGITS."""

    def energy(L):
        area = lens(L, a, b)
        if area == 0:
            return mpf(0)
        m = 1 - ((r - L) / (r + L)) ** 2  # 4rL/(r+L)^2, never above 1 by rounding
        if m == 1:
            # Only at contact, within ~1e-20 of the end point where lens ~ (a + b - L)^{3/2}:
            # the neglected contribution is below 1e-30.
            return mpf(0)
        return area * L * 4 * mp.ellipk(m) * r / (r + L)

    def derivative(L):
        area = lens(L, a, b)
        if area == 0:
            return mpf(0)
        m = 1 - ((r - L) / (r + L)) ** 2
        if m == 1:
            return mpf(0)  # as above
        k = mp.ellipk(m)
        e = mp.ellipe(m)
        return area * L * 4 * (-(e - (1 - m) * k) * r / (2 * (r - L)) - k * (r / (r + L)) ** 2)

    v, ev = mp.quad(energy, breakpoints(a, b), error=True)
    d, ed = mp.quad(derivative, breakpoints(a, b), error=True)
    return v / r, d / (r * r), abs(ev / v), abs(ed / d)


def reference(r, a, b, ma, mb, g):
    sa = ma / (mp.pi * a * a)
    sb = mb / (mp.pi * b * b)
    v, d, ev, ed = lens_integrals(r, a, b)
    return -g * sa * sb * v, -g * sa * sb * d, ev, ed


def hankel_energy(r, a, b, ma, mb, g):
    def integrand(k):
        if k == 0:
            return mpf(1)
        return (2 * mpmath.besselj(1, k * a) / (k * a)) * (2 * mpmath.besselj(1, k * b) / (k * b)) \
            * mpmath.besselj(0, k * r)

    return -g * ma * mb * mp.quadosc(integrand, [0, mp.inf], period=2 * mp.pi / r)


def series_energy(r, a, b, ma, mb, g, terms=12):
    c = [(-1) ** i / (mpf(4) ** i * mp.factorial(i) * mp.factorial(i + 1)) for i in range(terms)]
    total = mpf(0)
    for n in range(terms):
        i_n = (-1) ** n * mpf(4) ** n * mp.gamma(n + mpf(1) / 2) ** 2 / (mp.pi * r ** (2 * n + 1))
        inner = sum(c[i] * c[n - i] * a ** (2 * i) * b ** (2 * (n - i)) for i in range(n + 1))
        total += i_n * inner
    return -g * ma * mb * total


def check_lens_area():
    """lens(L) against the polar double integral of the intersection's indicator."""
    a, b, L = mpf(1), mpf("0.6"), mpf("0.9")

    def chord(x):
        # Points of disk A (centre 0) at radius x inside disk B (centre (L, 0)): angle where
        # |x e^{i phi} - L| <= b, i.e. cos phi >= (x^2 + L^2 - b^2) / (2 x L).
        if x == 0:
            return mpf(0)
        c = (x * x + L * L - b * b) / (2 * x * L)
        if c <= -1:
            return 2 * mp.pi * x
        if c >= 1:
            return mpf(0)
        return 2 * mp.acos(c) * x

    brute = mp.quad(chord, [0, L - b, a])
    exact = lens(L, a, b)
    assert abs(brute / exact - 1) < mpf(10) ** (-30), (brute, exact)


def decimal(x):
    return mpmath.nstr(x, OUTPUT_DIGITS, min_fixed=1, max_fixed=0)


def main():
    mp.dps = WORKING_DIGITS
    check_lens_area()
    cases = []
    worst_estimate = mpf(0)
    for label, a_f, b_f, ma_f, mb_f, g_f in PAIRS:
        gaps = GAPS if label in ("equal radii", "radii 1 : 0.5") else SHORT_GAPS
        a, b, ma, mb, g = (mpf(x) for x in (a_f, b_f, ma_f, mb_f, g_f))
        for gap in gaps:
            r_f = (a_f + b_f) * (1.0 + gap) if gap != 0.0 else a_f + b_f
            if gap == 1e-9:
                # The double nearest to (a + b)(1 + 1e-9), so the gap survives rounding.
                r_f = (a_f + b_f) + (a_f + b_f) * 1e-9
            r = mpf(r_f)
            assert r >= a + b, (label, gap)
            v, dv, ev, ed = reference(r, a, b, ma, mb, g)
            worst_estimate = max(worst_estimate, ev, ed)
            if max(ev, ed) > mpf(10) ** (-(OUTPUT_DIGITS + 2)):
                raise SystemExit(f"{label} gap {gap}: quadrature error estimate {ev}, {ed}")
            gmm = g * ma * mb
            u = -v * r / gmm
            f = dv * r * r / gmm
            if gap >= 99.0:
                s = series_energy(r, a, b, ma, mb, g)
                assert abs(s / v - 1) < mpf(10) ** -22, (label, gap, s, v)
            cases.append({
                "label": f"{label}: r = (R_A + R_B)(1 + {gap:g})",
                "radius_a": repr(a_f),
                "radius_b": repr(b_f),
                "mass_a": repr(ma_f),
                "mass_b": repr(mb_f),
                "g": repr(g_f),
                "separation": repr(r_f),
                "potential_energy": decimal(v),
                "dv_dr": decimal(dv),
                "energy_shape_factor": decimal(u),
                "force_shape_factor": decimal(f),
            })
            print(f"{cases[-1]['label']:55s} u = {mpmath.nstr(u, 20):>24s}  "
                  f"f = {mpmath.nstr(f, 20):>24s}")

    # The Hankel route at a few separations (oscillatory and slow: 25 digits, 1 to 4 s each).
    for a_f, b_f, r_f in [(1.0, 1.0, 3.0), (1.0, 0.1, 4.4), (1.0, 0.5, 5.0)]:
        a, b, r = mpf(a_f), mpf(b_f), mpf(r_f)
        v, _, _, _ = reference(r, a, b, mpf(1), mpf(1), mpf(1))
        with mp.workdps(HANKEL_DIGITS):
            h = hankel_energy(r, a, b, mpf(1), mpf(1), mpf(1))
            assert abs(h / v - 1) < mpf(10) ** -20, (a_f, b_f, r_f, h, v)

    out = {
        "generator": "tests/reference/disk_pair.py",
        "mpmath_version": mpmath.__version__,
        "working_digits": WORKING_DIGITS,
        "output_digits": OUTPUT_DIGITS,
        "estimated_relative_accuracy": ESTIMATED_RELATIVE_ACCURACY,
        "worst_quadrature_error_estimate": mpmath.nstr(worst_estimate, 3),
        "method": "lens-area convolution V = -G s_A s_B int lens(L) L 4K(m)/(r+L) dL and its "
                  "r-derivative, tanh-sinh quadrature; cross-checked against the Hankel "
                  "representation and the far-field series (see the script's docstring)",
        "conventions": "potential_energy V < 0; dv_dr = dV/dr; radial force on B along A->B is "
                       "-dV/dr; energy_shape_factor u = -V r/(G m_A m_B); force_shape_factor "
                       "f = r^2 (dV/dr)/(G m_A m_B); inputs are round-trip decimal strings of doubles",
        "cases": cases,
    }
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "disk_pair.json")
    with open(path, "w") as fh:
        json.dump(out, fh, indent=1)
        fh.write("\n")
    print(f"wrote {len(cases)} cases to {path}; worst quadrature estimate "
          f"{mpmath.nstr(worst_estimate, 3)}")


if __name__ == "__main__":
    main()
