//! Work–precision measurement of the engine's rules: what a benchmark command needs to run one
//! interaction with a chosen rule and parametrisation and report its value, evaluation count,
//! error estimate, true error against a reference and time per call.
//!
//! ```
//! use surfgrav_potentials::{Pose, Spheroid, Vec3};
//! use surfgrav_surfaces::interaction::work_precision::{measure, rule_catalogue, Reference};
//! use surfgrav_surfaces::interaction::Body;
//!
//! let body = || Body::spheroid(Spheroid::new(1.0, 0.25, 1.0).unwrap()).unwrap();
//! let (a, b) = (body(), body());
//! let pose_b = Pose::new(Vec3::new(3.0, 0.0, 0.0), Vec3::zeros());
//! // The founding paper's pair at separation 3, reference from tests/reference/interactions.json.
//! let reference = Reference {
//!     force_on_a: Vec3::new(1.1920025987549594249e-1, 0.0, 0.0),
//!     potential_energy: -3.4092245077761296201e-1,
//! };
//! for rule in rule_catalogue(&[1e-12]).iter().filter(|r| r.label.starts_with("nested")) {
//!     let m = measure(&a, &Pose::identity(), &b, &pose_b, rule.options, Some(&reference), 0.001)?;
//!     assert!(m.error.unwrap() < 1e-12 && m.error_estimate <= 1e-12);
//! }
//! # Ok::<(), surfgrav_surfaces::interaction::InteractionError>(())
//! ```

use super::{
    Body, Interaction, InteractionEngine, InteractionError, InteractionOptions, MethodChoice,
    Parametrisation,
};
use crate::{Real, Vec3};
use std::hint::black_box;
use std::time::Instant;
use surfgrav_potentials::Pose;

/// A rule of the engine to measure: a label for tables and the options that select it.
#[derive(Debug, Clone, PartialEq)]
pub struct RuleChoice {
    /// For example `"AH table t=10"`, `"ladder AH 1e-12"`, `"nested 1e-12"`.
    pub label: String,
    /// The engine options that select the rule.
    pub options: InteractionOptions,
}

/// Independent values to measure errors against (world frame, force on A).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reference {
    /// Force on A.
    pub force_on_a: Vec3,
    /// Mutual potential energy.
    pub potential_energy: Real,
}

/// One measurement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measurement {
    /// The engine's result (its best one when the tolerance was not met).
    pub interaction: Interaction,
    /// Whether the requested tolerance was met (always true for a single table).
    pub certified: bool,
    /// Field evaluations per call.
    pub evaluations: usize,
    /// The engine's estimate ($+\infty$ for a single, uncertified table).
    pub error_estimate: Real,
    /// $\max(|\delta\mathbf F|/|\mathbf F|, |\delta V|/|V|)$ against the reference, if given.
    pub error: Option<Real>,
    /// Best time per call over five batches, in seconds (warm caches; one thread).
    pub seconds: Real,
}

/// The rules a work–precision table compares: single tables of the fixed ladder in both
/// parametrisations (azimuth–height `AH`, polar-angle `PA`; transverse counts 2 to 24), the
/// certified ladder, the nested doubling rule and the G7K15 adaptive cubature at each
/// tolerance.
pub fn rule_catalogue(tolerances: &[Real]) -> Vec<RuleChoice> {
    let mut rules = vec![];
    for (name, parametrisation) in [
        ("AH", Parametrisation::AzimuthHeight),
        ("PA", Parametrisation::PolarAzimuth),
    ] {
        for t in [2u16, 4, 6, 8, 10, 12, 14, 17, 20, 24] {
            rules.push(RuleChoice {
                label: format!("{name} table t={t}"),
                options: InteractionOptions {
                    method: MethodChoice::FixedLevel(t),
                    parametrisation,
                    ..InteractionOptions::default()
                },
            });
        }
    }
    for &tolerance in tolerances {
        for (label, method, parametrisation) in [
            (
                "ladder AH",
                MethodChoice::FixedRules,
                Parametrisation::AzimuthHeight,
            ),
            (
                "ladder PA",
                MethodChoice::FixedRules,
                Parametrisation::PolarAzimuth,
            ),
            (
                "nested",
                MethodChoice::Nested,
                Parametrisation::AzimuthHeight,
            ),
            (
                "adaptive G7K15",
                MethodChoice::Adaptive,
                Parametrisation::AzimuthHeight,
            ),
        ] {
            rules.push(RuleChoice {
                label: format!("{label} {tolerance:.0e}"),
                options: InteractionOptions {
                    relative_tolerance: tolerance,
                    method,
                    parametrisation,
                    ..InteractionOptions::default()
                },
            });
        }
    }
    rules
}

