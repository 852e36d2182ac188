//! Nested rules: exactness, nesting, and the doubling cubature's estimate against true errors.

use std::f64::consts::{PI, TAU};
use std::ops::Range;
use surfgrav_quadrature::{
    geometric_estimate, rate_estimate, Interval, NestedCubature, NestedFejer, NestedLevels,
    NestedTensorRule, NestedTrapezoid, QuadratureError,
};

/// Fejér's second rule with n subdivisions integrates x^k exactly for k ≤ n − 2 (n − 1 for
/// even n); checked against 1e-14 of ∫|x^k| (the weights' rounding, `CONVERGED_RULE_REL`).
#[test]
fn fejer_is_exact_for_polynomials_at_every_level() {
    let rule = NestedFejer::new(3, 5, Interval::new(-1.0, 1.0).unwrap()).unwrap();
    for level in 0..=5 {
        let n = 3usize << level;
        let w = rule.weights(level);
        let x = &rule.nodes()[..rule.count(level)];
        assert_eq!(w.len(), n - 1);
        let degree = if n.is_multiple_of(2) { n - 1 } else { n - 2 };
        for k in 0..=degree.min(60) {
            let q: f64 = x.iter().zip(w).map(|(x, w)| w * x.powi(k as i32)).sum();
            let exact = if k % 2 == 1 {
                0.0
            } else {
                2.0 / (k as f64 + 1.0)
            };
            assert!(
                (q - exact).abs() < 1e-14,
                "level {level} x^{k}: {q} vs {exact}"
            );
        }
    }
}

#[test]
fn fejer_levels_are_nested_and_inside_the_interval() {
    let rule = NestedFejer::new(5, 4, Interval::new(0.0, 2.5).unwrap()).unwrap();
    for level in 0..4 {
        let n = 5usize << level;
        let direct: Vec<f64> = (1..n)
            .map(|k| 1.25 + 1.25 * (PI * k as f64 / n as f64).cos())
            .collect();
        let mut stored = rule.nodes()[..rule.count(level)].to_vec();
        stored.sort_by(f64::total_cmp);
        let mut direct_sorted = direct.clone();
        direct_sorted.sort_by(f64::total_cmp);
        for (a, b) in stored.iter().zip(&direct_sorted) {
            assert!((a - b).abs() <= 4.0 * f64::EPSILON * 2.5);
        }
        assert!(stored.iter().all(|&x| x > 0.0 && x < 2.5));
        let sum: f64 = rule.weights(level).iter().sum();
        assert!((sum - 2.5).abs() < 1e-14);
    }
}

/// The trapezoid levels integrate e^{ikφ} exactly for |k| < N; the half rule gives half the
/// full integral of an even function (here cos kφ).
#[test]
fn trapezoid_levels_are_exact_below_their_count() {
    for half in [false, true] {
        let rule = NestedTrapezoid::new(4, 4, 0.0, TAU, half).unwrap();
        for level in 0..=4 {
            let n = 4usize << level;
            let count = rule.count(level);
            for k in 0..n {
                let q: f64 = rule.nodes()[..count]
                    .iter()
                    .zip(&rule.factors()[..count])
                    .map(|(&phi, &f)| f * (k as f64 * phi).cos())
                    .sum::<f64>()
                    * rule.step(level);
                let full = if k == 0 { TAU } else { 0.0 };
                let exact = if half { 0.5 * full } else { full };
                assert!(
                    (q - exact).abs() < 1e-13,
                    "half {half} level {level} k {k}: {q}"
                );
            }
        }
    }
}

