//! The local expansion (`Polyhedron::local_expansion`) against the direct Werner–Scheeres sum
//! at points spread through its ball (centre, interior, boundary), on KW4 Alpha with a ball of
//! KW4 Beta's radius and on Didymos with a ball of its secondary's, over several separations
//! and bounds. The difference must lie within the certified bound plus the direct sum's own
//! rounding (≤ 1.7e-14 measured at 6 radii, `polyhedron_reach`; 3e-14 allowed, relative to |Φ|
//! and |a|). Near contact (the ball within 2 circumscribing radii) it must be refused. The
//! batch evaluation (`fields_into`) equals the single-point one bit for bit.
//!
//! `cargo test -p surfgrav-potentials --test polyhedron_local -- --nocapture` prints the
//! degrees and the worst difference over the bound.

use std::path::PathBuf;
use surfgrav_potentials::{LengthUnit, Mesh, Polyhedron, Vec3};

fn shapes() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/shapes")
}

const DIRECT_ROUNDING: f64 = 3e-14;

/// `count` points of a golden-angle spiral on the sphere of radius `r` about `c`.
fn spiral(c: &Vec3, r: f64, count: usize, twist: f64) -> Vec<Vec3> {
    (0..count)
        .map(|k| {
            let z = 1.0 - (2 * k + 1) as f64 / count as f64;
            let phi = k as f64 * 2.399_963_229_728_653 + twist;
            let s = (1.0 - z * z).sqrt();
            c + Vec3::new(s * phi.cos(), s * phi.sin(), z) * r
        })
        .collect()
}

#[test]
fn local_expansion_meets_its_bound_against_the_direct_sum() {
    let alpha = Mesh::read_obj(shapes().join("kw4_alpha.obj"), LengthUnit::Kilometres).unwrap();
    let didymos = Mesh::read_vertex_facet_csv(
        shapes().join("Didymos_A_vert_met.csv"),
        shapes().join("Didymos_A_facet.csv"),
        LengthUnit::Metres,
    )
    .unwrap();
    // (name, mesh, density, ball radius, centre distances in circumscribing radii)
    let cases = [
        ("KW4 Alpha", alpha, 1970.0, 296.1, [2.4, 2.9, 3.24, 5.0]),
        ("Didymos", didymos, 2104.0, 104.0, [2.3, 2.76, 4.0, 8.0]),
    ];
    for (name, mesh, density, ball, distances) in cases {
        let body = Polyhedron::with_density(&mesh, density).unwrap();
        let (c, big_r) = (body.centroid(), body.circumscribing_radius());
        for bound in [1e-9, 1e-12] {
            let mut worst: f64 = 0.0;
            let mut degrees = Vec::new();
            for (i, radii) in distances.into_iter().enumerate() {
                let dir = Vec3::new(0.8, -0.36, 0.48 - 0.1 * i as f64).normalize();
                let centre = c + dir * (radii * big_r);
                let local = body
                    .local_expansion(&centre, ball, bound)
                    .unwrap_or_else(|| panic!("{name} at {radii} radii: no expansion"));
                assert!(local.relative_bound() <= bound);
                degrees.push((local.degree(), local.source_degree()));
                let mut points = vec![centre];
                for (shell, twist) in [(0.5, 0.3), (0.9, 1.1), (1.0, 0.0)] {
                    points.extend(spiral(&centre, shell * ball, 20, twist));
                }
                // The four-at-a-time batch equals the single-point values bit for bit
                // (61 points: whole quads and a remainder).
                let mut batch = vec![local.field(&centre); points.len()];
                local.fields_into(&points, &mut batch);
                for (p, f) in points.iter().zip(&batch) {
                    let single = local.field(p);
                    assert_eq!(f.potential.to_bits(), single.potential.to_bits());
                    for (u, v) in f.acceleration.iter().zip(single.acceleration.iter()) {
                        assert_eq!(u.to_bits(), v.to_bits());
                    }
                }
                for p in &points {
                    assert!(local.contains(p) || (p - centre).norm() <= ball * (1.0 + 1e-15));
                    let e = local.field(p);
                    let d = body.field_direct(p);
                    let dphi = (e.potential - d.potential).abs() / d.potential.abs();
                    let da = (e.acceleration - d.acceleration).norm() / d.acceleration.norm();
                    let allowed = local.relative_bound() + DIRECT_ROUNDING;
                    worst = worst.max(dphi.max(da) / allowed);
                    assert!(dphi <= allowed, "{name} {radii} Φ {dphi:e} > {allowed:e}");
                    assert!(da <= allowed, "{name} {radii} a {da:e} > {allowed:e}");
                }
            }
            println!(
                "{name}, bound {bound:e}: (local, source) degrees {degrees:?}, worst difference / allowed {worst:.3}"
            );
        }
        // Near contact the ball reaches within 2 radii of the centroid: refused, as are bad
        // arguments.
        let near = c + Vec3::new(1.0, 0.0, 0.0) * (2.0 * big_r + 0.99 * ball);
        assert!(body.local_expansion(&near, ball, 1e-12).is_none());
        let touching = c + Vec3::new(1.0, 0.0, 0.0) * (big_r + ball);
        assert!(body.local_expansion(&touching, ball, 1e-12).is_none());
        let far = c + Vec3::new(0.0, 1.0, 0.0) * (4.0 * big_r);
        assert!(body.local_expansion(&far, ball, 0.0).is_none());
        assert!(body.local_expansion(&far, ball, f64::NAN).is_none());
        assert!(body.local_expansion(&far, -1.0, 1e-12).is_none());
        let nan = Vec3::new(f64::NAN, 0.0, 0.0);
        assert!(body.local_expansion(&nan, ball, 1e-12).is_none());
        // Beyond the highest degree offered, `LOCAL_MAX_DEGREE` (a ball nearly reaching the
        // body), it is refused.
        let huge = c + Vec3::new(0.0, 0.0, 1.0) * (2.0 * big_r + 3.0 * big_r);
        assert!(body
            .local_expansion_degrees(5.0 * big_r, 2.9 * big_r, 1e-13)
            .is_none());
        assert!(body.local_expansion(&huge, 2.9 * big_r, 1e-13).is_none());
    }
}
