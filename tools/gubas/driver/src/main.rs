//! Runs GUBAS-RS's mutual-potential series (Hou 2016) on the configurations that surfgrav's
//! `gubas_compare` example wrote, and compares GUBAS's force, torques and energy with
//! surfgrav's exact values.
//!
//! Usage: `gubas-compare-driver EXACT_CSV GUBAS_EXAMPLE_DIR ORDER... > gubas.csv`
//!
//! For every configuration and series order it evaluates what GUBAS-RS's equations of motion
//! evaluate per step (`hou_ode`): the rotated secondary integrals and the nine dT/dC cubes and
//! the partials dU/dr, dU/dC (`potential::map_potential_partials_rhs`), the torques assembled
//! as `hou_ode` assembles them, and the energy (`potential::potential`); timed by wall clock
//! and by this thread's CPU clock, best of ten batches. Only the public API of
//! the gubas_rs crate is called; nothing of it is copied.
//!
//! Inertia integrals T_lmn of the bodies:
//! - `shipped`: GUBAS-RS's own generators (`inertia::ell_mass_params_met` for an ellipsoid,
//!   which fills degrees 0, 2 and 4 only; `inertia::poly_inertia_met` for the polyhedron);
//! - `complete` (ellipsoids, orders above 4): every even degree up to the order, from the
//!   closed form T_lmn = M a^l b^m c^n · 3 Γ((l+1)/2) Γ((m+1)/2) Γ((n+1)/2) /
//!   (2π (l+m+n+3) Γ((l+m+n+3)/2)) (l, m, n even; zero otherwise), so that a truncated body
//!   does not hide the series' own error.
//!
//! Units inside GUBAS: km, kg, s. Results are converted to SI before comparing.

use gubas_rs::coefficients::{a_calc, b_calc, tk_calc};
use gubas_rs::inertia::{ell_mass_params_met, poly_inertia_met};
use gubas_rs::math3::{cross, norm, scale_v, sub_v, Mat3, Vec3};
use gubas_rs::potential::{map_potential_partials_rhs, potential};
use gubas_rs::types::{Cube, Params};
use std::collections::HashMap;
use std::time::Instant;

#[derive(Clone)]
struct Row {
    name: String,
    fields: HashMap<String, String>,
}

impl Row {
    fn text(&self, key: &str) -> &str {
        self.fields
            .get(key)
            .unwrap_or_else(|| panic!("column {key} missing"))
    }
    fn num(&self, key: &str) -> f64 {
        self.text(key)
            .parse()
            .unwrap_or_else(|e| panic!("{}: column {key}: {e}", self.name))
    }
    fn vec(&self, keys: [&str; 3]) -> [f64; 3] {
        keys.map(|k| self.num(k))
    }
}

fn read_rows(path: &str) -> Vec<Row> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .expect("empty file")
        .split(',')
        .map(String::from)
        .collect();
    lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let fields: HashMap<String, String> = header
                .iter()
                .cloned()
                .zip(l.split(',').map(String::from))
                .collect();
            Row {
                name: fields["config"].clone(),
                fields,
            }
        })
        .collect()
}

/// Γ(k/2) for a positive integer k.
fn gamma_half(k: usize) -> f64 {
    let mut x = if k % 2 == 0 {
        1.0
    } else {
        std::f64::consts::PI.sqrt()
    };
    let mut arg = if k % 2 == 0 { 1.0 } else { 0.5 };
    while arg < k as f64 / 2.0 {
        x *= arg;
        arg += 1.0;
    }
    x
}

/// Every inertia integral of a homogeneous ellipsoid up to degree `order` (km, kg).
fn complete_ellipsoid_cube(order: usize, mass: f64, axes_km: [f64; 3]) -> Cube {
    let mut t = Cube::new(order);
    for l in (0..=order).step_by(2) {
        for m in (0..=order - l).step_by(2) {
            for n in (0..=order - l - m).step_by(2) {
                let moment = 3.0 * gamma_half(l + 1) * gamma_half(m + 1) * gamma_half(n + 1)
                    / (2.0
                        * std::f64::consts::PI
                        * (l + m + n + 3) as f64
                        * gamma_half(l + m + n + 3));
                let value = mass
                    * axes_km[0].powi(l as i32)
                    * axes_km[1].powi(m as i32)
                    * axes_km[2].powi(n as i32)
                    * moment;
                t.set(l, m, n, value);
            }
        }
    }
    t
}

