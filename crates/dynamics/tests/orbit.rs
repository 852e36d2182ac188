//! Orbit analysis: apsides, periods and precession against analytic values.

mod common;

use common::{paper_point, Kepler};
use surfgrav_dynamics::{
    Adaptive, BodyState, CentralPair, FixedScheme, FixedStep, Integrator, InteractionModel,
    OrbitAnalyser, OrbitReport, TwoBodyState,
};
use surfgrav_potentials::{Real, Vec3};

fn analyse(
    integrator: &mut dyn Integrator,
    model: &dyn InteractionModel,
    initial: &TwoBodyState,
    t_end: Real,
) -> OrbitReport {
    let mut analyser = OrbitAnalyser::new();
    integrator
        .integrate(model, initial, 0.0, t_end, &mut |s| analyser.observe(s))
        .unwrap();
    analyser.report()
}

/// Kepler e = 0.5 with the adaptive integrator: T_r = 2π, ψ_p = 0, pericentre 0.5, apocentre 1.5.
#[test]
fn kepler_orbit_has_no_precession() {
    let kepler = Kepler::new(0.5);
    let mut integrator = Adaptive::new(1e-13, 1e-15).unwrap();
    let report = analyse(
        &mut integrator,
        &kepler.model,
        &kepler.initial_state(),
        5.3 * kepler.period(),
    );
    assert_eq!(report.apocentres.len(), 5);
    assert_eq!(report.pericentres.len(), 6); // t = 0 and five more.
    let t_r = report.radial_period.unwrap();
    let psi_p = report.precession_angle_deg.unwrap();
    println!(
        "Kepler: T_r − 2π = {:.3e}, ψ_p = {psi_p:.3e}°",
        t_r - kepler.period()
    );
    assert!((t_r - kepler.period()).abs() < 1e-10);
    assert!(psi_p.abs() < 1e-8);
    assert!((report.azimuthal_period.unwrap() - kepler.period()).abs() < 1e-10);
    for (k, apo) in report.apocentres.iter().enumerate() {
        assert!((apo.separation - 1.5).abs() < 1e-11);
        assert!((apo.time - (k as Real + 0.5) * kepler.period()).abs() < 1e-9);
    }
    assert!((report.minimum_separation.unwrap() - 0.5).abs() < 1e-11);
}

/// The paper-point scene with the paper's RK4, dt = 0.1, t = 300: T_r = 47.6177, minimum
/// separation 2.72222, no precession (issue 5's continuous-time values).
#[test]
fn paper_point_scene() {
    let (model, initial) = paper_point();
    let mut integrator = FixedStep::new(FixedScheme::RungeKutta4, 0.1).unwrap();
    let report = analyse(&mut integrator, &model, &initial, 300.0);
    // Exact: relative orbit with μ = 2, r0 = 7 at apocentre, v0 = 0.4:
    // a = 1/(2/r0 − v0²/μ), T = 2π√(a³/μ), r_p = 2a − r0.
    let a: Real = 1.0 / (2.0 / 7.0 - 0.16 / 2.0);
    let period = 2.0 * std::f64::consts::PI * (a * a * a / 2.0).sqrt();
    let pericentre = 2.0 * a - 7.0;
    let t_r = report.radial_period.unwrap();
    let psi_p = report.precession_angle_deg.unwrap();
    let d_min = report.minimum_separation.unwrap();
    println!(
        "paper-point RK4: T_r = {t_r:.7} (exact {period:.7}), d_min = {d_min:.7} (exact {pericentre:.7}), ψ_p = {psi_p:.3e}°, apocentres {}",
        report.apocentres.len()
    );
    assert!((t_r - 47.6177).abs() < 5e-5);
    assert!((d_min - 2.72222).abs() < 5e-6);
    assert!(psi_p.abs() < 1e-3);
    // RK4 at dt = 0.1 against the exact values.
    assert!((t_r - period).abs() < 1e-5);
    assert!((d_min - pericentre).abs() < 1e-6);
}

/// $V = -\alpha/r - \beta/(2r^2)$: the relative orbit obeys $u'' + (1 - \epsilon/L^2)u = k/L^2$
/// ($u = 1/r$, $k = \alpha/\mu\_{red}$, $\epsilon = \beta/\mu\_{red}$, $L = |\mathbf r\times\dot{\mathbf r}|$)
/// exactly, so apsides advance by $\psi_p = 360°\\,(1/\sqrt{1-\epsilon/L^2} - 1)$ per radial period
/// at any eccentricity.
#[test]
fn inverse_cube_force_precession() {
    let (alpha, beta) = (0.25, 0.01);
    let model = CentralPair::new(
        0.5,
        0.5,
        move |r: Real| -alpha / r - beta / (2.0 * r * r),
        move |r: Real| alpha / (r * r) + beta / (r * r * r),
    )
    .unwrap();
    let reduced_mass = 0.25;
    let (r0, v0) = (Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.2, 0.0));
    let initial = TwoBodyState::new(
        BodyState::new(-0.5 * r0, -0.5 * v0),
        BodyState::new(0.5 * r0, 0.5 * v0),
    );
    let l = r0.cross(&v0).norm();
    let epsilon = beta / reduced_mass;
    let expected = 360.0 * (1.0 / (1.0 - epsilon / (l * l)).sqrt() - 1.0);
    for (name, mut integrator) in [
        (
            "dopri5",
            Box::new(Adaptive::new(1e-12, 1e-14).unwrap()) as Box<dyn Integrator>,
        ),
        (
            "yoshida6",
            Box::new(FixedStep::new(FixedScheme::Yoshida6, 0.02).unwrap()),
        ),
    ] {
        let report = analyse(integrator.as_mut(), &model, &initial, 60.0);
        let psi_p = report.precession_angle_deg.unwrap();
        println!(
            "{name}: ψ_p = {psi_p:.10}° (exact {expected:.10}°), error {:.2e}, apocentres {}",
            psi_p - expected,
            report.apocentres.len()
        );
        assert!(report.apocentres.len() >= 3);
        assert!((psi_p - expected).abs() < 1e-7 * expected.abs());
        let t_r = report.radial_period.unwrap();
        let t_psi = report.azimuthal_period.unwrap();
        assert!((t_psi - t_r * 360.0 / (360.0 + psi_p)).abs() < 1e-12 * t_r);
        assert!(
            (report.precession_rate_arcmin.unwrap() - 60.0 * psi_p / t_r).abs() < 1e-12 * psi_p
        );
    }
}