#[test]
fn bad_nested_rules_are_errors() {
    assert!(matches!(
        NestedTrapezoid::new(3, 2, 0.0, TAU, true),
        Err(QuadratureError::InvalidNesting { .. })
    ));
    assert!(matches!(
        NestedTrapezoid::new(0, 2, 0.0, TAU, false),
        Err(QuadratureError::ZeroOrder)
    ));
    assert!(NestedFejer::new(1, 2, Interval::new(0.0, 1.0).unwrap()).is_err());
    assert!(NestedFejer::new(4, 11, Interval::new(0.0, 1.0).unwrap()).is_err());
    assert_eq!(rate_estimate(1e-3, 1e-6), 1e-9);
    assert_eq!(rate_estimate(0.0, 0.0), 0.0);
    assert_eq!(rate_estimate(0.0, 1e-9), f64::INFINITY);
    assert!((geometric_estimate(1e-2, 1e-6, 2.0) / 1e-14 - 1.0).abs() < 1e-12);
    assert_eq!(
        geometric_estimate(1e-3, 1e-6, 1.0),
        rate_estimate(1e-3, 1e-6)
    );
    assert!((geometric_estimate(1e-2, 1e-6, 1.5) / 1e-12 - 1.0).abs() < 1e-12);
    // A change that grows is not extrapolated below the matched estimate.
    assert_eq!(
        geometric_estimate(1e-6, 1e-3, 2.0),
        rate_estimate(1e-6, 1e-3)
    );
    assert_eq!(geometric_estimate(0.0, 0.0, 1.5), 0.0);
    assert_eq!(geometric_estimate(0.0, 1e-9, 1.5), f64::INFINITY);
}

/// The far-field case of the geometric estimate: the integrand of
/// [`cubature_estimate_bounds_the_true_error`] with ε ≥ 7 (analytic in a strip of half-width
/// acosh(1 + ε) ≥ 2 in φ, geometric convergence from the coarsest levels), integrated from
/// the coarsest start (base 2 in both directions) with [`geometric_estimate`] at exponent
/// 1.5, as the interaction engine does far away: the estimate bounds the true error (or the
/// error is at rounding, 10⁻¹⁵) and the tolerance is met, with fewer evaluations than the
/// matched estimate δ₂²/δ₁ needs.
#[test]
fn geometric_estimate_bounds_the_true_error_far_away() {
    let mut worst: f64 = 0.0;
    for eps in [7.0f64, 10.0, 29.0, 1e3, 1e6] {
        let exact = TAU * (1.0 / (1.0 + eps)).asin();
        for tolerance in [1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
            let rule = NestedTensorRule {
                periodic: NestedTrapezoid::new(2, 10, 0.0, TAU, false).unwrap(),
                across: NestedFejer::new(2, 8, Interval::new(0.0, 1.0).unwrap()).unwrap(),
            };
            let start = NestedLevels {
                periodic: 2,
                across: 2,
            };
            let line = |k: usize, range: Range<usize>, out: &mut [f64; 1]| {
                let x = rule.across.nodes()[k];
                for m in range.clone() {
                    let phi = rule.periodic.nodes()[m];
                    out[0] += rule.periodic.factors()[m] / (1.0 + eps - x * phi.cos());
                }
                range.len()
            };
            let norm = |a: &[f64; 1], b: &[f64; 1]| (a[0] - b[0]).abs() / a[0].abs();
            let mut cubature = NestedCubature::<1>::new();
            let r = cubature
                .integrate_with(&rule, start, tolerance, 1_000_000, line, norm, |d1, d2| {
                    geometric_estimate(d1, d2, 1.5)
                })
                .unwrap();
            let matched = NestedCubature::<1>::new()
                .integrate(&rule, start, tolerance, 1_000_000, line, norm)
                .unwrap();
            assert!(r.converged, "eps {eps} tol {tolerance}");
            assert!(r.evaluations <= matched.evaluations);
            let err = (r.value[0] - exact).abs() / exact;
            assert!(r.error_estimate <= tolerance);
            assert!(
                err <= r.error_estimate.max(1e-15),
                "eps {eps} tol {tolerance}: error {err:e} > estimate {:e}",
                r.error_estimate
            );
            worst = worst.max(err / r.error_estimate.max(1e-15));
        }
    }
    println!("worst true error / estimate: {worst:.3}");
}

