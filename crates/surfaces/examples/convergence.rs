//! Work–precision study of the two ellipsoid parametrisations, and node-table build timings.
//!
//! Run with `cargo run --release -p surfgrav-surfaces --example convergence`.
//!
//! For each integrand it prints the relative error against an independent reference as the
//! number of nodes grows in one direction (the other direction converged), and the smallest
//! (periodic, transverse) node counts that keep the relative error below the target. Rules:
//! periodic trapezoid in azimuth, Gauss–Legendre in height z or in polar angle θ.

#[path = "../tests/common/mod.rs"]
mod common;

use common::{gauss_legendre, inverse_distance_flux, trapezoid, Vec3};
use nalgebra::Rotation3;
use std::hint::black_box;
use std::time::Instant;
use surfgrav_surfaces::{EllipsoidSurface, Surface, SurfaceNodes};

const TARGET: f64 = 1e-12;
/// Node count converged in either direction for every integrand below.
const CONVERGED: usize = 400;
/// A count "meets the target" only if the next `STABLE` counts do too (guards against lucky
/// zero crossings of the error).
const STABLE: usize = 8;

#[derive(Clone, Copy, Debug)]
enum Integrand {
    /// ∮ dS / |r − r0|; reference: the exterior attraction of a homogeneous ellipsoid.
    InverseDistance(Vec3),
    /// ⅓∮ r·dS against 4/3 π abc.
    Volume,
    /// Σ|W| against 4π abc R_G.
    Area,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Form {
    AzimuthHeight,
    PolarAzimuth,
}

struct Case {
    ellipsoid: EllipsoidSurface,
    form: Form,
    integrand: Integrand,
    reference: Vec3,
}

impl Case {
    fn new(ellipsoid: EllipsoidSurface, form: Form, integrand: Integrand) -> Self {
        let reference = match integrand {
            Integrand::InverseDistance(r0) => {
                let fine = inverse_distance_flux(&ellipsoid.semi_axes(), &r0, 600);
                let coarse = inverse_distance_flux(&ellipsoid.semi_axes(), &r0, 300);
                let spread = (fine - coarse).norm() / fine.norm();
                assert!(spread < 1e-14, "reference not converged: {spread:e}");
                fine
            }
            Integrand::Volume => Vec3::new(ellipsoid.volume(), 0.0, 0.0),
            Integrand::Area => Vec3::new(ellipsoid.surface_area(), 0.0, 0.0),
        };
        Self {
            ellipsoid,
            form,
            integrand,
            reference,
        }
    }

    fn surface(&self) -> Box<dyn Surface> {
        match self.form {
            Form::AzimuthHeight => Box::new(self.ellipsoid.azimuth_height()),
            Form::PolarAzimuth => Box::new(self.ellipsoid.polar_azimuth()),
        }
    }

    fn error(&self, n_periodic: usize, n_transverse: usize) -> f64 {
        let surface = self.surface();
        let p = trapezoid(n_periodic);
        let t = gauss_legendre(n_transverse);
        let nodes = SurfaceNodes::with_periodic_rule(&*surface, p.rule(), t.rule()).unwrap();
        let value = match self.integrand {
            Integrand::InverseDistance(r0) => nodes.integrate(|r| 1.0 / (r - r0).norm()),
            Integrand::Volume => Vec3::new(nodes.enclosed_volume(), 0.0, 0.0),
            Integrand::Area => Vec3::new(nodes.area(), 0.0, 0.0),
        };
        (value - self.reference).norm() / self.reference.norm()
    }