/// $\max(|\delta\mathbf F|/|\mathbf F|, |\delta V|/|V|)$ of `result` against `reference`.
pub fn relative_error(result: &Interaction, reference: &Reference) -> Real {
    let force = (result.force_on_a - reference.force_on_a).norm()
        / reference.force_on_a.norm().max(Real::MIN_POSITIVE);
    let energy =
        ((result.potential_energy - reference.potential_energy) / reference.potential_energy).abs();
    force.max(energy)
}

/// Runs A (at `pose_a`) and B (at `pose_b`) with `options`, measures the error against
/// `reference` and the best time per call over five batches of at least `batch_seconds`.
///
/// # Errors
/// The engine's errors, except a missed tolerance, which is reported as `certified: false`
/// with the best result.
pub fn measure(
    a: &Body,
    pose_a: &Pose,
    b: &Body,
    pose_b: &Pose,
    options: InteractionOptions,
    reference: Option<&Reference>,
    batch_seconds: Real,
) -> Result<Measurement, InteractionError> {
    let mut engine = InteractionEngine::new(options)?;
    let call = |engine: &mut InteractionEngine| match engine.interact(a, pose_a, b, pose_b) {
        Ok(r) => Ok((r, true)),
        Err(InteractionError::ToleranceNotMet { best, .. }) => Ok((*best, false)),
        Err(e) => Err(e),
    };
    let (interaction, certified) = call(&mut engine)?;
    let mut reps = 1usize;
    loop {
        let start = Instant::now();
        for _ in 0..reps {
            black_box(call(&mut engine)?);
        }
        if start.elapsed().as_secs_f64() >= batch_seconds || reps >= 1 << 24 {
            break;
        }
        reps *= 2;
    }
    let mut seconds = Real::INFINITY;
    for _ in 0..5 {
        let start = Instant::now();
        for _ in 0..reps {
            black_box(call(&mut engine)?);
        }
        seconds = seconds.min(start.elapsed().as_secs_f64() / reps as Real);
    }
    Ok(Measurement {
        interaction,
        certified,
        evaluations: interaction.evaluations,
        error_estimate: interaction.error_estimate,
        error: reference.map(|r| relative_error(&interaction, r)),
        seconds,
    })
}

/// The cheapest single fixed table (no estimate; either parametrisation, transverse count 1 to
/// `max_transverse`) whose error against `reference` is at most `target`: the best fixed rule
/// "at equal accuracy" to compare a certified rule with. `None` if no table reaches it.
///
/// # Errors
/// The engine's errors.
#[allow(clippy::too_many_arguments)]
pub fn cheapest_fixed_table(
    a: &Body,
    pose_a: &Pose,
    b: &Body,
    pose_b: &Pose,
    reference: &Reference,
    target: Real,
    max_transverse: u16,
    batch_seconds: Real,
) -> Result<Option<(String, Measurement)>, InteractionError> {
    let mut best: Option<(String, Measurement)> = None;
    for (name, parametrisation) in [
        ("AH", Parametrisation::AzimuthHeight),
        ("PA", Parametrisation::PolarAzimuth),
    ] {
        for t in 1..=max_transverse {
            let options = InteractionOptions {
                method: MethodChoice::FixedLevel(t),
                parametrisation,
                ..InteractionOptions::default()
            };
            let mut engine = InteractionEngine::new(options)?;
            let r = engine.interact(a, pose_a, b, pose_b)?;
            if relative_error(&r, reference) <= target {
                let m = measure(
                    a,
                    pose_a,
                    b,
                    pose_b,
                    options,
                    Some(reference),
                    batch_seconds,
                )?;
                if best.as_ref().is_none_or(|(_, b)| m.seconds < b.seconds) {
                    best = Some((format!("{name} table t={t}"), m));
                }
                break;
            }
        }
    }
    Ok(best)
}
