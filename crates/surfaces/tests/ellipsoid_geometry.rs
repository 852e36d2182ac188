//! Geometric identities of the surfaces and their node tables: the area vector is the outward
//! cross product of the partial derivatives, ∮ dS = 0, ⅓∮ r·dS is the volume, Σ|W| is the area.

mod common;

use common::tolerance::{FINITE_DIFFERENCE_REL, POTENTIAL_REL};
use common::{gauss_legendre, rel, trapezoid, SplitMix, Vec3};
use std::f64::consts::PI;
use surfgrav_surfaces::{
    EllipsoidSurface, Interval, NodeTableError, ParameterDomain, Periodicity, Surface, SurfaceNodes,
};

/// A torus (major radius `major`, tube radius `minor`): a closed surface periodic in both
/// directions, to exercise the trait through `dyn Surface`.
#[derive(Debug)]
struct Torus {
    major: f64,
    minor: f64,
}

impl Surface for Torus {
    fn parameter_domain(&self) -> ParameterDomain {
        ParameterDomain {
            u: Interval::FULL_TURN,
            v: Interval::FULL_TURN,
            periodicity: Periodicity::Both,
        }
    }
    fn point(&self, u: f64, v: f64) -> Vec3 {
        let w = self.major + self.minor * v.cos();
        Vec3::new(w * u.cos(), w * u.sin(), self.minor * v.sin())
    }
    fn area_vector(&self, u: f64, v: f64) -> Vec3 {
        let w = self.major + self.minor * v.cos();
        Vec3::new(v.cos() * u.cos(), v.cos() * u.sin(), v.sin()) * (w * self.minor)
    }
    fn enclosed_volume(&self) -> Option<f64> {
        Some(2.0 * PI * PI * self.major * self.minor * self.minor)
    }
    fn surface_area(&self) -> Option<f64> {
        Some(4.0 * PI * PI * self.major * self.minor)
    }
    fn bounding_radius(&self) -> f64 {
        self.major + self.minor
    }
}

/// The two parametrisations of an ellipsoid, as trait objects.
fn both_forms(e: &EllipsoidSurface) -> [Box<dyn Surface>; 2] {
    [Box::new(e.azimuth_height()), Box::new(e.polar_azimuth())]
}

fn random_ellipsoid(rng: &mut SplitMix) -> EllipsoidSurface {
    EllipsoidSurface::new(
        rng.uniform(0.1, 3.0),
        rng.uniform(0.1, 3.0),
        rng.uniform(0.1, 3.0),
    )
    .unwrap()
}

/// A table with `n_periodic` trapezoid nodes in the periodic direction and `n_transverse`
/// Gauss–Legendre nodes in the other.
fn table(surface: &dyn Surface, n_periodic: usize, n_transverse: usize) -> SurfaceNodes {
    let p = trapezoid(n_periodic);
    let t = gauss_legendre(n_transverse);
    SurfaceNodes::with_periodic_rule(surface, p.rule(), t.rule()).unwrap()
}

/// Central difference with one Richardson step, error O(h⁴).
fn derivative(f: impl Fn(f64) -> Vec3, x: f64, h: f64) -> Vec3 {
    let d = |h: f64| (f(x + h) - f(x - h)) / (2.0 * h);
    (d(h / 2.0) * 4.0 - d(h)) / 3.0
}

#[test]
fn area_vector_is_the_outward_cross_product_of_the_partials() {
    let mut rng = SplitMix(11);
    for _ in 0..20 {
        let e = random_ellipsoid(&mut rng);
        let axes = e.semi_axes();
        for surface in both_forms(&e) {
            let domain = surface.parameter_domain();
            for _ in 0..20 {
                // Interior parameters, away from the poles where ∂r/∂z is infinite.
                let pick = |i: Interval, rng: &mut SplitMix| {
                    let m = 0.1 * i.length();
                    rng.uniform(i.start() + m, i.end() - m)
                };
                let (u, v) = (pick(domain.u, &mut rng), pick(domain.v, &mut rng));
                let (r, s) = surface.point_and_area_vector(u, v);
                assert_eq!(r, surface.point(u, v));
                assert_eq!(s, surface.area_vector(u, v));
                // On the surface.
                let level = r.component_div(&axes).norm_squared();
                assert!((level - 1.0).abs() < POTENTIAL_REL, "{level}");
                // Equal to ∂u r × ∂v r.
                let r_u = derivative(|x| surface.point(x, v), u, 1e-4 * domain.u.length());
                let r_v = derivative(|x| surface.point(u, x), v, 1e-4 * domain.v.length());
                let cross = r_u.cross(&r_v);
                assert!(
                    (cross - s).norm() < FINITE_DIFFERENCE_REL * s.norm(),
                    "{surface:?} at ({u}, {v}): {s} vs {cross}"
                );
                // Along the outward normal ∇(Σ x²/a²) and pointing the same way.
                let gradient = r.component_div(&axes.component_mul(&axes));
                assert!(s.dot(&gradient) > 0.0);
                assert!(s.cross(&gradient).norm() < POTENTIAL_REL * s.norm() * gradient.norm());
            }
        }
    }
}

