//! Measuring tools of the rule's plans (not checks; run with `--ignored --nocapture`), and
//! the helpers the tests share to place the random-pose set's disk cases as the engine does.

use super::*;

mod measuring {
    use super::*;

    /// For every disk case of the random-pose set (`LEVEL_ERRORS_SEED`, default 12;
    /// `LEVEL_ERRORS_ONLY` filters the labels; the disk the default engine integrates over),
    /// the fraction of its planned count each 1-D rule (the angular table, the radial sides,
    /// the rim) needs alone for a true error of at most 1e-12 against the independent
    /// reference at 1e-13, the other rules at three times their plans: how well each rule is
    /// planned (the margins [`ROW_MARGIN`], [`RIM_MARGIN`] were measured with it).
    #[test]
    #[ignore]
    fn side_needs() {
        measured_disks(|case| {
            let (lamina, aim) = (case.lamina, case.aim);
            let error_of = |a: &LaminaAim| {
                let mut w = LaminaWorkspace::default();
                case.error(w.nodes(lamina, a, aim.start).unwrap())
            };
            let scaled = |f: [Real; 3]| {
                let mut a = aim;
                a.angle = a.angle.with_margin(f[0]);
                for s in &mut a.angles {
                    *s = s.with_margin(f[0]);
                }
                a.inward = a.inward.map(|s| s.with_margin(f[1]));
                a.outward = a.outward.map(|s| s.with_margin(f[1]));
                a.rim = a.rim.with_margin(f[2]);
                a
            };
            let mut needs = [0.0; 3];
            for side in 0..3 {
                let mut f = 0.2;
                while f < 4.0 {
                    let mut fs = [3.0; 3];
                    fs[side] = f;
                    if error_of(&scaled(fs)) <= 1e-12 {
                        break;
                    }
                    f += 0.05;
                }
                needs[side] = f;
            }
            let base = [
                aim.angle.predicted,
                aim.inward.or(aim.outward).map_or(0.0, |s| s.predicted),
                aim.rim.predicted,
            ];
            println!(
                "{:32} exact {} start {:3} eta {:.3} stretch {} needs angle {:.2} (of {:5.1}) radial {:.2} (of {:5.1}) rim {:.2} (of {:5.1})",
                case.label, aim.rows.is_some(), aim.start, aim.angle_eta, aim.stretch_points, needs[0], base[0], needs[1], base[1], needs[2], base[2]
            );
        });
    }

