//! surfgrav's exact force, torques and mutual energy for the configurations of the GUBAS
//! side-by-side comparison (`tools/gubas/`, issues 11 and 13), one CSV row per configuration
//! on stdout, a readable line per configuration on stderr.
//!
//! The primary A sits at the origin in its own body frame (identity pose); the secondary B is
//! placed by its centroid position and rotation vector, both in A's frame, which is the frame
//! GUBAS works in (its relative position and C(B → A)). SI units, G = 6.6743e-11.
//!
//! Per configuration:
//! - the value written is the engine's result at relative tolerance 1e-13 (certified unless the
//!   `certified` column says otherwise);
//! - `agreement` is its difference from an independent reference (the fixed-rule ladder at 1e-13
//!   over the *other* body's surface, polar-angle form), in the engine's error measure:
//!   max(|δF|/|F|, |δV|/|V|, |δM|/max(|M|, |V|) for each torque);
//! - `seconds` and `cpu_seconds` are the warm wall and CPU time of one evaluation of force +
//!   both torques + energy certified to 1e-12, each the best of five batches of at least 20 ms
//!   of the process's CPU time (`/proc/self/task/*/schedstat`, nanoseconds; on a shared machine
//!   the CPU time is the one to read: wall time counts the waits for a core), one worker thread
//!   (run with `RAYON_NUM_THREADS=1`), with the field evaluations and the error estimate.
//!
//! `RAYON_NUM_THREADS=1 cargo run --release -p surfgrav-interaction --example gubas_compare > exact.csv`

use std::path::PathBuf;
use std::time::Instant;
use surfgrav_interaction::work_precision::{independent_reference, interaction_error};
use surfgrav_interaction::{
    Body, Interaction, InteractionEngine, InteractionError, InteractionOptions,
};
use surfgrav_potentials::{Ellipsoid, LengthUnit, Mesh, Polyhedron, Pose, Potential, Vec3};

/// CODATA 2018, m³ kg⁻¹ s⁻² (the value GUBAS is given too, in km³).
const G: f64 = 6.6743e-11;

/// How a body is described to both codes.
#[derive(Clone, Copy)]
enum Shape {
    /// Semi-axes (m) along the body's x, y, z and total mass (kg).
    Ellipsoid([f64; 3], f64),
    /// The Didymos radar polyhedron (`data/shapes/Didymos_A_*.csv`) at this density (kg/m³).
    Didymos(f64),
}

struct Config {
    name: &'static str,
    a: Shape,
    b: Shape,
    /// B's centroid in A's frame (m).
    position: [f64; 3],
    /// B's rotation vector, B's frame → A's frame (rad).
    rotation: [f64; 3],
}

fn ellipsoid_mass(axes: [f64; 3], density: f64) -> f64 {
    4.0 / 3.0 * std::f64::consts::PI * axes[0] * axes[1] * axes[2] * density
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / n, v[1] / n, v[2] / n]
}

fn scaled(v: [f64; 3], s: f64) -> [f64; 3] {
    [v[0] * s, v[1] * s, v[2] * s]
}