/// T_lmn of one body (km, kg) and its principal moments.
fn body_cube(row: &Row, side: char, order: usize, complete: bool, example: &str) -> (Cube, Vec3) {
    let kind = row.text(&format!("kind_{side}"));
    let density_km = row.num(&format!("density_{side}")) * 1e9; // kg/km³
    match kind {
        "ellipsoid" => {
            let k = |i: usize| format!("{side}{i}");
            let axes_m = [row.num(&k(1)), row.num(&k(2)), row.num(&k(3))];
            let (moments, shipped) =
                ell_mass_params_met(order, order, density_km, axes_m[0], axes_m[1], axes_m[2]);
            if !complete {
                return (shipped, moments);
            }
            let axes_km = axes_m.map(|x| x / 1000.0);
            let full = complete_ellipsoid_cube(order, shipped.get(0, 0, 0), axes_km);
            // The two agree where GUBAS fills the cube (degrees ≤ 4).
            for (l, m, n) in [
                (0, 0, 0),
                (2, 0, 0),
                (0, 2, 0),
                (0, 0, 2),
                (4, 0, 0),
                (2, 2, 0),
                (0, 2, 2),
            ] {
                if l + m + n <= order.min(4) {
                    let (a, b) = (shipped.get(l, m, n), full.get(l, m, n));
                    assert!(
                        (a - b).abs() <= 1e-13 * b.abs(),
                        "T_{l}{m}{n}: {a:e} vs {b:e}"
                    );
                }
            }
            (full, moments)
        }
        "didymos_polyhedron" => {
            let facets = format!("{example}/Didymos_A_facet.csv");
            let vertices = format!("{example}/Didymos_A_vert_met.csv");
            let cube = poly_inertia_met(order, density_km, &facets, &vertices);
            let moments = gubas_rs::inertia::poly_moi_met(density_km, &facets, &vertices);
            (cube, moments)
        }
        other => panic!("{}: unknown body kind {other}", row.name),
    }
}

fn params(g_km: f64, order: usize, ta: Cube, tb: Cube, ia: Vec3, ib: Vec3) -> Params {
    let (mc, ms) = (ta.get(0, 0, 0), tb.get(0, 0, 0));
    let zero3 = [[0.0; 3]; 3];
    let mut p = Params {
        g: g_km,
        m: mc * ms / (mc + ms),
        nu: ms / (mc + ms),
        ta,
        tb,
        ia,
        ib,
        n: order,
        tk: tk_calc(order),
        a: a_calc(order),
        b: b_calc(order),
        flyby_toggle: 0,
        helio_toggle: 0,
        sg_toggle: 0,
        tt_toggle: 0,
        mplanet: 0.0,
        a_hyp: 0.0,
        e_hyp: 0.0,
        i_hyp: 0.0,
        raan_hyp: 0.0,
        om_hyp: 0.0,
        tau_hyp: 0.0,
        n_hyp: 0.0,
        msolar: 0.0,
        a_helio: 0.0,
        e_helio: 0.0,
        i_helio: 0.0,
        raan_helio: 0.0,
        om_helio: 0.0,
        tau_helio: 0.0,
        n_helio: 0.0,
        sol_rad: 0.0,
        au_def: 0.0,
        mean_motion: 0.0,
        love1: 0.0,
        love2: 0.0,
        refrad1: 0.0,
        refrad2: 0.0,
        rho_a: 0.0,
        rho_b: 0.0,
        eps1: 0.0,
        eps2: 0.0,
        ida: zero3,
        idb: zero3,
        msun: 0.0,
    };
    p.compute_lgvi_inertia();
    p
}

/// Rotation matrix of a rotation vector (Rodrigues).
fn rotation(v: [f64; 3]) -> Mat3 {
    let angle = norm(v);
    let mut r = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    if angle == 0.0 {
        return r;
    }
    let k = scale_v(1.0 / angle, v);
    let kx = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]];
    let (s, c) = angle.sin_cos();
    for i in 0..3 {
        for j in 0..3 {
            let k2: f64 = (0..3).map(|m| kx[i][m] * kx[m][j]).sum();
            r[i][j] += s * kx[i][j] + (1.0 - c) * k2;
        }
    }
    r
}

struct Wrench {
    force_on_b: Vec3,
    torque_on_a: Vec3,
    torque_on_b: Vec3,
    energy: f64,
}

/// One evaluation as `hou_ode` makes it, in GUBAS's units (km, kg, s).
fn evaluate(c: Mat3, r: Vec3, p: &Params) -> Wrench {
    let (tbp, du_dr, du_cols) = map_potential_partials_rhs(c, r, p);
    let col = |j: usize| [c[0][j], c[1][j], c[2][j]];
    let mut sum = [0.0; 3];
    for (j, du) in du_cols.iter().enumerate() {
        let t = cross(col(j), *du);
        sum = [sum[0] + t[0], sum[1] + t[1], sum[2] + t[2]];
    }
    let torque_on_b = scale_v(-1.0, sum);
    let torque_on_a = sub_v(cross(r, du_dr), torque_on_b);
    let r_mag = norm(r);
    let e = scale_v(1.0 / r_mag, r);
    let energy = potential(p.g, p.n, &p.tk, &p.a, &p.b, e, r_mag, &p.ta, &tbp);
    Wrench {
        force_on_b: scale_v(-1.0, du_dr),
        torque_on_a,
        torque_on_b,
        energy,
    }
}

/// CPU time of this thread in seconds (Linux: the first field of `/proc/thread-self/schedstat`
/// is the time run, in nanoseconds); NaN where it cannot be read.
fn thread_cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |ns| ns * 1e-9)
}