    /// The measuring tool of the rule (not a check; `cargo test -p surfgrav-interaction --lib
    /// -- --ignored --nocapture level_errors`): for every disk case of the random-pose set
    /// (`LEVEL_ERRORS_SEED`, default 12; four per pair of kinds, gaps 0.05 to 5; the disk the
    /// default engine integrates over), the true error of each level of the rule against the
    /// independent reference at 1e-13, and the evaluations of the first level whose error is
    /// at most 1e-12 (`LEVEL_ERRORS_ONLY` filters the labels; `LEVEL_ERRORS_ALL` prints every
    /// level from half the plan's first to twice it, `LEVEL_ERRORS_PARTS` which 1-D rule limits
    /// the first level, a singular circle's row singularities and the stretch's points).
    #[test]
    #[ignore]
    fn level_errors() {
        let (mut total, mut worst) = (0usize, (0usize, String::new()));
        measured_disks(|case| {
            let (lamina, aim, y) = (case.lamina, &case.aim, case.y);
            let mut workspace = LaminaWorkspace::default();
            let mut error_at = |level: u16| {
                let nodes = workspace.nodes(lamina, aim, level).unwrap();
                let len = nodes.area_points().len() + nodes.rim_points().len();
                (case.error(nodes), len)
            };
            if std::env::var("LEVEL_ERRORS_ALL").is_ok() {
                for level in (aim.start / 2).max(4)..=(2 * aim.start) {
                    let (e, len) = error_at(level);
                    println!("    level {level}: {len} ev, error {e:.1e}");
                }
            }
            let (start_error, start_len) = error_at(aim.start);
            let mut first = None;
            for level in 3..=(4 * aim.start).max(60) {
                let (e, len) = error_at(level);
                if e <= 1e-12 {
                    first = Some((level, len));
                    break;
                }
            }
            if std::env::var("LEVEL_ERRORS_PARTS").is_ok() {
                if let SingularSet::Circle(c) = singular_set(y) {
                    for s in (1..=20).map(|k| Real::from(k) * 0.05 * lamina.radius()) {
                        println!(
                            "    circle row s {s:.3}: {:?} (centre {:.3})",
                            CircleRows::new(c, &case.map).at(s),
                            aim.angle_centre
                        );
                    }
                }
                // Which 1-D rule limits the first level: each doubled alone.
                let twice = |side: ClusteredSide| side.with_margin(2.0);
                let mut variants = vec![];
                let mut a = *aim;
                a.angle = twice(a.angle);
                for side in &mut a.angles {
                    *side = twice(*side);
                }
                variants.push(("angle", a));
                let mut a = *aim;
                a.inward = a.inward.map(twice);
                a.outward = a.outward.map(twice);
                variants.push(("radial", a));
                let mut a = *aim;
                a.rim = twice(a.rim);
                variants.push(("rim", a));
                println!("    angle {:?}", aim.angle);
                println!("    radial {:?} {:?}", aim.inward, aim.outward);
                println!("    rim {:?}", aim.rim);
                for (name, a) in variants {
                    let mut w = LaminaWorkspace::default();
                    let nodes = w.nodes(lamina, &a, aim.start).unwrap();
                    println!("    {name} doubled: error {:.1e}", case.error(nodes));
                }
                let set = singular_set(y);
                for k in 0..RIM_SAMPLES {
                    let phi = k as Real * std::f64::consts::TAU / RIM_SAMPLES as Real;
                    let r = lamina.radius();
                    let r_y = case
                        .map
                        .apply(&Vec3::new(r * phi.cos(), r * phi.sin(), 0.0));
                    let p = case.map.back(&(set.nearest(&r_y) - case.map.offset));
                    let eta = angular_width(r, p.xy().norm(), p.z.abs());
                    if eta < STRETCH * aim.angle_eta {
                        println!(
                            "    rim {phi:.3}: nearest at phi {:.3} s {:.3} h {:.3}  eta(R) {eta:.3}",
                            p.y.atan2(p.x),
                            p.xy().norm(),
                            p.z
                        );
                    }
                }
            }
            let (level, len) = first.unwrap_or((0, usize::MAX));
            total += len;
            if len > worst.0 {
                worst = (len, case.label.to_string());
            }
            println!(
                "{:32} {} start {:3} ({:5} ev, err {:.1e})  1e-12 at level {:3}: {:6} ev   eta {:.3} s_q {:.3} h {:.3} rim {:.3?} stretch {}",
                case.label,
                if case.certified { " " } else { "?" },
                aim.start,
                start_len,
                start_error,
                level,
                len,
                aim.angle_eta,
                aim.singular[0].0,
                aim.singular[0].1,
                aim.singular[1],
                aim.stretch_points,
            );
        });
        println!("total {total}, worst {} ({})", worst.0, worst.1);
    }
}

/// The periodic trapezoid rule on the row of radius `s` of X (mapped into Y's frame by `map`)
/// over `field`'s potential, nodes at $2\pi(k + \text{shift})/n$: of `counts`, those whose
/// errors (relative, against `reference` nodes) lie in `window`, and the rate of convergence
/// between the first and the last of them, as (first, last, rate); `None` with fewer than two.
pub(crate) fn row_rate(
    field: &Body,
    map: &FrameMap,
    s: Real,
    shift: Real,
    reference: usize,
    counts: impl Iterator<Item = usize>,
    window: std::ops::RangeInclusive<Real>,
) -> Option<(usize, usize, Real)> {
    let trapezoid = |n: usize| {
        let step = std::f64::consts::TAU / n as Real;
        (0..n)
            .map(|k| {
                let phi = (k as Real + shift) * step;
                let r = map.apply(&Vec3::new(s * phi.cos(), s * phi.sin(), 0.0));
                field.potential().field(&r).potential
            })
            .sum::<Real>()
            * step
    };
    let exact = trapezoid(reference);
    let error = |n: usize| ((trapezoid(n) - exact) / exact).abs();
    let inside: Vec<usize> = counts.filter(|&n| window.contains(&error(n))).collect();
    let (&first, &last) = (inside.first()?, inside.last()?);
    if first == last {
        return None;
    }
    Some((
        first,
        last,
        (error(first) / error(last)).ln() / (last - first) as Real,
    ))
}