fn configurations(didymos_max_x: f64) -> Vec<Config> {
    // 1999 KW4 as two ellipsoids (Ho et al. 2021), 2548 m apart.
    let kw4_a = Shape::Ellipsoid([766.0, 747.5, 673.5], 2.353e12);
    let kw4_b = Shape::Ellipsoid([285.0, 231.5, 174.5], 0.135e12);
    // Didymos-like ellipsoids (F2BPtoolkit's test), 1195 m apart.
    let dl_a = Shape::Ellipsoid(
        [400.0, 395.0, 340.0],
        ellipsoid_mass([400.0, 395.0, 340.0], 2170.0),
    );
    let dl_b = Shape::Ellipsoid(
        [85.0, 73.0, 63.0],
        ellipsoid_mass([85.0, 73.0, 63.0], 2400.0),
    );
    // The DART standard system: radar primary and triaxial secondary, one density, 1180 m.
    let rho = 2_103.985_767_887_719;
    let ds_a = Shape::Didymos(rho);
    let ds_axes = [103.6778, 79.7526, 66.4605];
    let ds_b = Shape::Ellipsoid(ds_axes, ellipsoid_mass(ds_axes, rho));
    let tilt_1 = unit([0.8, 0.5, 0.33]);
    let tilt_2 = unit([-0.3, 0.9, -0.4]);
    let tilt_3 = unit([0.2, -0.35, 0.92]);
    let config = |name, a, b, position, rotation| Config {
        name,
        a,
        b,
        position,
        rotation,
    };
    vec![
        config("kw4 aligned", kw4_a, kw4_b, [2548.0, 0.0, 0.0], [0.0; 3]),
        config(
            "kw4 tilted 1",
            kw4_a,
            kw4_b,
            scaled(tilt_1, 2548.0),
            [0.3, -0.5, 0.7],
        ),
        config(
            "kw4 tilted 2",
            kw4_a,
            kw4_b,
            scaled(tilt_2, 2548.0),
            [-1.1, 0.4, 0.2],
        ),
        config(
            "kw4 tilted 3",
            kw4_a,
            kw4_b,
            scaled(tilt_3, 2548.0),
            [0.5, 1.3, -0.6],
        ),
        // Long axes on the line of centres, gap 0.05 × B's largest semi-axis (285 m); the
        // circumscribing spheres (766 + 285 = 1051 m) do not overlap at 1065.25 m.
        config(
            "kw4 near contact x",
            kw4_a,
            kw4_b,
            [766.0 + 285.0 * 1.05, 0.0, 0.0],
            [0.0; 3],
        ),
        // B above A's short axis, B's long axis vertical, gap 0.05 × 285 m: the circumscribing
        // spheres overlap (972.75 m < 1051 m), outside the series' guaranteed convergence.
        config(
            "kw4 near contact z",
            kw4_a,
            kw4_b,
            [0.0, 0.0, 673.5 + 285.0 * 1.05],
            [0.0, std::f64::consts::FRAC_PI_2, 0.0],
        ),
        config(
            "didymos-like aligned",
            dl_a,
            dl_b,
            [1195.0, 0.0, 0.0],
            [0.0; 3],
        ),
        config(
            "didymos-like tilted 1",
            dl_a,
            dl_b,
            scaled(tilt_1, 1195.0),
            [0.3, -0.5, 0.7],
        ),
        config(
            "didymos-like near contact x",
            dl_a,
            dl_b,
            [400.0 + 85.0 * 1.05, 0.0, 0.0],
            [0.0; 3],
        ),
        config(
            "didymos-standard aligned",
            ds_a,
            ds_b,
            [1180.0, 0.0, 0.0],
            [0.0; 3],
        ),
        config(
            "didymos-standard tilted 1",
            ds_a,
            ds_b,
            scaled(tilt_1, 1180.0),
            [0.3, -0.5, 0.7],
        ),
        // B's tip 0.05 × 103.68 m beyond the mesh's largest x: the gap is at least that.
        config(
            "didymos-standard near contact x",
            ds_a,
            ds_b,
            [didymos_max_x + ds_axes[0] * 1.05, 0.0, 0.0],
            [0.0; 3],
        ),
    ]
}

fn shapes() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/shapes")
}

fn didymos(density: f64) -> Result<Polyhedron, Box<dyn std::error::Error>> {
    let mesh = Mesh::read_vertex_facet_csv(
        shapes().join("Didymos_A_vert_met.csv"),
        shapes().join("Didymos_A_facet.csv"),
        LengthUnit::Metres,
    )?;
    Ok(Polyhedron::with_density(&mesh, density)?.with_gravitational_constant(G)?)
}

fn body(shape: Shape) -> Result<Body, Box<dyn std::error::Error>> {
    Ok(match shape {
        Shape::Ellipsoid([a, b, c], mass) => {
            Body::ellipsoid(Ellipsoid::new(a, b, c, mass)?.with_gravitational_constant(G)?)?
        }
        Shape::Didymos(density) => Body::polyhedron(didymos(density)?)?,
    })
}

/// `kind,x1,x2,x3,mass,density` columns: an ellipsoid's semi-axes, or the mesh name.
fn shape_columns(shape: Shape) -> Result<String, Box<dyn std::error::Error>> {
    Ok(match shape {
        Shape::Ellipsoid([a, b, c], mass) => {
            let density = mass / (4.0 / 3.0 * std::f64::consts::PI * a * b * c);
            format!("ellipsoid,{a:e},{b:e},{c:e},{mass:e},{density:e}")
        }
        Shape::Didymos(density) => {
            let mass = didymos(density)?.mass();
            format!("didymos_polyhedron,0,0,0,{mass:e},{density:e}")
        }
    })
}

/// CPU time of this process's threads in seconds (Linux: the first field of each
/// `/proc/self/task/*/schedstat` is the time that thread ran, in nanoseconds; the mesh rule's
/// node loop runs on rayon's worker, so the calling thread's clock alone misses it); NaN where
/// it cannot be read.
fn process_cpu_seconds() -> f64 {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return f64::NAN;
    };
    let mut ns = 0.0;
    for task in tasks.flatten() {
        let Some(run) = std::fs::read_to_string(task.path().join("schedstat"))
            .ok()
            .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        else {
            return f64::NAN;
        };
        ns += run;
    }
    ns * 1e-9
}

