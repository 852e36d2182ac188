//! Work–precision of the interaction engine over seeded random poses (issue 12): pairs of
//! spheroids, triaxial ellipsoids and disks (six kinds of pair) at random attitudes and
//! directions, at gaps of 0.05, 0.2, 1 and 5 times the smaller body's bounding radius
//! ([`work_precision::pose_set`]), certified to 10⁻¹². For each gap it prints the median and
//! worst time per interaction (warm, one core, best of five batches), the evaluations, and the
//! true error against an independent reference (the ladder at 10⁻¹³ over the other body's
//! surface, polar-angle form: [`work_precision::independent_reference`]); a violation is a
//! true error above the engine's estimate plus the reference's. It then times 1999 KW4 as two
//! ellipsoids, aligned and in random attitudes, and the founding paper's pair.
//!
//! `cargo run --release -p surfgrav-interaction --example pose_benchmark [-- PER_PAIR [SEED]]`
//!
//! Environment: `POSE_BENCHMARK_VERBOSE` prints every case; `POSE_BENCHMARK_ONLY=TEXT` keeps the
//! cases whose label contains TEXT; `POSE_BENCHMARK_KW4=N` times KW4 in N random attitudes
//! (default 20); `POSE_BENCHMARK_PARAMETRISATION=aimed|azimuth-height` forces a rule;
//! `POSE_BENCHMARK_SURFACE=a|b` the surface integrated over.

use surfgrav_interaction::work_precision::{
    independent_reference, interaction_error, measure, pose_set, SplitMix64,
};
use surfgrav_interaction::{Body, InteractionOptions, Parametrisation, SurfaceChoice};
use surfgrav_potentials::{Ellipsoid, Pose, Spheroid, Vec3};

const GAPS: [f64; 4] = [0.05, 0.2, 1.0, 5.0];