/// ∫₀^{2π}∫₀^1 1/(1 + ε − x cos φ) dx dφ = 2π ∫₀^1 dx / √((1+ε)² − x²) = 2π asin(1/(1+ε)):
/// near-singular at (φ, x) = (0, 1) for small ε. The estimate bounds the true error for every
/// ε and tolerance, and the tolerance is met.
#[test]
fn cubature_estimate_bounds_the_true_error() {
    let mut worst: f64 = 0.0;
    for eps in [1.0f64, 0.1, 1e-2, 1e-3] {
        let exact = TAU * (1.0 / (1.0 + eps)).asin();
        for tolerance in [1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
            for base in [4usize, 6, 10] {
                let rule = NestedTensorRule {
                    periodic: NestedTrapezoid::new(base, 10, 0.0, TAU, false).unwrap(),
                    across: NestedFejer::new(3, 8, Interval::new(0.0, 1.0).unwrap()).unwrap(),
                };
                let mut cubature = NestedCubature::<1>::new();
                let r = cubature
                    .integrate(
                        &rule,
                        NestedLevels {
                            periodic: 2,
                            across: 2,
                        },
                        tolerance,
                        10_000_000,
                        |k, range, out| {
                            let x = rule.across.nodes()[k];
                            for m in range.clone() {
                                let phi = rule.periodic.nodes()[m];
                                out[0] += rule.periodic.factors()[m] / (1.0 + eps - x * phi.cos());
                            }
                            range.len()
                        },
                        |a, b| (a[0] - b[0]).abs() / a[0].abs(),
                    )
                    .unwrap();
                assert!(r.converged, "eps {eps} tol {tolerance}");
                let err = (r.value[0] - exact).abs() / exact;
                assert!(r.error_estimate <= tolerance);
                assert!(
                    err <= r.error_estimate.max(1e-15),
                    "eps {eps} tol {tolerance} base {base}: error {err:e} > estimate {:e}",
                    r.error_estimate
                );
                worst = worst.max(err / r.error_estimate.max(1e-15));
            }
        }
    }
    println!("worst true error / estimate: {worst:.3}");
}

/// `integrate_converted` asks for nested line sums (`start..ends[s]` into `outs[s]`) and a
/// conversion: a caller that sums each line in one pass and converts by scaling gets the same
/// value, estimate and count as `integrate_with` on the one-range closure, and the converted
/// value is the conversion of the value.
#[test]
fn converted_integration_with_nested_line_sums_matches_the_plain_one() {
    let eps = 0.05;
    let rule = NestedTensorRule {
        periodic: NestedTrapezoid::new(6, 8, 0.0, TAU, false).unwrap(),
        across: NestedFejer::new(3, 8, Interval::new(0.0, 1.0).unwrap()).unwrap(),
    };
    let term = |m: usize, k: usize| {
        let (x, phi) = (rule.across.nodes()[k], rule.periodic.nodes()[m]);
        rule.periodic.factors()[m] / (1.0 + eps - x * phi.cos())
    };
    let start = NestedLevels {
        periodic: 2,
        across: 2,
    };
    let norm = |a: &[f64; 1], b: &[f64; 1]| (a[0] - b[0]).abs() / a[0].abs();
    let plain = NestedCubature::<1>::new()
        .integrate_with(
            &rule,
            start,
            1e-10,
            1_000_000,
            |k, range: Range<usize>, out: &mut [f64; 1]| {
                for m in range.clone() {
                    out[0] += term(m, k);
                }
                range.len()
            },
            norm,
            rate_estimate,
        )
        .unwrap();
    let mut calls = 0;
    let (converted, scaled) = NestedCubature::<1>::new()
        .integrate_converted(
            &rule,
            start,
            1e-10,
            1_000_000,
            |k, start, ends: &[usize], outs: &mut [[f64; 1]]| {
                calls += 1;
                let mut running = 0.0;
                let mut from = start;
                for (&end, out) in ends.iter().zip(outs) {
                    for m in from..end {
                        running += term(m, k);
                    }
                    out[0] += running;
                    from = end;
                }
                ends.last().map_or(0, |&end| end - start)
            },
            |q: &[f64; 1]| 2.0 * q[0],
            |a: &[f64; 1], b: &[f64; 1], ca: &f64, cb: &f64| {
                assert_eq!((*ca, *cb), (2.0 * a[0], 2.0 * b[0]));
                norm(a, b)
            },
            rate_estimate,
        )
        .unwrap();
    assert!(plain.converged && converted.converged);
    assert_eq!(converted.value, plain.value);
    assert_eq!(converted.error_estimate, plain.error_estimate);
    assert_eq!(converted.evaluations, plain.evaluations);
    assert_eq!(scaled, 2.0 * plain.value[0]);
    // One call per new line, and one per line and doubling of the periodic level.
    let (p, a) = (plain.levels.periodic, plain.levels.across);
    assert!(calls >= rule.across.count(a) && calls <= rule.across.count(a) * (1 + p));
}