/// Best wall and best CPU seconds per call over five batches of at least `batch` CPU seconds.
fn time_per_call(batch: f64, mut f: impl FnMut()) -> (f64, f64) {
    // Calls are made in chunks of at least 1 ms, the clocks read between chunks only (a read of
    // /proc costs microseconds, as much as a cheap call).
    let t = Instant::now();
    f();
    let chunk = (1e-3 / t.elapsed().as_secs_f64().max(1e-9)).ceil().min(1e6) as u32;
    let (mut wall, mut cpu) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..5 {
        let (t0, c0) = (Instant::now(), process_cpu_seconds());
        let mut calls = 0u32;
        // Wall time bounds the batch where the CPU clock cannot be read.
        while calls == 0
            || !(process_cpu_seconds() - c0 >= batch || t0.elapsed().as_secs_f64() >= 20.0 * batch)
        {
            for _ in 0..chunk {
                f();
            }
            calls += chunk;
        }
        wall = wall.min(t0.elapsed().as_secs_f64() / f64::from(calls));
        cpu = cpu.min((process_cpu_seconds() - c0) / f64::from(calls));
    }
    (wall, cpu)
}

fn engine_result(
    result: Result<Interaction, InteractionError>,
) -> Result<(Interaction, bool), InteractionError> {
    match result {
        Ok(r) => Ok((r, true)),
        Err(InteractionError::ToleranceNotMet { best, .. }) => Ok((*best, false)),
        Err(e) => Err(e),
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let didymos_max_x = didymos(1.0)?
        .vertices()
        .iter()
        .map(|v| v.x)
        .fold(f64::NEG_INFINITY, f64::max);
    println!(
        "config,kind_a,a1,a2,a3,mass_a,density_a,kind_b,b1,b2,b3,mass_b,density_b,px,py,pz,rx,ry,rz,g,\
         fbx,fby,fbz,max,may,maz,mbx,mby,mbz,v,certified,agreement,seconds,cpu_seconds,evaluations,estimate"
    );
    for c in configurations(didymos_max_x) {
        let (a, b) = (body(c.a)?, body(c.b)?);
        let pose_a = Pose::identity();
        let pose_b = Pose::new(Vec3::from(c.position), Vec3::from(c.rotation));
        let mut exact = InteractionEngine::new(InteractionOptions {
            relative_tolerance: 1e-13,
            ..InteractionOptions::default()
        })?;
        let (r, certified) = engine_result(exact.interact(&a, &pose_a, &b, &pose_b))?;
        let (independent, _) = independent_reference(&a, &pose_a, &b, &pose_b, 1e-13)?;
        let agreement = interaction_error(&r, &independent);
        let mut engine = InteractionEngine::new(InteractionOptions {
            relative_tolerance: 1e-12,
            ..InteractionOptions::default()
        })?;
        let (timed, timed_certified) = engine_result(engine.interact(&a, &pose_a, &b, &pose_b))?;
        let (seconds, cpu_seconds) = time_per_call(0.02, || {
            let _ = std::hint::black_box(engine.interact(&a, &pose_a, &b, &pose_b));
        });
        let timed_error = interaction_error(&timed, &r);
        eprintln!(
            "{}: |F| = {:.6e} N, V = {:.6e} J, certified 1e-13: {certified}, vs independent {agreement:.1e}; \
             1e-12 (certified: {timed_certified}): {:.1} µs CPU ({:.1} µs wall), {} evaluations, estimate {:.1e}, error {timed_error:.1e}",
            c.name,
            r.force_on_b.norm(),
            r.potential_energy,
            cpu_seconds * 1e6,
            seconds * 1e6,
            timed.evaluations,
            timed.error_estimate,
        );
        let v3 = |v: &Vec3| format!("{:.17e},{:.17e},{:.17e}", v.x, v.y, v.z);
        println!(
            "{},{},{},{},{},{G:e},{},{},{},{:.17e},{certified},{agreement:.3e},{seconds:.4e},{cpu_seconds:.4e},{},{:.3e}",
            c.name,
            shape_columns(c.a)?,
            shape_columns(c.b)?,
            v3(&Vec3::from(c.position)),
            v3(&Vec3::from(c.rotation)),
            v3(&r.force_on_b),
            v3(&r.torque_on_a),
            v3(&r.torque_on_b),
            r.potential_energy,
            timed.evaluations,
            timed.error_estimate,
        );
    }
    Ok(())
}