fn quantile(sorted: &[f64], q: f64) -> f64 {
    let i = ((sorted.len() - 1) as f64 * q).round() as usize;
    sorted[i]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let per_pair: usize = args.get(1).map_or(Ok(4), |s| s.parse())?;
    let seed: u64 = args.get(2).map_or(Ok(12), |s| s.parse())?;
    let verbose = std::env::var("POSE_BENCHMARK_VERBOSE").is_ok();
    let mut options = InteractionOptions::default();
    match std::env::var("POSE_BENCHMARK_PARAMETRISATION").as_deref() {
        Ok("aimed") => options.parametrisation = Parametrisation::Aimed,
        Ok("azimuth-height") => options.parametrisation = Parametrisation::AzimuthHeight,
        _ => {}
    }
    match std::env::var("POSE_BENCHMARK_SURFACE").as_deref() {
        Ok("a") => options.surface = SurfaceChoice::A,
        Ok("b") => options.surface = SurfaceChoice::B,
        _ => {}
    }
    let mut cases = pose_set(seed, &GAPS, per_pair);
    if let Ok(only) = std::env::var("POSE_BENCHMARK_ONLY") {
        cases.retain(|c| c.label.contains(&only));
    }
    println!("# Random poses, seed {seed}, {per_pair} per pair of kinds, certified 1e-12\n");
    println!("| gap | cases | median µs | worst µs | median evals | worst evals | worst true error | worst error/estimate | violations | not certified |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let mut all_times = vec![];
    for &gap in GAPS.iter().filter(|_| per_pair > 0) {
        let (mut times, mut evals) = (vec![], vec![]);
        let (mut worst_error, mut worst_ratio) = (0.0f64, 0.0f64);
        let (mut violations, mut uncertified) = (0, 0);
        let mut worst_label = String::new();
        for case in cases.iter().filter(|c| c.gap == gap) {
            let m = measure(
                &case.a,
                &case.pose_a,
                &case.b,
                &case.pose_b,
                options,
                None,
                0.002,
            )?;
            let (reference, certified) =
                independent_reference(&case.a, &case.pose_a, &case.b, &case.pose_b, 1e-13)?;
            let error = interaction_error(&m.interaction, &reference);
            let allowed = m.error_estimate + reference.error_estimate;
            if error > allowed || !certified {
                violations += usize::from(error > allowed);
            }
            uncertified += usize::from(!m.certified);
            worst_error = worst_error.max(error);
            worst_ratio = worst_ratio.max(error / m.error_estimate);
            let micros = m.seconds * 1e6;
            if times.iter().all(|&t| micros > t) {
                worst_label = case.label.clone();
            }
            if verbose {
                println!(
                    "{:32} {:>9.1} µs {:>7} evals  est {:.1e} err {:.1e} ref {:.1e}{} {:?}",
                    case.label,
                    micros,
                    m.evaluations,
                    m.error_estimate,
                    error,
                    reference.error_estimate,
                    if certified { "" } else { " (ref uncertified)" },
                    m.interaction.method,
                );
            }
            times.push(micros);
            evals.push(m.evaluations as f64);
        }
        if times.is_empty() {
            continue;
        }
        all_times.extend_from_slice(&times);
        times.sort_by(f64::total_cmp);
        evals.sort_by(f64::total_cmp);
        println!(
            "| {gap} | {} | {:.1} | {:.1} ({worst_label}) | {:.0} | {:.0} | {:.1e} | {:.2} | {violations} | {uncertified} |",
            times.len(),
            quantile(&times, 0.5),
            times[times.len() - 1],
            quantile(&evals, 0.5),
            evals[evals.len() - 1],
            worst_error,
            worst_ratio,
        );
    }
    all_times.sort_by(f64::total_cmp);
    if let Some(&worst) = all_times.last() {
        println!(
            "\nAll gaps: median {:.1} µs, worst {:.1} µs over {} cases.\n",
            quantile(&all_times, 0.5),
            worst,
            all_times.len()
        );
    }

    // 1999 KW4 as two ellipsoids (Ho et al. 2021 shapes; SI units).
    let g = 6.674e-11;
    let primary = Body::ellipsoid(
        Ellipsoid::new(766.0, 747.5, 673.5, 2.353e12)?.with_gravitational_constant(g)?,
    )?;
    let secondary = Body::ellipsoid(
        Ellipsoid::new(285.0, 231.5, 174.5, 0.135e12)?.with_gravitational_constant(g)?,
    )?;
    let pose_a = Pose::identity();
    let aligned = Pose::new(Vec3::new(2548.0, 0.0, 0.0), Vec3::zeros());
    let m = measure(
        &primary, &pose_a, &secondary, &aligned, options, None, 0.005,
    )?;
    println!(
        "KW4 aligned: {:.1} µs, {} evaluations, estimate {:.1e}",
        m.seconds * 1e6,
        m.evaluations,
        m.error_estimate
    );
    let mut rng = SplitMix64::new(seed ^ 0x004b_5734);
    let attitudes: usize = std::env::var("POSE_BENCHMARK_KW4")
        .map_or(Ok(20), |s| s.parse())
        .map_err(|e| format!("POSE_BENCHMARK_KW4 must be a count: {e}"))?;
    let mut tilted = vec![];
    for _ in 0..attitudes.max(1) {
        let pose_a = Pose::new(Vec3::zeros(), rng.rotation_vector());
        let pose_b = Pose::new(rng.direction() * 2548.0, rng.rotation_vector());
        let m = measure(&primary, &pose_a, &secondary, &pose_b, options, None, 0.002)?;
        let (reference, _) = independent_reference(&primary, &pose_a, &secondary, &pose_b, 1e-13)?;
        let error = interaction_error(&m.interaction, &reference);
        if verbose {
            println!(
                "KW4 tilted: {:.1} µs, {} evaluations, level {:?}, over {:?}, estimate {:.1e}, true error {error:.1e}",
                m.seconds * 1e6,
                m.evaluations,
                m.interaction.level,
                m.interaction.integrated_over,
                m.error_estimate
            );
        }
        tilted.push((m.seconds * 1e6, m.evaluations, error, m.error_estimate));
    }
    tilted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let worst = tilted[tilted.len() - 1];
    println!(
        "KW4 random attitudes ({}): median {:.1} µs, worst {:.1} µs ({} evaluations, true error {:.1e}, estimate {:.1e})",
        tilted.len(),
        tilted[tilted.len() / 2].0,
        worst.0,
        worst.1,
        worst.2,
        worst.3
    );

    // The founding paper's pair.
    let paper = || Body::spheroid(Spheroid::new(1.0, 0.25, 1.0).unwrap()).unwrap();
    let (a, b) = (paper(), paper());
    for separation in [2.1, 2.55, 3.0, 7.0, 30.0] {
        let pose_b = Pose::new(Vec3::new(separation, 0.0, 0.0), Vec3::zeros());
        let m = measure(&a, &Pose::identity(), &b, &pose_b, options, None, 0.005)?;
        println!(
            "paper pair separation {separation}: {:.1} µs, {} evaluations",
            m.seconds * 1e6,
            m.evaluations
        );
    }
    Ok(())
}
