//! Moving a node table into another frame equals building it in that frame.

mod common;

use common::tolerance::{ACCELERATION_REL, POTENTIAL_REL};
use common::{gauss_legendre, inverse_distance_flux, rel, rel_vec, trapezoid, SplitMix, Vec3};
use nalgebra::Rotation3;
use std::f64::consts::FRAC_PI_2;
use surfgrav_surfaces::{EllipsoidSurface, NodeTableError, SurfaceNodes};

fn height_table(e: &EllipsoidSurface) -> SurfaceNodes {
    let (p, h) = (trapezoid(64), gauss_legendre(24));
    SurfaceNodes::with_periodic_rule(&e.azimuth_height(), p.rule(), h.rule()).unwrap()
}

fn polar_table(e: &EllipsoidSurface) -> SurfaceNodes {
    let (p, t) = (trapezoid(64), gauss_legendre(40));
    SurfaceNodes::with_periodic_rule(&e.polar_azimuth(), p.rule(), t.rule()).unwrap()
}

#[test]
fn rotated_table_integrates_like_the_rotated_shape_built_directly() {
    // Rotations that permute the axes map the ellipsoid (a, b, c) onto another axis-aligned
    // ellipsoid: +90° about x sends (x, y, z) to (x, −z, y), giving semi-axes (a, c, b); the
    // 120° turn about (1, 1, 1) sends (x, y, z) to (z, x, y), giving (c, a, b) with the original
    // poles on the x axis. The moved table and the table built for the image shape use
    // different nodes on the same surface, so their integrals agree only if the points and the
    // area vectors were both moved correctly.
    let (a, b, c) = (1.3, 0.8, 0.45);
    let e = EllipsoidSurface::new(a, b, c).unwrap();
    let cases = [
        (
            Rotation3::from_axis_angle(&Vec3::x_axis(), FRAC_PI_2),
            EllipsoidSurface::new(a, c, b).unwrap(),
        ),
        (
            Rotation3::from_scaled_axis(
                Vec3::new(1.0, 1.0, 1.0).normalize() * (2.0 * std::f64::consts::PI / 3.0),
            ),
            EllipsoidSurface::new(c, a, b).unwrap(),
        ),
    ];
    let offset = Vec3::new(0.4, -2.0, 1.1);
    let mut rng = SplitMix(31);
    for (rotation, image) in cases {
        // The rotation really maps the axes as claimed.
        let m = rotation.matrix();
        for (i, row) in m.row_iter().enumerate() {
            assert!(row.iter().filter(|x| x.abs() > 0.5).count() == 1, "row {i}");
        }
        for original in [height_table(&e), polar_table(&e)] {
            let moved = original.transformed(&rotation, &offset).unwrap();
            let direct = polar_table(&image)
                .transformed(&Rotation3::identity(), &offset)
                .unwrap();
            assert!((moved.origin() - offset).norm() < POTENTIAL_REL);
            assert!(rel(moved.enclosed_volume(), e.volume()) < POTENTIAL_REL);
            assert!(rel(moved.area(), original.area()) < POTENTIAL_REL);
            assert!(moved.total_area_vector().norm() < POTENTIAL_REL * e.surface_area());
            for _ in 0..10 {
                let r0 = offset + rng.unit_vector() * rng.uniform(2.1, 6.0) * a;
                let f = |r: &Vec3| 1.0 / (r - r0).norm();
                let (fm, fd) = (moved.integrate(f), direct.integrate(f));
                assert!(rel_vec(&fm, &fd) < ACCELERATION_REL, "{fm} vs {fd}");
                let g = |r: &Vec3| (r - r0).norm_squared().recip();
                let (mm, md) = (moved.integrate_moment(g), direct.integrate_moment(g));
                assert!(rel_vec(&mm, &md) < ACCELERATION_REL, "{mm} vs {md}");
            }
        }
    }
}

#[test]
fn random_rotation_reproduces_the_exact_flux_in_the_new_frame() {
    // In the new frame the source sits at R r0 + t and the flux is R times the body-frame one.
    let mut rng = SplitMix(32);
    for _ in 0..20 {
        let e = EllipsoidSurface::new(
            rng.uniform(0.3, 1.5),
            rng.uniform(0.3, 1.5),
            rng.uniform(0.3, 1.5),
        )
        .unwrap();
        let rotation = rng.rotation();
        let offset = rng.unit_vector() * rng.uniform(0.0, 10.0);
        let r0 = rng.unit_vector() * e.bounding_radius() * rng.uniform(2.1, 8.0);
        let exact = rotation * inverse_distance_flux(&e.semi_axes(), &r0, 200);
        let source = rotation * r0 + offset;
        for table in [height_table(&e), polar_table(&e)] {
            let moved = table.transformed(&rotation, &offset).unwrap();
            let flux = moved.integrate(|r| 1.0 / (r - source).norm());
            assert!(
                rel_vec(&flux, &exact) < ACCELERATION_REL,
                "{flux} vs {exact}"
            );
        }
    }
}

#[test]
fn node_by_node_transformation_composition_and_buffer_reuse() {
    let mut rng = SplitMix(33);
    let e = EllipsoidSurface::new(1.0, 0.6, 0.3).unwrap();
    let table = height_table(&e);
    let (r1, t1) = (rng.rotation(), Vec3::new(1.0, 2.0, 3.0));
    let (r2, t2) = (rng.rotation(), Vec3::new(-0.5, 0.1, 4.0));
    let once = table.transformed(&r1, &t1).unwrap();
    assert_eq!(once.len(), table.len());
    assert_eq!(once.rule_sizes(), table.rule_sizes());
    for ((p, w), (q, v)) in table.iter().zip(once.iter()) {
        assert!((r1 * p + t1 - q).norm() < POTENTIAL_REL * t1.norm());
        assert!(rel(v.norm(), w.norm()) < POTENTIAL_REL);
    }
    // Composition: (R2, t2) ∘ (R1, t1) = (R2 R1, R2 t1 + t2).
    let twice = once.transformed(&r2, &t2).unwrap();
    let composed = table.transformed(&(r2 * r1), &(r2 * t1 + t2)).unwrap();
    let scale = (r2 * t1 + t2).norm();
    for ((p, w), (q, v)) in twice.iter().zip(composed.iter()) {
        assert!((p - q).norm() < POTENTIAL_REL * scale);
        assert!((w - v).norm() < POTENTIAL_REL * w.norm());
    }
    assert!(rel(twice.enclosed_volume(), e.volume()) < POTENTIAL_REL);
    // transform_into gives the same table and, once sized, does not reallocate.
    let mut out = table
        .transformed(&Rotation3::identity(), &Vec3::zeros())
        .unwrap();
    assert_eq!(out, table);
    let (points_ptr, areas_ptr) = (out.points().as_ptr(), out.weighted_area_vectors().as_ptr());
    table.transform_into(&r1, &t1, &mut out).unwrap();
    assert_eq!(out, once);
    assert_eq!(out.points().as_ptr(), points_ptr);
    assert_eq!(out.weighted_area_vectors().as_ptr(), areas_ptr);
    // Non-finite transforms are refused and leave the output untouched.
    let before = out.clone();
    assert_eq!(
        table.transform_into(&r1, &Vec3::new(f64::NAN, 0.0, 0.0), &mut out),
        Err(NodeTableError::NonFiniteTransform)
    );
    let bad = Rotation3::from_matrix_unchecked(r1.matrix() * f64::INFINITY);
    assert_eq!(
        table.transformed(&bad, &t1),
        Err(NodeTableError::NonFiniteTransform)
    );
    assert_eq!(out, before);
}
