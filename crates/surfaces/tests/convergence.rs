//! Snapshot of the node counts each parametrisation needs (work–precision, see the
//! `convergence` example for the full study). A change in these counts means the geometry or
//! the node placement changed: look before updating the snapshot.

mod common;

use common::tolerance::ACCELERATION_REL;
use common::{gauss_legendre, inverse_distance_flux, rel_vec, trapezoid, Vec3};
use surfgrav_surfaces::{EllipsoidSurface, Surface, SurfaceNodes};

/// Converged count in the direction not being studied (the sweeps of the example converge by 48).
const CONVERGED: usize = 128;

/// Relative error of ∮ f dS (f = 1/|r − r0|) or of the area, with the given counts.
fn error(surface: &dyn Surface, r0: Option<Vec3>, reference: &Vec3, np: usize, nt: usize) -> f64 {
    let (p, t) = (trapezoid(np), gauss_legendre(nt));
    let nodes = SurfaceNodes::with_periodic_rule(surface, p.rule(), t.rule()).unwrap();
    let value = match r0 {
        Some(r0) => nodes.integrate(|r| 1.0 / (r - r0).norm()),
        None => Vec3::new(nodes.area(), 0.0, 0.0),
    };
    rel_vec(&value, reference)
}

/// Smallest count (in the periodic direction if `periodic`) from which the error stays below
/// ACCELERATION_REL for eight more counts.
fn minimal(surface: &dyn Surface, r0: Option<Vec3>, reference: &Vec3, periodic: bool) -> usize {
    let err = |n| {
        if periodic {
            error(surface, r0, reference, n, CONVERGED)
        } else {
            error(surface, r0, reference, CONVERGED, n)
        }
    };
    let mut run = 0;
    for n in 1..=CONVERGED {
        if err(n) <= ACCELERATION_REL {
            run += 1;
            if run > 8 {
                return n - 8;
            }
        } else {
            run = 0;
        }
    }
    panic!("not converged by {CONVERGED} nodes");
}

#[test]
fn node_counts_for_the_paper_shape_snapshot() {
    // Oblate spheroid a = 1, c = 0.25; source on the equator at 2.1 and 7 radii; the area.
    let e = EllipsoidSurface::spheroid(1.0, 0.25).unwrap();
    let (height, polar) = (e.azimuth_height(), e.polar_azimuth());
    let mut found = Vec::new();
    for d in [2.1, 7.0] {
        let r0 = Vec3::new(d, 0.0, 0.0);
        let reference = inverse_distance_flux(&e.semi_axes(), &r0, 300);
        let counts = [
            minimal(&height, Some(r0), &reference, true),
            minimal(&height, Some(r0), &reference, false),
            minimal(&polar, Some(r0), &reference, false),
        ];
        found.push(counts);
    }
    let area = Vec3::new(e.surface_area(), 0.0, 0.0);
    found.push([
        minimal(&height, None, &area, true),
        minimal(&height, None, &area, false),
        minimal(&polar, None, &area, false),
    ]);
    // [azimuth nodes, height nodes (azimuth–height form), polar-angle nodes (polar form)]
    let snapshot = [[39, 13, 22], [17, 7, 14], [1, 47, 74]];
    assert_eq!(found, snapshot);
    // The paper's form needs fewer transverse nodes than the smooth one in every case.
    assert!(found.iter().all(|[_, h, p]| h < p));
}
