#!/usr/bin/env python3
"""Reference Gauss-Legendre and Gauss-Kronrod rules for surfgrav-quadrature's tests.

Writes tests/reference/gauss_legendre.json (next to this script):

- ``gauss_legendre``: for each order n, the non-negative nodes of the n-point Gauss-Legendre rule
  on [-1, 1] in increasing order and their weights (the rule is symmetric: node -x has the weight
  of x). Nodes are the roots of the Legendre polynomial P_n, found by Newton's method on the
  three-term recurrence (k+1) P_{k+1} = (2k+1) x P_k - k P_{k-1} in WORKING_DIGITS-digit
  arithmetic; the weights are w = 2 / ((1 - x^2) P_n'(x)^2) with
  P_n'(x) = n (x P_n - P_{n-1}) / (x^2 - 1).
- ``kronrod_15``: the 15-point Kronrod extension of the 7-point Gauss rule. The 8 new nodes are the
  roots of the Stieltjes polynomial E_8 (monic, even, orthogonal to x^0..x^7 with the sign-changing
  weight P_7(x) on [-1, 1]); the 15 weights make the rule exact for x^0..x^14 (and, by symmetry,
  for every odd power up to x^23); the 7-point Gauss weights are listed for the embedded rule.

Every value is a decimal string of OUTPUT_DIGITS significant digits, computed with WORKING_DIGITS
digits; the script checks its own results (residuals, sum of weights, exactness) before writing.

Usage: python3 tests/reference/gauss_legendre.py   (needs mpmath; about a minute)
"""

import json
import math
import os
from fractions import Fraction

import mpmath
from mpmath import mp, mpf

WORKING_DIGITS = 50
OUTPUT_DIGITS = 25
ORDERS = [1, 2, 3, 4, 5, 7, 8, 15, 20, 33, 64, 100, 101, 255, 500, 999, 1000]


def legendre_pair(n, x):
    """Returns (P_n(x), P_{n-1}(x)) by the three-term recurrence."""
    previous, current = mpf(1), x
    if n == 0:
        return previous, mpf(0)
    for k in range(1, n):
        previous, current = current, ((2 * k + 1) * x * current - k * previous) / (k + 1)
    return current, previous