    /// Smallest n in the chosen direction with the error below TARGET for n .. n + STABLE.
    fn minimal(&self, periodic: bool, other: usize) -> Option<usize> {
        let err = |n: usize| {
            if periodic {
                self.error(n, other)
            } else {
                self.error(other, n)
            }
        };
        let mut run = 0;
        for n in 1..=CONVERGED {
            if err(n) <= TARGET {
                run += 1;
                if run > STABLE {
                    return Some(n - STABLE);
                }
            } else {
                run = 0;
            }
        }
        None
    }
}

fn describe(i: Integrand) -> String {
    match i {
        Integrand::InverseDistance(r0) => format!(
            "∮dS/|r−r0|, |r0| = {:.1}, dir ({:.2},{:.2},{:.2})",
            r0.norm(),
            r0.x / r0.norm(),
            r0.y / r0.norm(),
            r0.z / r0.norm()
        ),
        Integrand::Volume => "volume ⅓∮r·dS".to_string(),
        Integrand::Area => "area Σ|W|".to_string(),
    }
}

fn main() {
    let shapes = [
        (
            "oblate a=b=1, c=0.25",
            EllipsoidSurface::spheroid(1.0, 0.25).unwrap(),
        ),
        (
            "triaxial 1, 0.6, 0.25",
            EllipsoidSurface::new(1.0, 0.6, 0.25).unwrap(),
        ),
        (
            "prolate a=b=0.25, c=1",
            EllipsoidSurface::spheroid(0.25, 1.0).unwrap(),
        ),
    ];
    let sweep = [4, 8, 12, 16, 20, 24, 32, 40, 48, 64, 96, 128];
    println!("target relative error {TARGET:e}; other direction at {CONVERGED} nodes\n");
    for (name, e) in shapes {
        let mut integrands = vec![Integrand::Volume, Integrand::Area];
        let directions = [
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 1.0).normalize(),
            Vec3::new(0.0, 0.0, 1.0),
        ];
        for d in [2.1, 3.0, 7.0] {
            for dir in directions {
                integrands.push(Integrand::InverseDistance(dir * d));
            }
        }
        println!("=== {name} ===");
        println!(
            "{:<46} {:<14} {:>9} {:>9} {:>6} {:>10}",
            "integrand", "form", "periodic", "transv.", "nodes", "error"
        );
        for integrand in &integrands {
            for form in [Form::AzimuthHeight, Form::PolarAzimuth] {
                let case = Case::new(e, form, *integrand);
                let np = case.minimal(true, CONVERGED);
                let nt = case.minimal(false, CONVERGED);
                match (np, nt) {
                    (Some(mut np), Some(mut nt)) => {
                        // Both directions at their minimum may add up above the target.
                        while case.error(np, nt) > TARGET {
                            np += 1;
                            nt += 1;
                        }
                        println!(
                            "{:<46} {:<14} {:>9} {:>9} {:>6} {:>10.1e}",
                            describe(*integrand),
                            format!("{form:?}"),
                            np,
                            nt,
                            np * nt,
                            case.error(np, nt)
                        );
                    }
                    _ => println!("{:<46} {:?}: not reached", describe(*integrand), form),
                }
            }
        }
        // Error sweeps for the hardest point (equatorial, d = 2.1) and the area.
        for integrand in [
            Integrand::InverseDistance(Vec3::new(2.1, 0.0, 0.0)),
            Integrand::Area,
        ] {
            println!("\nsweep, {}:", describe(integrand));
            println!(
                "{:>5} {:>12} {:>12} {:>12} {:>12} {:>12}",
                "n", "AH transv.", "AH tr. odd P", "PA transv.", "AH periodic", "PA periodic"
            );
            let ah = Case::new(e, Form::AzimuthHeight, integrand);
            let pa = Case::new(e, Form::PolarAzimuth, integrand);
            for n in sweep {
                println!(
                    "{:>5} {:>12.2e} {:>12.2e} {:>12.2e} {:>12.2e} {:>12.2e}",
                    n,
                    ah.error(CONVERGED, n),
                    ah.error(CONVERGED + 1, n),
                    pa.error(CONVERGED, n),
                    ah.error(n, CONVERGED),
                    pa.error(n, CONVERGED)
                );
            }
        }
        println!();
    }

    // Timings: building a table and moving it into another frame.
    println!("=== timings (oblate a=1, c=0.25) ===");
    println!(
        "{:>9} {:>9} {:>8} {:>14} {:>14} {:>14}",
        "periodic", "transv.", "nodes", "build AH [µs]", "build PA [µs]", "transform [µs]"
    );
    let e = EllipsoidSurface::spheroid(1.0, 0.25).unwrap();
    let ah = e.azimuth_height();
    let pa = e.polar_azimuth();
    let rotation = Rotation3::from_scaled_axis(Vec3::new(0.3, -0.2, 0.9));
    let offset = Vec3::new(3.0, 1.0, -0.5);
    for (np, nt) in [(16, 16), (32, 24), (64, 32), (128, 64), (256, 128)] {
        let p = trapezoid(np);
        let t = gauss_legendre(nt);
        let reps = (2_000_000 / (np * nt)).max(5);
        let time = |f: &mut dyn FnMut()| {
            f();
            let start = Instant::now();
            for _ in 0..reps {
                f();
            }
            start.elapsed().as_secs_f64() / reps as f64 * 1e6
        };
        let build_ah = time(&mut || {
            black_box(SurfaceNodes::with_periodic_rule(&ah, p.rule(), t.rule()).unwrap());
        });
        let build_pa = time(&mut || {
            black_box(SurfaceNodes::with_periodic_rule(&pa, p.rule(), t.rule()).unwrap());
        });
        let table = SurfaceNodes::with_periodic_rule(&ah, p.rule(), t.rule()).unwrap();
        let mut moved = table.transformed(&rotation, &offset).unwrap();
        let transform = time(&mut || {
            table
                .transform_into(black_box(&rotation), &offset, &mut moved)
                .unwrap();
            black_box(&moved);
        });
        println!(
            "{:>9} {:>9} {:>8} {:>14.2} {:>14.2} {:>14.2}",
            np,
            nt,
            np * nt,
            build_ah,
            build_pa,
            transform
        );
    }
}
