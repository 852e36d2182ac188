//! The paper's presets, run through the scene layer (TOML text → `build()` → model →
//! integration → diagnostics), reproduce the reference values of issue 5.
//!
//! Provenance: the values are quoted in issue 5 ("What the paper's scenes must give") as
//! continuous-time results of an independent computation, rounded to the digits shown. Each
//! tolerance is half a unit in the last quoted digit: the rounding of the reference itself. The
//! integration error of RK4 at the paper's steps is far below that (paper-2s: the tabulated and
//! direct paths agree to 1.2e-11 in separation; halving the step moves ψ_p by 1.1e-5° and the
//! minimum separation by 4.2e-8).
//!
//! Each run takes milliseconds (tabulated V(r); release-level test profile).

use surfgrav_scenarios::presets;
use surfgrav_scenarios::simulate::{run_scene, RunRecord};

fn run(name: &str) -> RunRecord {
    let scene = presets::find(name)
        .expect("preset exists")
        .scene()
        .expect("preset builds");
    run_scene(&scene).expect("preset runs")
}

/// |value − reference| ≤ half a unit in the reference's last digit.
fn check(what: &str, value: Option<f64>, reference: f64, decimals: i32) {
    let value = value.unwrap_or_else(|| panic!("{what}: no value"));
    let tolerance = 0.5 * 10f64.powi(-decimals);
    assert!(
        (value - reference).abs() <= tolerance,
        "{what}: {value} vs {reference} ± {tolerance}"
    );
}

#[test]
fn paper_2s_precession_periods_and_energy_scatter() {
    let r = run("paper-2s");
    assert_eq!(r.method, "tabulated V(r)");
    let o = &r.orbit;
    check("ψ_p (deg)", o.precession_angle_deg, 18.964, 3);
    check("Ω_p (arcmin)", o.precession_rate_arcmin, 24.03, 2);
    check("T_r", o.radial_period, 47.355, 3);
    check("T_ψ", o.azimuthal_period, 44.985, 3);
    check("minimum separation", o.minimum_separation, 2.5472, 4);
    assert_eq!(r.summary.steps, 3000);
    // Issue 5: σ(ΔE) about 3e-11 per step with exact forces, three orders of magnitude below
    // the paper's 3e-8. Measured 3.13e-11; the bounds allow a factor 3 either way.
    let sigma = r.energy.step_changes.standard_deviation;
    assert!((1e-11..1e-10).contains(&sigma), "σ(ΔE) = {sigma:e}");
}

#[test]
fn paper_2s_prolate_precesses_backwards() {
    let o = run("paper-2s-prolate").orbit;
    check("ψ_p (deg)", o.precession_angle_deg, -10.478, 3);
    check("Ω_p (arcmin)", o.precession_rate_arcmin, -13.09, 2);
    check("minimum separation", o.minimum_separation, 2.8540, 4);
}

#[test]
fn paper_2d_disks() {
    let r = run("paper-2d");
    assert_eq!(r.summary.steps, 30_000);
    let o = &r.orbit;
    check("ψ_p (deg)", o.precession_angle_deg, 30.2225, 4);
    check("Ω_p (arcmin)", o.precession_rate_arcmin, 38.27, 2);
    check("minimum separation", o.minimum_separation, 2.4695, 4);
}

#[test]
fn paper_point_is_kepler() {
    let r = run("paper-point");
    assert_eq!(r.method, "point masses (exact)");
    let o = &r.orbit;
    check("T_r", o.radial_period, 47.6177, 4);
    check("minimum separation", o.minimum_separation, 2.72222, 5);
    // No precession: RK4's own apsidal drift at dt = 0.1 is 5.0e-6 degrees per orbit.
    let psi = o.precession_angle_deg.unwrap();
    assert!(psi.abs() < 1e-4, "{psi}");
}