def gauss_legendre_half(n):
    """Non-negative nodes (increasing) and weights of the n-point rule on [-1, 1]."""
    nodes, weights = [], []
    tolerance = mpf(10) ** (-(WORKING_DIGITS - 5))
    for k in range(1, n // 2 + 1):
        # Largest roots first: theta_k ~ (k - 1/4) pi / (n + 1/2) plus the Tricomi correction.
        psi = (k - 0.25) * math.pi / (n + 0.5)
        theta = psi + 1.0 / (8.0 * (n + 0.5) ** 2 * math.tan(psi))
        x = mpf(math.cos(theta))
        for _ in range(100):
            p, q = legendre_pair(n, x)
            derivative = n * (x * p - q) / (x * x - 1)
            step = p / derivative
            x -= step
            if abs(step) < tolerance:
                break
        else:
            raise RuntimeError(f"Newton did not converge for n={n}, k={k}")
        p, q = legendre_pair(n, x)
        derivative = n * (x * p - q) / (x * x - 1)
        nodes.append(x)
        weights.append(2 / ((1 - x * x) * derivative**2))
    if n % 2 == 1:
        x = mpf(0)
        p, q = legendre_pair(n, x)
        derivative = n * (x * p - q) / (x * x - 1)
        nodes.append(x)
        weights.append(2 / derivative**2)
    # Increasing order of the non-negative nodes.
    nodes.reverse()
    weights.reverse()
    check_rule(n, nodes, weights)
    return nodes, weights


def check_rule(n, nodes, weights):
    """Distinct roots with tiny residuals, weights summing to 2."""
    for x in nodes:
        p, _ = legendre_pair(n, x)
        assert abs(p) < mpf(10) ** (-(WORKING_DIGITS - 8)), (n, x, p)
    for a, b in zip(nodes, nodes[1:]):
        assert b - a > mpf(10) ** -10, (n, a, b)
    total = sum(2 * w for w, x in zip(weights, nodes) if x != 0)
    total += sum(w for w, x in zip(weights, nodes) if x == 0)
    assert abs(total - 2) < mpf(10) ** (-(WORKING_DIGITS - 8)), (n, total)
    assert len(nodes) == (n + 1) // 2


def legendre_coefficients(n):
    """Exact monomial coefficients of P_n (index = power)."""
    previous, current = [Fraction(1)], [Fraction(0), Fraction(1)]
    if n == 0:
        return previous
    for k in range(1, n):
        shifted = [Fraction(0)] + current
        following = [Fraction(0)] * (k + 2)
        for i, c in enumerate(shifted):
            following[i] += Fraction(2 * k + 1, k + 1) * c
        for i, c in enumerate(previous):
            following[i] -= Fraction(k, k + 1) * c
        previous, current = current, following
    return current


def monomial_integral(power):
    """Integral of x^power over [-1, 1]."""
    return Fraction(0) if power % 2 else Fraction(2, power + 1)


def kronrod_15():
    gauss_order = 7
    p7 = legendre_coefficients(gauss_order)

    def moment(power):  # integral of P_7(x) x^power over [-1, 1]
        return sum(c * monomial_integral(i + power) for i, c in enumerate(p7))

    # E_8(x) = x^8 + c6 x^6 + c4 x^4 + c2 x^2 + c0, orthogonal to x^1, x^3, x^5, x^7 under P_7.
    unknown_powers = [0, 2, 4, 6]
    rows = [1, 3, 5, 7]
    matrix = mpmath.matrix([[mpf(moment(r + p).numerator) / moment(r + p).denominator
                             for p in unknown_powers] for r in rows])
    rhs = mpmath.matrix([-mpf(moment(r + 8).numerator) / moment(r + 8).denominator for r in rows])
    c = mpmath.lu_solve(matrix, rhs)
    # Roots in y = x^2 of y^4 + c6 y^3 + c4 y^2 + c2 y + c0.
    y_roots = mpmath.polyroots([1, c[3], c[2], c[1], c[0]], maxsteps=200, extraprec=200)
    y_roots = sorted(mpmath.re(y) for y in y_roots)
    for y in y_roots:
        assert 0 < y < 1
    new_nodes = [mpmath.sqrt(y) for y in y_roots]
    gauss_nodes, gauss_weights = gauss_legendre_half(gauss_order)
    positive_nodes = sorted(gauss_nodes + new_nodes)  # 0 and 7 positive nodes
    assert positive_nodes[0] == 0 and len(positive_nodes) == 8
    # Weights of the symmetric rule: exact for x^0, x^2, ..., x^14 (8 unknowns).
    matrix = mpmath.matrix([[(mpf(1) if x == 0 else mpf(2)) * x ** (2 * j) if not (x == 0 and j > 0)
                             else mpf(0) for x in positive_nodes] for j in range(8)])
    rhs = mpmath.matrix([mpf(2) / (2 * j + 1) for j in range(8)])
    weights = list(mpmath.lu_solve(matrix, rhs))
    for w in weights:
        assert w > 0
    # Exact for x^16 ... x^22 as well (the defining property of the Kronrod extension).
    for j in range(8, 12):
        value = sum((1 if x == 0 else 2) * w * x ** (2 * j) for x, w in zip(positive_nodes, weights))
        assert abs(value - mpf(2) / (2 * j + 1)) < mpf(10) ** (-(WORKING_DIGITS - 10)), j
    # And not for x^24.
    value = sum((1 if x == 0 else 2) * w * x**24 for x, w in zip(positive_nodes, weights))
    assert abs(value - mpf(2) / 25) > mpf(10) ** -10
    return {
        "gauss_order": gauss_order,
        "kronrod_nodes": [fmt(x) for x in positive_nodes],
        "kronrod_weights": [fmt(w) for w in weights],
        "gauss_nodes": [fmt(x) for x in gauss_nodes],
        "gauss_weights": [fmt(w) for w in gauss_weights],
    }


def fmt(value):
    if value == 0:
        return "0"
    return mpmath.nstr(value, OUTPUT_DIGITS, strip_zeros=False, min_fixed=-5, max_fixed=1)


def main():
    mp.dps = WORKING_DIGITS
    rules = []
    for n in ORDERS:
        nodes, weights = gauss_legendre_half(n)
        rules.append({"order": n, "nodes": [fmt(x) for x in nodes], "weights": [fmt(w) for w in weights]})
    document = {
        "generator": "tests/reference/gauss_legendre.py",
        "mpmath_version": mpmath.__version__,
        "working_digits": WORKING_DIGITS,
        "output_digits": OUTPUT_DIGITS,
        "interval": [-1, 1],
        "layout": "non-negative nodes in increasing order; node -x has the weight of node x",
        "gauss_legendre": rules,
        "kronrod_15": kronrod_15(),
    }
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "gauss_legendre.json")
    with open(path, "w") as out:
        json.dump(document, out, indent=1)
        out.write("\n")


if __name__ == "__main__":
    main()
