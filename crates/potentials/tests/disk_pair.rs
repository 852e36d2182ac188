//! The coplanar disk–disk closed form against committed high-precision reference values, and the
//! laws it must obey.
//!
//! `tests/reference/disk_pair.json` (workspace root) comes from `tests/reference/disk_pair.py`:
//! 40-digit values of $V$ and $\mathrm dV/\mathrm dr$ by the lens-area convolution (independent of
//! Conway's closed form; cross-checked in the script against the Hankel representation and the
//! far-field series), for equal and unequal radii from touching to $10^8$ radii sums. Inputs are
//! decimal strings of doubles, parsed with `str::parse::<f64>` (correctly rounded).

use std::sync::OnceLock;

use serde_json::Value;
use surfgrav_potentials::tolerance::{DISK_PAIR_REL, FINITE_DIFFERENCE_REL};
use surfgrav_potentials::{
    coplanar_disk_interaction, CoplanarDiskPair, DiskPairError, UniformDisk, Vec3,
};

struct Case {
    label: String,
    radius_a: f64,
    radius_b: f64,
    mass_a: f64,
    mass_b: f64,
    g: f64,
    separation: f64,
    potential_energy: f64,
    dv_dr: f64,
    energy_shape_factor: f64,
    force_shape_factor: f64,
}

fn reference_path() -> String {
    format!(
        "{}/../../tests/reference/disk_pair.json",
        env!("CARGO_MANIFEST_DIR")
    )
}

fn number(case: &Value, key: &str) -> f64 {
    let text = case[key]
        .as_str()
        .unwrap_or_else(|| panic!("{key}: expected a decimal string in {case}"));
    text.parse::<f64>()
        .unwrap_or_else(|e| panic!("{key}: cannot parse {text:?}: {e}"))
}

fn cases() -> &'static [Case] {
    static CASES: OnceLock<Vec<Case>> = OnceLock::new();
    CASES.get_or_init(|| {
        let text = std::fs::read_to_string(reference_path())
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", reference_path()));
        let root: Value = serde_json::from_str(&text).expect("disk_pair.json is not valid JSON");
        root["cases"]
            .as_array()
            .expect("no cases array")
            .iter()
            .map(|c| Case {
                label: c["label"].as_str().expect("label").to_owned(),
                radius_a: number(c, "radius_a"),
                radius_b: number(c, "radius_b"),
                mass_a: number(c, "mass_a"),
                mass_b: number(c, "mass_b"),
                g: number(c, "g"),
                separation: number(c, "separation"),
                potential_energy: number(c, "potential_energy"),
                dv_dr: number(c, "dv_dr"),
                energy_shape_factor: number(c, "energy_shape_factor"),
                force_shape_factor: number(c, "force_shape_factor"),
            })
            .collect()
    })
}

fn disks(case: &Case) -> (UniformDisk, UniformDisk) {
    let a = UniformDisk::new(case.radius_a, case.mass_a)
        .and_then(|d| d.with_gravitational_constant(case.g))
        .unwrap();
    let b = UniformDisk::new(case.radius_b, case.mass_b)
        .and_then(|d| d.with_gravitational_constant(case.g))
        .unwrap();
    (a, b)
}

fn relative(got: f64, want: f64) -> f64 {
    ((got - want) / want).abs()
}