#[test]
fn closed_surface_integral_of_area_vectors_vanishes() {
    let mut rng = SplitMix(12);
    for _ in 0..50 {
        let e = random_ellipsoid(&mut rng);
        for surface in both_forms(&e) {
            // Odd and even sizes; the identity holds for any rule symmetric enough to integrate
            // cos φ, sin φ and odd functions of z exactly.
            for (np, nt) in [(3, 2), (16, 9), (41, 30)] {
                let nodes = table(&*surface, np, nt);
                let sum = nodes.total_area_vector();
                assert!(
                    sum.norm() < POTENTIAL_REL * e.surface_area(),
                    "{surface:?} ({np}, {nt}): {sum}"
                );
            }
        }
    }
}

#[test]
fn one_third_of_the_flux_of_r_is_the_volume() {
    let mut rng = SplitMix(13);
    for _ in 0..50 {
        let e = random_ellipsoid(&mut rng);
        let exact = 4.0 / 3.0 * PI * e.x_semi_axis() * e.y_semi_axis() * e.z_semi_axis();
        assert!(rel(e.volume(), exact) < POTENTIAL_REL);
        // Azimuth–height: r·S = ab exactly, so any rule gives the volume.
        let h = e.azimuth_height();
        assert_eq!(h.enclosed_volume(), Some(e.volume()));
        for (np, nt) in [(1, 1), (3, 2), (16, 9)] {
            let v = table(&h, np, nt).enclosed_volume();
            assert!(
                rel(v, exact) < POTENTIAL_REL,
                "({np}, {nt}): {v} vs {exact}"
            );
        }
        // Polar angle: r·S = abc sin θ, integrated by Gauss–Legendre in θ.
        let p = e.polar_azimuth();
        let v = table(&p, 4, 16).enclosed_volume();
        assert!(rel(v, exact) < POTENTIAL_REL, "{v} vs {exact}");
    }
}

/// Textbook surface areas: sphere 4πR²; oblate (c < a) 2πa²[1 + (1 − e²) artanh(e)/e];
/// prolate (c > a) 2πa²[1 + c arcsin(e)/(a e)], e the eccentricity. For needles and pancakes
/// (e → 1) arcsin and artanh are ill-conditioned in e, so they are evaluated as
/// arcsin e = atan2(√(c² − a²), a) and, for e ≥ 1/2, artanh e = ln((1 + e) a/c).
fn spheroid_area(equatorial: f64, polar: f64) -> f64 {
    let (a, c) = (equatorial, polar);
    if a == c {
        4.0 * PI * a * a
    } else if c < a {
        let e = ((a - c) * (a + c)).sqrt() / a;
        let artanh = if e < 0.5 {
            e.atanh()
        } else {
            ((1.0 + e) * (a / c)).ln()
        };
        2.0 * PI * a * a * (1.0 + (c / a) * (c / a) * artanh / e)
    } else {
        let root = ((c - a) * (c + a)).sqrt();
        let e = root / c;
        2.0 * PI * a * a * (1.0 + c * root.atan2(a) / (a * e))
    }
}