/// The frame map the engine integrates a disk X in (`surface_choice::place`: X turned about
/// its axis so that Y's centroid lies in its x–z plane).
pub(crate) fn engine_map(
    px: &surfgrav_potentials::Pose,
    py: &surfgrav_potentials::Pose,
) -> (FrameMap, nalgebra::UnitQuaternion<Real>) {
    use nalgebra::UnitQuaternion;
    use surfgrav_potentials::PoseExt;
    let relative = px
        .rotation
        .inverse_transform_vector(&(py.position() - px.position()));
    let turn = relative.y.atan2(relative.x);
    let rotation = px.rotation * UnitQuaternion::from_axis_angle(&Vec3::z_axis(), turn);
    let map = FrameMap::between(
        &surfgrav_potentials::Pose::from_position_rotation(px.position(), rotation),
        py,
    )
    .unwrap();
    (map, rotation)
}

/// A case's two sides as (X, X's pose, Y, Y's pose): integrated over A, then over B.
pub(super) fn both_sides(
    case: &crate::work_precision::PoseCase,
) -> [(
    &Body,
    &surfgrav_potentials::Pose,
    &Body,
    &surfgrav_potentials::Pose,
); 2] {
    [
        (&case.a, &case.pose_a, &case.b, &case.pose_b),
        (&case.b, &case.pose_b, &case.a, &case.pose_a),
    ]
}

/// Calls `visit(case, lamina, y, map)` for each side of each case of the random-pose set of
/// `seed` (four per pair of kinds, gaps 0.05 to 5) whose label contains `label` and whose
/// integrated body is a disk: the disk, the other body and the engine's frame map.
pub(super) fn for_each_disk_side(
    seed: u64,
    label: &str,
    mut visit: impl FnMut(&crate::work_precision::PoseCase, &Lamina, &Body, &FrameMap),
) {
    use crate::body::BodyShape;
    for case in crate::work_precision::pose_set(seed, &[0.05, 0.2, 1.0, 5.0], 4)
        .iter()
        .filter(|c| c.label.contains(label))
    {
        for (x, px, y, py) in both_sides(case) {
            if let BodyShape::Disk(lamina) = x.shape() {
                visit(case, lamina, y, &engine_map(px, py).0);
            }
        }
    }
}

/// The side of a disk case the default engine integrates over (A unless the engine chose B or
/// A is no disk), as (sign, X, X's pose, Y, Y's pose): the sign is +1 where X is A (the
/// reference's force is on A), −1 where it is B.
pub(super) fn engine_side(
    case: &crate::work_precision::PoseCase,
) -> (
    Real,
    &Body,
    &surfgrav_potentials::Pose,
    &Body,
    &surfgrav_potentials::Pose,
) {
    use crate::body::BodyShape;
    let chosen = crate::InteractionEngine::default()
        .interact(&case.a, &case.pose_a, &case.b, &case.pose_b)
        .map(|r| r.integrated_over)
        .unwrap_or(None);
    if chosen == Some(crate::Side::B) || !matches!(case.a.shape(), BodyShape::Disk(_)) {
        (-1.0, &case.b, &case.pose_b, &case.a, &case.pose_a)
    } else {
        (1.0, &case.a, &case.pose_a, &case.b, &case.pose_b)
    }
}