#[test]
fn matches_reference_values() {
    let all = cases();
    assert!(all.len() >= 40, "only {} reference cases", all.len());
    // Worst errors by range of gap / (R_A + R_B).
    let ranges = [
        ("touching", 0.0, 0.0),
        ("gap ≤ 1e-3", 1e-300, 1e-3),
        ("1e-3 < gap ≤ 1", 1e-3, 1.0),
        ("1 < gap ≤ 1e3", 1.0, 1e3),
        ("gap > 1e3", 1e3, f64::INFINITY),
    ];
    let mut worst = vec![(0.0_f64, 0.0_f64, String::new()); ranges.len()];
    let mut failures = Vec::new();
    for case in all {
        let (a, b) = disks(case);
        let got = coplanar_disk_interaction(&a, &b, case.separation)
            .unwrap_or_else(|e| panic!("{}: {e}", case.label));
        let errors = [
            relative(got.potential_energy, case.potential_energy),
            relative(got.radial_force, -case.dv_dr),
            relative(got.energy_shape_factor, case.energy_shape_factor),
            relative(got.force_shape_factor, case.force_shape_factor),
        ];
        let energy_err = errors[0].max(errors[2]);
        let force_err = errors[1].max(errors[3]);
        let contact = case.radius_a + case.radius_b;
        let gap = (case.separation - contact) / contact;
        let slot = ranges
            .iter()
            .position(|&(_, lo, hi)| {
                (gap == 0.0 && hi == 0.0) || (gap >= lo && gap <= hi && hi > 0.0)
            })
            .unwrap();
        if energy_err > worst[slot].0 || force_err > worst[slot].1 {
            worst[slot].2 = case.label.clone();
        }
        worst[slot].0 = worst[slot].0.max(energy_err);
        worst[slot].1 = worst[slot].1.max(force_err);
        if !(energy_err <= DISK_PAIR_REL && force_err <= DISK_PAIR_REL) {
            failures.push(format!(
                "{}: V {:e} vs {:e}, F {:e} vs {:e}, u {:e} vs {:e}, f {:e} vs {:e}: \
                 errors {errors:?}",
                case.label,
                got.potential_energy,
                case.potential_energy,
                got.radial_force,
                -case.dv_dr,
                got.energy_shape_factor,
                case.energy_shape_factor,
                got.force_shape_factor,
                case.force_shape_factor,
            ));
        }
    }
    println!(
        "coplanar disk pair, {} cases, tolerance {DISK_PAIR_REL:.0e}",
        all.len()
    );
    for ((name, _, _), (e, f, label)) in ranges.iter().zip(&worst) {
        println!("{name:<16} V,u {e:9.2e}   F,f {f:9.2e}   worst at {label}");
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// F = −dV/dr by Richardson-extrapolated central differences, from near contact to far away.
#[test]
fn force_is_minus_the_derivative_of_the_energy() {
    for (ra, rb) in [(1.0, 1.0), (1.0, 0.5), (0.3, 2.0), (1.0, 0.01)] {
        let a = UniformDisk::new(ra, 2.0).unwrap();
        let b = UniformDisk::new(rb, 0.7).unwrap();
        let pair = CoplanarDiskPair::new(&a, &b).unwrap();
        let contact = ra + rb;
        for factor in [1.01, 1.05, 1.3, 2.0, 5.0, 30.0, 1000.0] {
            let r = contact * factor;
            let h = 1e-3 * (r - contact).min(r);
            let v = |x: f64| pair.interaction(x).unwrap().potential_energy;
            let d = |h: f64| (v(r + h) - v(r - h)) / (2.0 * h);
            let derivative = (4.0 * d(h / 2.0) - d(h)) / 3.0;
            let force = pair.interaction(r).unwrap().radial_force;
            // Cancellation in the difference quotient: ε |V| / h.
            let scale = force.abs().max(v(r).abs() / r);
            let err = (force + derivative).abs() / scale;
            assert!(
                err < FINITE_DIFFERENCE_REL,
                "radii {ra}, {rb}, r = {r}: F = {force:e}, −dV/dr ≈ {:e}, rel {err:.2e}",
                -derivative
            );
        }
    }
}

#[test]
fn newtons_third_law_and_direction() {
    let a = UniformDisk::new(1.0, 3.0).unwrap();
    let b = UniformDisk::new(0.4, 0.5).unwrap();
    let pair = CoplanarDiskPair::new(&a, &b).unwrap();
    for d in [
        Vec3::new(1.4, 0.0, 0.0),
        Vec3::new(-2.0, 3.0, 0.0),
        Vec3::new(0.0, -7.5, -0.0),
        Vec3::new(1e3, 1e3, 0.0),
    ] {
        let forces = pair.forces(&d).unwrap();
        assert_eq!(forces.force_on_a, -forces.force_on_b);
        let r = d.x.hypot(d.y);
        let scalar = pair.interaction(r).unwrap();
        assert_eq!(forces.interaction, scalar);
        // Attraction: B is pulled toward A, along −d, with the scalar's magnitude.
        let along = forces.force_on_b.dot(&d) / r;
        assert!(along < 0.0);
        assert!(relative(along, scalar.radial_force) < 1e-15);
        assert!(relative(forces.force_on_b.norm(), scalar.radial_force.abs()) < 1e-15);
        assert_eq!(forces.force_on_b.z, 0.0);
    }
}

#[test]
fn symmetric_in_the_two_disks_and_linear_in_g_and_masses() {
    let a = UniformDisk::new(1.3, 2.0).unwrap();
    let b = UniformDisk::new(0.2, 5.0).unwrap();
    let r = 2.7;
    let ab = coplanar_disk_interaction(&a, &b, r).unwrap();
    let ba = coplanar_disk_interaction(&b, &a, r).unwrap();
    assert_eq!(ab, ba);
    let g = 6.674_30e-11;
    let a_si = UniformDisk::new(1.3, 4.0)
        .unwrap()
        .with_gravitational_constant(g)
        .unwrap();
    let b_si = b.with_gravitational_constant(g).unwrap();
    let scaled = coplanar_disk_interaction(&a_si, &b_si, r).unwrap();
    assert!(relative(scaled.potential_energy, 2.0 * g * ab.potential_energy) < 4e-16);
    assert!(relative(scaled.radial_force, 2.0 * g * ab.radial_force) < 4e-16);
    assert_eq!(scaled.energy_shape_factor, ab.energy_shape_factor);
}

/// u = 1 + (R_A² + R_B²)/(8r²) + O(r⁻⁴) and f = 1 + 3(R_A² + R_B²)/(8r²) + O(r⁻⁴) (from
/// f = u − r du/dr); the next terms are below 1e-14 relative at r = 1e4.
#[test]
fn tends_to_point_masses_with_the_quadrupole_correction() {
    let (ra, rb) = (1.0, 0.6);
    let a = UniformDisk::new(ra, 1.0).unwrap();
    let b = UniformDisk::new(rb, 1.0).unwrap();
    for r in [1e4, 1e5, 1e8] {
        let i = coplanar_disk_interaction(&a, &b, r).unwrap();
        let q = (ra * ra + rb * rb) / (8.0 * r * r);
        assert!(relative(i.energy_shape_factor, 1.0 + q) < DISK_PAIR_REL);
        assert!(relative(i.force_shape_factor, 1.0 + 3.0 * q) < DISK_PAIR_REL);
        assert!(relative(i.potential_energy, -(1.0 + q) / r) < DISK_PAIR_REL);
        assert!(relative(i.radial_force, -(1.0 + 3.0 * q) / (r * r)) < DISK_PAIR_REL);
    }
}

/// Touching is allowed and continuous with the nearly touching pair; overlap, non-finite
/// separations, out-of-plane vectors and mixed G are errors.
#[test]
fn domain_and_errors() {
    let a = UniformDisk::new(1.0, 1.0).unwrap();
    let b = UniformDisk::new(0.5, 1.0).unwrap();
    let pair = CoplanarDiskPair::new(&a, &b).unwrap();
    assert_eq!(pair.contact_separation(), 1.5);
    let touching = pair.interaction(1.5).unwrap();
    let near = pair.interaction(1.5 + 1e-12).unwrap();
    assert!(touching.potential_energy.is_finite() && touching.radial_force.is_finite());
    assert!(relative(touching.potential_energy, near.potential_energy) < 1e-11);
    assert!(relative(touching.radial_force, near.radial_force) < 1e-10);

    assert!(matches!(
        pair.interaction(1.4999),
        Err(DiskPairError::Overlap { .. })
    ));
    assert!(matches!(
        pair.interaction(0.0),
        Err(DiskPairError::Overlap { .. })
    ));
    for bad in [f64::NAN, f64::INFINITY, -1.0] {
        assert!(matches!(
            pair.interaction(bad),
            Err(DiskPairError::InvalidSeparation { .. })
        ));
    }
    assert!(matches!(
        pair.forces(&Vec3::new(3.0, 0.0, 1e-30)),
        Err(DiskPairError::NotCoplanar { .. })
    ));
    assert!(matches!(
        pair.forces(&Vec3::new(3.0, f64::NAN, 0.0)),
        Err(DiskPairError::InvalidSeparation { .. })
    ));
    assert!(matches!(
        pair.forces(&Vec3::new(1.0, 0.0, 0.0)),
        Err(DiskPairError::Overlap { .. })
    ));
    let other_g = b.with_gravitational_constant(2.0).unwrap();
    assert!(matches!(
        CoplanarDiskPair::new(&a, &other_g),
        Err(DiskPairError::GravitationalConstantMismatch { .. })
    ));
    let err = coplanar_disk_interaction(&a, &other_g, 3.0).unwrap_err();
    assert!(err.to_string().contains("same G"));
}
