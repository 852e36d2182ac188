//! Repeats one case of the pose benchmark's set for profiling the solid loops:
//! `cargo run --release -p surfgrav-interaction --example solid_loop_profile -- LABEL [SECONDS [SEED]]`
//! (LABEL a substring of a case's label, e.g. "ellipsoid-ellipsoid gap 1 #2"; SEED that of
//! the pose set, 12 by default). Prints the
//! evaluations and the time per call and per evaluation (warm, one engine).

use std::time::Instant;
use surfgrav_interaction::work_precision::pose_set;
use surfgrav_interaction::{InteractionEngine, InteractionError, InteractionOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let label = args
        .get(1)
        .map_or("ellipsoid-ellipsoid gap 1 #2", |s| s.as_str());
    let seconds: f64 = args.get(2).map_or(Ok(3.0), |s| s.parse())?;
    let seed: u64 = args.get(3).map_or(Ok(12), |s| s.parse())?;
    let cases = pose_set(seed, &[0.05, 0.2, 1.0, 5.0], 4);
    let case = cases
        .iter()
        .find(|c| c.label.contains(label))
        .ok_or("no case with this label")?;
    let mut engine = InteractionEngine::new(InteractionOptions::default())?;
    let call = |engine: &mut InteractionEngine| match engine.interact(
        &case.a,
        &case.pose_a,
        &case.b,
        &case.pose_b,
    ) {
        Ok(r) => Ok(r),
        Err(InteractionError::ToleranceNotMet { best, .. }) => Ok(*best),
        Err(e) => Err(e),
    };
    let first = call(&mut engine)?;
    let start = Instant::now();
    let mut calls = 0u64;
    while start.elapsed().as_secs_f64() < seconds {
        for _ in 0..16 {
            std::hint::black_box(call(&mut engine)?);
        }
        calls += 16;
    }
    let per_call = start.elapsed().as_secs_f64() / calls as f64;
    println!(
        "{}: {} evaluations, {:.2} µs per call, {:.1} ns per evaluation ({} calls)",
        case.label,
        first.evaluations,
        per_call * 1e6,
        per_call * 1e9 / first.evaluations as f64,
        calls
    );
    Ok(())
}