/// The pose set's seed of the measuring tools: `LEVEL_ERRORS_SEED`, 12 by default.
pub(super) fn level_errors_seed() -> u64 {
    std::env::var("LEVEL_ERRORS_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(12)
}

/// A disk case of the random-pose set as the measuring tools see it: the disk X the default
/// engine integrates over, in the engine's frame, with its plan and the independent reference
/// (the ladder at 1e-13 over the other body).
pub(super) struct MeasuredDisk<'a> {
    pub(super) label: &'a str,
    pub(super) lamina: &'a Lamina,
    pub(super) x: &'a Body,
    pub(super) y: &'a Body,
    pub(super) map: FrameMap,
    pub(super) turned: nalgebra::UnitQuaternion<Real>,
    pub(super) aim: LaminaAim,
    pub(super) reference: Interaction,
    pub(super) certified: bool,
    /// +1 where X is A (the reference's force is on A), −1 where it is B.
    pub(super) sign: Real,
}

impl MeasuredDisk<'_> {
    /// The relative error of the table `nodes` (force or energy, the larger) against the
    /// reference.
    pub(super) fn error(&self, nodes: &LaminaNodes) -> Real {
        let r = crate::kernel::lamina_sums(nodes, self.y.potential(), &self.map).integrals(
            self.x.density(),
            &Vec3::z(),
            0,
        );
        let reference = &self.reference;
        let e =
            ((r.potential_energy - reference.potential_energy) / reference.potential_energy).abs();
        let f = (self.turned * r.force - self.sign * reference.force_on_a).norm()
            / reference.force_on_a.norm();
        e.max(f)
    }
}

/// Calls `visit` for every disk case of the random-pose set of `LEVEL_ERRORS_SEED` (default
/// 12; four per pair of kinds, gaps 0.05 to 5) whose label contains `LEVEL_ERRORS_ONLY` and
/// whose disk has an aimed plan.
pub(super) fn measured_disks(mut visit: impl FnMut(&MeasuredDisk<'_>)) {
    use crate::body::BodyShape;
    let only = std::env::var("LEVEL_ERRORS_ONLY").unwrap_or_default();
    for case in crate::work_precision::pose_set(level_errors_seed(), &[0.05, 0.2, 1.0, 5.0], 4)
        .iter()
        .filter(|c| c.label.contains("disk") && c.label.contains(only.as_str()))
    {
        let (sign, x, px, y, py) = engine_side(case);
        let BodyShape::Disk(lamina) = x.shape() else {
            continue;
        };
        let (map, turned) = engine_map(px, py);
        let Some(aim) = lamina_aim(lamina, y, &map, 1e-12) else {
            continue;
        };
        let (reference, certified) = crate::work_precision::independent_reference(
            &case.a,
            &case.pose_a,
            &case.b,
            &case.pose_b,
            1e-13,
        )
        .unwrap();
        visit(&MeasuredDisk {
            label: &case.label,
            lamina,
            x,
            y,
            map,
            turned,
            aim,
            reference,
            certified,
            sign,
        });
    }
}

/// The cost of planning: the mean time of [`lamina_aim`] and of one level's node table (at
/// the plan's first level) over both sides of the disk-disk cases of the random-pose set
/// (`LEVEL_ERRORS_SEED`; not a check: timing belongs to benchmarks, this only locates it).
mod plan_timing {
    use super::*;

    #[test]
    #[ignore]
    fn plan_timing() {
        let (mut plan_ns, mut nodes_ns, mut count) = (0.0, 0.0, 0);
        for_each_disk_side(level_errors_seed(), "disk-disk", |_, lamina, y, map| {
            let Some(aim) = lamina_aim(lamina, y, map, 1e-12) else {
                return;
            };
            let n = 2000;
            let t = std::time::Instant::now();
            for _ in 0..n {
                std::hint::black_box(lamina_aim(lamina, y, std::hint::black_box(map), 1e-12));
            }
            plan_ns += t.elapsed().as_nanos() as f64 / n as f64;
            let mut w = LaminaWorkspace::default();
            let t = std::time::Instant::now();
            for _ in 0..n {
                std::hint::black_box(
                    w.nodes(lamina, &aim, aim.start)
                        .unwrap()
                        .area_points()
                        .len(),
                );
            }
            nodes_ns += t.elapsed().as_nanos() as f64 / n as f64;
            count += 1;
        });
        println!(
            "{count} aims: plan {:.0} ns, nodes at start {:.0} ns (mean)",
            plan_ns / count as f64,
            nodes_ns / count as f64
        );
    }
}