#[test]
fn surface_areas_match_closed_forms() {
    let mut rng = SplitMix(14);
    // Closed form of `Ellipsoid` (Carlson R_G) against the textbook spheroid formulas.
    let mut shapes = vec![
        (1.0, 1.0),
        (1.0, 0.25),
        (0.25, 1.0),
        (1.0, 0.999),
        (3.0, 1e-3),
        (0.999, 1.0),
        (1.0, 1e-4),
        (1e-4, 1.0),
        (1.0, 1e4),
    ];
    for _ in 0..40 {
        shapes.push((rng.uniform(0.05, 4.0), rng.uniform(0.05, 4.0)));
    }
    for &(a, c) in &shapes {
        let e = EllipsoidSurface::spheroid(a, c).unwrap();
        let exact = spheroid_area(a, c);
        assert!(
            rel(e.surface_area(), exact) < POTENTIAL_REL,
            "({a}, {c}): {} vs {exact}",
            e.surface_area()
        );
    }
    let sphere = EllipsoidSurface::sphere(2.5).unwrap();
    assert!(rel(sphere.surface_area(), 25.0 * PI) < POTENTIAL_REL);
    // Node tables (Σ |W_k|) against the closed forms: spheres, spheroids, and triaxial shapes
    // against R_G. Rules large enough for the flattest shape drawn (c/a ≥ 1/4).
    let mut triaxial = vec![(1.0, 1.0, 1.0), (1.0, 1.0, 0.25), (0.25, 0.25, 1.0)];
    for _ in 0..10 {
        triaxial.push((
            rng.uniform(1.0, 2.0),
            rng.uniform(0.5, 1.0),
            rng.uniform(0.5, 1.0),
        ));
    }
    for (a, b, c) in triaxial {
        let e = EllipsoidSurface::new(a, b, c).unwrap();
        for surface in both_forms(&e) {
            let area = table(&*surface, 96, 96).area();
            assert_eq!(surface.surface_area(), Some(e.surface_area()));
            assert!(
                rel(area, e.surface_area()) < POTENTIAL_REL,
                "{surface:?}: {area} vs {}",
                e.surface_area()
            );
        }
    }
}

#[test]
fn domains_periodicity_and_rule_roles() {
    let e = EllipsoidSurface::new(1.5, 1.0, 0.5).unwrap();
    let h = e.azimuth_height();
    let p = e.polar_azimuth();
    assert_eq!(h.parameter_domain().periodicity, Periodicity::U);
    assert_eq!(h.parameter_domain().u, Interval::FULL_TURN);
    assert_eq!(h.parameter_domain().v, Interval::new(-0.5, 0.5).unwrap());
    assert_eq!(p.parameter_domain().periodicity, Periodicity::V);
    assert_eq!(p.parameter_domain().u, Interval::new(0.0, PI).unwrap());
    assert_eq!(h.bounding_radius(), 1.5);
    // `with_periodic_rule` puts the trapezoid rule on the periodic direction whichever it is.
    let (tp, gl) = (trapezoid(7), gauss_legendre(5));
    let by_role = SurfaceNodes::with_periodic_rule(&p, tp.rule(), gl.rule()).unwrap();
    let explicit = SurfaceNodes::new(&p, gl.rule(), tp.rule()).unwrap();
    assert_eq!(by_role, explicit);
    assert_eq!(by_role.rule_sizes(), (5, 7));
    assert_eq!(by_role.len(), 35);
    // Node ordering k = j n_u + i.
    let gl_mapped: Vec<(f64, f64)> = gl.rule().mapped_to(p.parameter_domain().u).collect();
    let k = 3 * 5 + 2;
    let phi = 2.0 * PI * 3.0 / 7.0;
    assert_eq!(by_role.points()[k], p.point(gl_mapped[2].0, phi));
    // A torus is periodic in both directions: the role-based builder refuses it.
    let torus = Torus {
        major: 2.0,
        minor: 0.5,
    };
    assert_eq!(
        SurfaceNodes::with_periodic_rule(&torus, tp.rule(), gl.rule()),
        Err(NodeTableError::NotSinglyPeriodic {
            periodicity: Periodicity::Both
        })
    );
}

#[test]
fn identities_hold_for_a_user_surface_through_dyn() {
    // The same identities for a torus given as `Box<dyn Surface>`, with trapezoid rules in both
    // periodic directions: the tables are generic over `?Sized` surfaces.
    let torus: Box<dyn Surface> = Box::new(Torus {
        major: 2.0,
        minor: 0.5,
    });
    let (tu, tv) = (trapezoid(24), trapezoid(17));
    let nodes = SurfaceNodes::new(&*torus, tu.rule(), tv.rule()).unwrap();
    let area = torus.surface_area().unwrap();
    let sum = nodes.total_area_vector();
    assert!(sum.norm() < POTENTIAL_REL * area);
    assert!(rel(nodes.enclosed_volume(), torus.enclosed_volume().unwrap()) < POTENTIAL_REL);
    assert!(rel(nodes.area(), area) < POTENTIAL_REL);
}