/// Best wall and best CPU seconds per call over ten batches of at least `batch` CPU seconds
/// (on a shared machine the CPU time is the one to read: wall time counts the waits).
fn time_per_call(batch: f64, mut f: impl FnMut()) -> (f64, f64) {
    // Calls are made in chunks of at least 1 ms, the clocks read between chunks only (a read of
    // /proc costs microseconds, as much as a cheap call).
    let t = Instant::now();
    f();
    let chunk = (1e-3 / t.elapsed().as_secs_f64().max(1e-9)).ceil().min(1e6) as u32;
    let (mut wall, mut cpu) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..10 {
        let (t0, c0) = (Instant::now(), thread_cpu_seconds());
        let mut calls = 0u32;
        // Wall time bounds the batch where the CPU clock cannot be read.
        while calls == 0
            || !(thread_cpu_seconds() - c0 >= batch || t0.elapsed().as_secs_f64() >= 20.0 * batch)
        {
            for _ in 0..chunk {
                f();
            }
            calls += chunk;
        }
        wall = wall.min(t0.elapsed().as_secs_f64() / calls as f64);
        cpu = cpu.min((thread_cpu_seconds() - c0) / calls as f64);
    }
    (wall, cpu)
}

fn diff_norm(a: Vec3, b: Vec3) -> f64 {
    norm(sub_v(a, b))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 4 {
        eprintln!("usage: {} EXACT_CSV GUBAS_EXAMPLE_DIR ORDER...", args[0]);
        std::process::exit(2);
    }
    let rows = read_rows(&args[1]);
    let example = &args[2];
    let orders: Vec<usize> = args[3..]
        .iter()
        .map(|s| s.parse().expect("order: a non-negative integer"))
        .collect();
    println!(
        "config,order,integrals,fbx,fby,fbz,max,may,maz,mbx,mby,mbz,v,\
         force_error,torque_a_error,torque_b_error,energy_error,error,gubas_seconds,gubas_cpu_seconds,surfgrav_seconds,surfgrav_cpu_seconds"
    );
    for row in &rows {
        let g_km = row.num("g") * 1e-9;
        let r_km = row.vec(["px", "py", "pz"]).map(|x| x / 1000.0);
        let c = rotation(row.vec(["rx", "ry", "rz"]));
        let exact_f = row.vec(["fbx", "fby", "fbz"]);
        let exact_ma = row.vec(["max", "may", "maz"]);
        let exact_mb = row.vec(["mbx", "mby", "mbz"]);
        let exact_v = row.num("v");
        let ellipsoids = row.text("kind_a") == "ellipsoid" && row.text("kind_b") == "ellipsoid";
        for &order in &orders {
            let variants: &[bool] = if order > 4 && ellipsoids {
                &[false, true]
            } else {
                &[false]
            };
            for &complete in variants {
                let (ta, ia) = body_cube(row, 'a', order, complete, example);
                let (tb, ib) = body_cube(row, 'b', order, complete, example);
                let p = params(g_km, order, ta, tb, ia, ib);
                let w = evaluate(c, r_km, &p);
                // km, kg, s → SI: force × 1e3, torque and energy × 1e6.
                let f = scale_v(1e3, w.force_on_b);
                let ma = scale_v(1e6, w.torque_on_a);
                let mb = scale_v(1e6, w.torque_on_b);
                let v = w.energy * 1e6;
                // surfgrav's error measure: torques against max(|M|, |V|).
                let force_error = diff_norm(f, exact_f) / norm(exact_f);
                let ta_error = diff_norm(ma, exact_ma) / norm(exact_ma).max(exact_v.abs());
                let tb_error = diff_norm(mb, exact_mb) / norm(exact_mb).max(exact_v.abs());
                let energy_error = (v - exact_v).abs() / exact_v.abs();
                let error = force_error.max(ta_error).max(tb_error).max(energy_error);
                let batch = if order >= 8 { 0.1 } else { 0.05 };
                let (seconds, cpu_seconds) = time_per_call(batch, || {
                    std::hint::black_box(evaluate(
                        std::hint::black_box(c),
                        std::hint::black_box(r_km),
                        &p,
                    ));
                });
                println!(
                    "{},{order},{},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{force_error:.3e},{ta_error:.3e},{tb_error:.3e},{energy_error:.3e},{error:.3e},{seconds:.4e},{cpu_seconds:.4e},{},{}",
                    row.name,
                    if complete { "complete" } else { "shipped" },
                    f[0], f[1], f[2], ma[0], ma[1], ma[2], mb[0], mb[1], mb[2], v,
                    row.text("seconds"),
                    row.text("cpu_seconds"),
                );
                eprintln!(
                    "{} order {order} {}: F {force_error:.2e} M_A {ta_error:.2e} M_B {tb_error:.2e} V {energy_error:.2e}, {:.1} µs CPU (surfgrav {:.1} µs CPU)",
                    row.name,
                    if complete { "complete" } else { "shipped" },
                    cpu_seconds * 1e6,
                    row.num("cpu_seconds") * 1e6
                );
            }
        }
    }
}
