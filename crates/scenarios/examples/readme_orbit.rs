//! The README's library example, compiled and run here so that it cannot rot: a potential
//! paired with a surface (two of the paper's oblate spheroids), then the orbit integrated.
//! The `surfgrav` module below stands in for the facade crate's re-exports.
//!
//! Run with `cargo run --release -p surfgrav-scenarios --example readme_orbit`.

mod surfgrav {
    pub use surfgrav_dynamics as dynamics;
    pub use surfgrav_interaction as interaction;
    pub use surfgrav_potentials as potentials;
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // --- README example starts ---
    use surfgrav::dynamics::{
        run_with_diagnostics, BodyState, FixedScheme, FixedStep, SceneModel, SceneSettings,
        TwoBodyState,
    };
    use surfgrav::interaction::Body;
    use surfgrav::potentials::{Spheroid, Vec3};

    // The paper's 2S scene: two oblate spheroids a = 1, c = 0.25, m = 1 (G = 1), 7 apart.
    let body = Body::spheroid(Spheroid::new(1.0, 0.25, 1.0)?)?;
    let start = TwoBodyState::new(
        BodyState::new(Vec3::new(-3.5, 0.0, 0.0), Vec3::new(0.0, 0.2, 0.0)),
        BodyState::new(Vec3::new(3.5, 0.0, 0.0), Vec3::new(0.0, -0.2, 0.0)),
    );
    // Central pair in its equatorial plane: V(r) is tabulated once from the surface integrals.
    let model = SceneModel::build(body.clone(), body, &start, &SceneSettings::default())?;
    let mut rk4 = FixedStep::new(FixedScheme::RungeKutta4, 0.1)?;
    let run = run_with_diagnostics(&mut rk4, &model, &start, 0.0, 300.0, &mut |_| {})?;

    // The orbit precesses forward by ψ_p = 18.964° per radial period; energy is kept to 1e-7.
    let psi = run
        .orbit
        .precession_angle_deg
        .ok_or("no precession measured")?;
    assert!((psi - 18.964).abs() < 1e-3);
    assert!(run.energy.max_relative_drift < 1e-7);
    // --- README example ends ---
    println!(
        "ψ_p = {psi:.4}°, max |E − E0|/|E0| = {:.1e}",
        run.energy.max_relative_drift
    );
    Ok(())
}
