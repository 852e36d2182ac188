//! The ladder of fixed tables (the default strategy; see the [module docs](super::super),
//! method 3): tensor tables of growing resolution, from a level predicted from the gap and the
//! tolerance, until two successive levels agree to the tolerance. [`run_ladder`] is the loop
//! over levels, shared with the aimed rule's ladder ([`super::aimed_ladder`]);
//! [`SingleLevel`] evaluates one table of it, uncertified.

use super::{Problem, Strategy};
use crate::aimed::lamina::angular_width;
use crate::aimed::{nearest_on_ellipsoid, nearest_singular_point};
use crate::assembly::{
    assemble, not_met, relative_from_absolute, solid_values, symmetrise_lamina, Values,
    ROUNDING_PER_TERM,
};
use crate::body::{with_field, Body, BodyShape};
use crate::error::{InteractionError, Side};
use crate::kernel::{lamina_sums, solid_table_sums};
use crate::options::{Interaction, InteractionOptions, Method, Request};
use crate::overlap::check_nodes;
use crate::rules::{
    next_transverse, table_size, NodeTable, Parametrisation, TableKey, MAX_TRANSVERSE,
    TRANSVERSE_RATIO,
};
use crate::surface_choice::{start_transverse, Placement};
use surfgrav_surfaces::{Real, Vec3};

/// The ladder over X's cached node tables ([`super::super::rules`]).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct FixedLadder;

impl Strategy for FixedLadder {
    fn refine(&mut self, problem: &Problem<'_>) -> Result<Interaction, InteractionError> {
        let Problem {
            x,
            y,
            placement: p,
            options,
            request,
            budget,
        } = *problem;
        let key = |transverse: u16| table_key(options, p, transverse);
        run_ladder(
            &ladder_settings(options, budget),
            p,
            start_transverse(options, p).max(p.lamina_start),
            |level| table_size(x.shape(), &key(level)),
            // Both counts of a fixed table grow with the level.
            |_, _| true,
            |level| {
                let table = x.table(key(level))?;
                if p.node_check {
                    check_nodes(&table, y, &p.map)?;
                }
                Ok((evaluate_table(x, y, &table, p, request), table.len()))
            },
        )
    }
}

/// The narrowest angular singularity $\eta$ for which [`far_lamina_start`] predicts (the 13
/// cases it was measured on have $\eta$ from 1.7 to 6.4).
const FAR_LAMINA_ETA: Real = 1.0;

/// The first transverse count for a disk X (otherwise 0), from the angular singularity of
/// the integrand on its rim: with Y's nearest singular point at in-plane radius $s_q$ and
/// height $h$ in the disk's frame, the integrand on the rim circle $s = R$ is singular at
/// $\varphi = \varphi_q \pm i\eta$, $\cosh\eta = (R^2 + s_q^2 + h^2)/(2Rs_q)$ (as for the aimed
/// lamina rule, `aimed/lamina.rs`), and the periodic trapezoid rule's error falls like
/// $e^{-\eta n}$ with $n \approx t/\kappa$ azimuths for $t$ radial nodes ([`table_size`]): $t =
/// \kappa\ln(1/\tau)/\eta$. The gap formula of [`start_transverse`], fitted to the founding
/// paper's spheroids, started up to 5 levels low for disks far from Y: on the 13 cases of
/// the random-pose set that use the fixed lamina table (`pose_benchmark`, seed 12, gaps 1 and
/// 5) this count is within one level of the start with the fewest evaluations in 12, three
/// below in one, and the larger of the two starts took their evaluations from 6,046 to 4,540
/// (seed 13, not used to fit: the gap-5 disk cases 5,020 to 4,028; single cases can take up
/// to two levels more than before). Nearer ($\eta <$
/// [`FAR_LAMINA_ETA`]) the table's azimuth clustering toward Y, which this count ignores,
/// takes over, and the gap formula serves alone.
pub(crate) fn far_lamina_start(
    x: &Body,
    y: &Body,
    p: &Placement,
    options: &InteractionOptions,
) -> u16 {
    let BodyShape::Disk(lamina) = x.shape() else {
        return 0;
    };
    let radius = lamina.radius();
    let disk = Vec3::new(radius, radius, 0.0);
    let (_, q) = nearest_singular_point(y, &p.map, |r| nearest_on_ellipsoid(&disk, r), radius);
    let eta = angular_width(radius, q.xy().norm(), q.z.abs());
    if eta.is_nan() || eta < FAR_LAMINA_ETA {
        return 0;
    }
    let kappa = TRANSVERSE_RATIO[usize::from(p.ratio).min(TRANSVERSE_RATIO.len() - 1)];
    let t = kappa * (1.0 / options.relative_tolerance).ln() / eta;
    (t.round() as u16).min(MAX_TRANSVERSE)
}

/// One table of the ladder, with this transverse count ([`super::super::MethodChoice::FixedLevel`]):
/// nothing certifies it, its error estimate is $+\infty$.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SingleLevel {
    /// The transverse count per half range (clamped to the ladder's range).
    pub(crate) transverse: u16,
}

impl Strategy for SingleLevel {
    fn refine(&mut self, problem: &Problem<'_>) -> Result<Interaction, InteractionError> {
        let Problem {
            x,
            y,
            placement: p,
            options,
            request,
            budget,
        } = *problem;
        let transverse = self.transverse.clamp(1, MAX_TRANSVERSE);
        let table = x.table(table_key(options, p, transverse))?;
        if table.len() > budget {
            return Err(InteractionError::BudgetTooSmall {
                max_evaluations: budget,
                minimum: table.len(),
            });
        }
        if p.node_check {
            check_nodes(&table, y, &p.map)?;
        }
        let method = match p.side {
            Side::A => Method::SurfaceOverA,
            Side::B => Method::SurfaceOverB,
        };
        evaluate_table(x, y, &table, p, request).finish(
            method,
            Some(p.side),
            table.len(),
            Real::INFINITY,
            Some(transverse),
        )
    }
}

/// Growth factor of the ladder for the tolerance (module docs of [`super::super::rules`]).
pub(crate) fn growth(options: &InteractionOptions) -> Real {
    let digits = -options.relative_tolerance.log10();
    (1.0 + 1.0 / digits.max(1.0)).max(1.08)
}

/// The key of the fixed table with `transverse` nodes per half range for this placement.
pub(crate) fn table_key(options: &InteractionOptions, p: &Placement, transverse: u16) -> TableKey {
    TableKey {
        parametrisation: match options.parametrisation {
            Parametrisation::Aimed | Parametrisation::Automatic => Parametrisation::AzimuthHeight,
            other => other,
        },
        transverse,
        ratio: p.ratio,
        clustering: p.clustering,
        half_transverse: p.half_transverse,
        half_azimuth: p.half_azimuth,
    }
}

/// The ladder's settings from the options, with a budget of `max_evaluations`.
pub(crate) fn ladder_settings(
    options: &InteractionOptions,
    max_evaluations: usize,
) -> LadderSettings {
    LadderSettings {
        tolerance: options.relative_tolerance,
        max_evaluations,
        growth: growth(options),
        jump: false,
        single_step: false,
        geometric: false,
        oscillating: false,
    }
}

/// The ratio of the last two changes at or below which an aimed ladder's levels count as
/// converging geometrically ([`LadderSettings::geometric`]).
const GEOMETRIC_RATIO: Real = 0.25;

/// What a ladder of levels needs from the engine's options.
pub(crate) struct LadderSettings {
    pub(crate) tolerance: Real,
    pub(crate) max_evaluations: usize,
    pub(crate) growth: Real,
    /// From the third level on, jump to the level the observed rate of convergence predicts
    /// (at most 1.5 times the current one) instead of the next of the ladder. The aimed rule
    /// only: on the fixed tables a disk pair at gap 0.05 (`pose_benchmark`, seed 12, four per
    /// pair, case disk-disk #3) then certified 2.6e-13 with a true error of 5.8e-13 (the
    /// split Gauss–Legendre halves stall from one level to the next, so the change after a
    /// jump can understate the jumped level's error); without it, 3.6e-13 and 3.2e-14.
    pub(crate) jump: bool,
    /// Steps of one node where the ladder would step two (see `aimed_ladder`).
    pub(crate) single_step: bool,
    /// The levels' errors fall geometrically (the aimed rules: one rule per direction, every
    /// level refining each): from the third level on, where the last change is at most
    /// [`GEOMETRIC_RATIO`] of the one before, the estimate is the change (or the geometric
    /// tail, if larger) without the factor 2 that the fixed tables' uneven convergence needs.
    /// The change bounds the coarser level's error, and the reported finer level's is then
    /// about a quarter of it or less. Measured (`pose_benchmark`, seeds 12-16, 480 cases):
    /// 0 estimates exceeded; the fourth levels it saves were up to a third of a case's cost
    /// (a disk pair at gap 0.05, seed 14 #3: changes 4.8e-12 then 9.0e-13 certify at the third
    /// level instead of a fourth).
    pub(crate) geometric: bool,
    /// The levels' errors may oscillate (the aimed rule with its pole on a common axis and a
    /// ring of singularities off the pole, [`crate::aimed::Aim::ring`]): Gauss–Legendre's error
    /// for a singular pair off the interval's axis, $\theta\_L \pm iw$, turns in phase from level
    /// to level, so a level near a zero crossing agrees with the next by accident. The first
    /// change then counts twice and every later estimate is at least the change before it.
    /// Measured (`near_axis_sweep`, seeds 1-15, 2026, 7, 99; 1,360 pairs): a prolate spheroid
    /// 0.1 below an oblate one (seed 10 #41) changed by 1.2e-10 then 1.1e-13 with a true error
    /// of 4.0e-13, and an oblate one near the axis of a prolate one (seed 13 #67) by 2.8e-13 on
    /// its first pair with a true error of 4.2e-13; with this, no estimate exceeded and none
    /// failed, at 1-13 % more evaluations on these sweeps (the stacked oblate–prolate
    /// configuration 360 -> 512). Also the aimed lamina rule's plans corrected by a focal
    /// ellipse's exact rows (`LaminaAim::corrected` in `aimed/lamina.rs`), whose first change
    /// understated a near-contact error.
    pub(crate) oscillating: bool,
}

/// A ladder of levels from `start` (a level named by its transverse count): `size(level)` is
/// a level's cost in evaluations, `evaluate(level)` its values and cost. Levels grow until two
/// successive ones agree to the tolerance (see the module docs for the estimate).
/// `refines(from, to)` says whether level `to` has more nodes than `from` in every 1-D rule of
/// its table: the next level is the first one from the ladder's step that does, because a
/// rule whose count stays keeps its error out of the change between the two levels. (The
/// aimed lamina rule scales each of its sides with the level and rounds up, so a side with few
/// nodes kept its count over a step: started at 0.7 of the plan's first level, the random-pose
/// set's disk-disk gap 1 #0 (seed 13) certified 2.3e-14 with a true error of 2.2e-12, its
/// radial side at 7 nodes on both levels.)
pub(crate) fn run_ladder(
    settings: &LadderSettings,
    p: &Placement,
    start: u16,
    size: impl Fn(u16) -> usize,
    refines: impl Fn(u16, u16) -> bool,
    mut evaluate: impl FnMut(u16) -> Result<(Values, usize), InteractionError>,
) -> Result<Interaction, InteractionError> {
    let tolerance = settings.tolerance;
    let method = match p.side {
        Side::A => Method::SurfaceOverA,
        Side::B => Method::SurfaceOverB,
    };
    let growth = settings.growth;
    // Room for a full step above the first level: a start predicted at the top level (a
    // singular curve running close along a disk, e.g. two parallel disks 0.02 apart) would
    // otherwise evaluate one level, have nothing to compare it with, and report no result.
    let planned = start.min((Real::from(MAX_TRANSVERSE) / growth).floor() as u16 - 1);
    let mut level = planned;
    // With a small budget, start low enough for two levels to fit (a reported best result
    // with its estimate is worth more than no result).
    while level > 2 {
        let pair = size(level) + size(next_transverse(level, growth));
        if pair <= settings.max_evaluations {
            break;
        }
        level = ((Real::from(level) / growth).floor() as u16)
            .min(level - 1)
            .max(2);
    }
    // Levels below the planned start are not yet in the regime where the change between two
    // of them bounds the coarser one's error: the first change from a start lowered for the
    // budget counts twice, as the uneven changes below do.
    let lowered = level < planned;
    let mut previous: Option<Values> = None;
    let mut previous_change: Option<Real> = None;
    let mut previous_ratio: Option<Real> = None;
    // A step whose change fell by less than GEOMETRIC_RATIO has been seen (see `slow`).
    let mut erratic = false;
    let mut previous_level = level;
    let mut jumped = false;
    let mut previous_force_change: Option<Real> = None;
    let mut evaluations = 0usize;
    let mut best: Option<Interaction> = None;
    loop {
        let cost = size(level);
        if evaluations + cost > settings.max_evaluations {
            return match best {
                Some(best) => Err(not_met(tolerance, best)),
                None => Err(InteractionError::BudgetTooSmall {
                    max_evaluations: settings.max_evaluations,
                    minimum: evaluations + cost,
                }),
            };
        }
        let (values, cost) = evaluate(level)?;
        evaluations += cost;
        let force_change_before = previous_force_change;
        previous_force_change = previous.map(|coarse| values.force_change(&coarse));
        if let Some(coarse) = previous {
            let change = values.relative_change(&coarse);
            // From the third level on (the start prediction was too low: a harder regime,
            // near contact or far from the equator), convergence in t can be uneven:
            // Gauss–Legendre on the split halves gives errors 4.0e-11 at t = 28 and
            // 3.0e-11 at t = 32 for a close prolate–oblate pair, and the fine level's
            // error reached 1.2 times the last change (3.65e-14 against 3.05e-14). There the
            // estimate is twice the change, or the tail of a geometric series with the
            // observed ratio ρ of the last two changes, change·ρ/(1 − ρ), if larger (the
            // change itself where the levels converge geometrically: `geometric`).
            let first = if lowered || settings.oscillating {
                2.0 * change
            } else {
                0.0
            };
            let before_change = if settings.oscillating {
                previous_change.unwrap_or(0.0)
            } else {
                0.0
            };
            // Once a step has fallen by less than GEOMETRIC_RATIO, a later fast one no longer
            // certifies its change alone: the levels are not converging geometrically there.
            // Measured: a disk of radius 0.98 held 8.9e-4 of its radius from a unit disk (a
            // random draw near contact; `tests/stress.rs`), over itself, the engine's choice,
            // at 1e-10: changes 9.2e-7, 1.6e-7, 1.3e-7, 4.8e-9, 1.2e-9, 3.8e-10 and 1.8e-11,
            // certified 1.8e-11 with a true error of 2.4e-11; now 3.7e-11. (No evaluation of
            // the random-pose sets of seeds 12 to 16, 32 and 39 changes.)
            let slow = previous_change.map_or(first, |before: Real| {
                let ratio = if before > 0.0 { change / before } else { 1.0 };
                let ratio = ratio.min(0.99);
                let floor = if settings.geometric && ratio <= GEOMETRIC_RATIO && !erratic {
                    1.0
                } else {
                    2.0
                };
                (floor * change).max(change * ratio / (1.0 - ratio))
            });
            if previous_change.is_some_and(|before| change > GEOMETRIC_RATIO * before) {
                erratic = true;
            }
            // Where the levels need not converge geometrically, a change that falls far below
            // what the rate before it predicts may be two levels' errors that happen to agree:
            // the fixed tables of an ellipsoid 0.05 from a spheroid (`pose_benchmark` seed 24,
            // spheroid-ellipsoid gap 0.05 #0, in the polar-angle form over the ellipsoid)
            // changed by 1.3e-11, 7.4e-12, 3.4e-12, 4.5e-14 and 1.5e-13 from level 85 to 92,
            // 100, 108 and 117, and at 1e-13 level 108 certified 9.0e-14 with a true error of
            // 1.3e-13. The coarser level's error is then also taken as the previous change
            // times the previous ratio of changes (the rate before it), if larger.
            let stalled = match (previous_change, previous_ratio) {
                (Some(before), Some(ratio)) if !settings.geometric => before * ratio,
                _ => 0.0,
            };
            previous_ratio = previous_change.map(|before: Real| {
                if before > 0.0 {
                    (change / before).min(0.99)
                } else {
                    0.99
                }
            });
            previous_change = Some(change);
            let estimate = change
                .max(slow)
                .max(stalled)
                .max(before_change)
                .max(values.form_discrepancy(values.torque_on_a.norm()))
                .max(values.rounding);
            let result = values.finish(method, Some(p.side), evaluations, estimate, Some(level))?;
            if estimate <= tolerance {
                return Ok(result);
            }
            if change <= values.rounding && stalled.max(before_change) <= tolerance {
                // The levels agree to rounding: refining cannot lower the estimate. (Unless
                // what stands above the tolerance is the rate or the change before a sudden
                // drop: the next level then shows whether the drop holds.)
                return Err(not_met(tolerance, result));
            }
            best = Some(result);
        }
        if level >= MAX_TRANSVERSE {
            return match best {
                Some(best) => Err(not_met(tolerance, best)),
                None => Err(InteractionError::NonFiniteResult {
                    what: "no resolution level could be evaluated",
                }),
            };
        }
        let mut regular = if settings.single_step {
            (level + 1).max((growth * Real::from(level)).ceil() as u16)
        } else {
            next_transverse(level, growth)
        };
        while regular < MAX_TRANSVERSE && !refines(level, regular) {
            regular += 1;
        }
        if level + (regular - level).div_ceil(2) > MAX_TRANSVERSE {
            // Not even half a step left: a smaller one (the top level clamped) changes so
            // little that the change would understate the error. Measured: two parallel
            // disks 0.02 apart certified 2.9e-15 from levels 598 and 600 with a true error of
            // 8e-9; from 553 and 599 the estimate is 9.6e-9. (Half a step still certifies
            // the references of the pose set that climb to the top: 569 and 600.)
            return match best {
                Some(best) => Err(not_met(tolerance, best)),
                None => Err(InteractionError::NonFiniteResult {
                    what: "no resolution level could be evaluated",
                }),
            };
        }
        let mut next = regular;
        let mut jump = false;
        if let (true, false, Some(before), Some(change)) = (
            settings.jump,
            jumped,
            force_change_before,
            previous_force_change,
        ) {
            // Errors falling like exp(−r t): the rate from the last two changes of the force
            // (each the error of its coarser level; the force alone, so that a force-only
            // evaluation takes the same levels and stops no later), and the level whose
            // error would be half the tolerance; the level after it then certifies. Never
            // two jumps in a row: the change after a jump measures the level before it.
            let from = Real::from(previous_level);
            let rate = (before / change).ln() / (Real::from(level) - from);
            if rate.is_finite() && rate > 0.0 {
                let needed = from + (2.0 * change / tolerance).ln() / rate;
                let capped = needed.min(1.5 * Real::from(level)).ceil();
                if capped > Real::from(next) {
                    next = capped as u16;
                    jump = true;
                }
            }
        }
        jumped = jump;
        previous_level = level;
        previous = Some(values);
        level = next.min(MAX_TRANSVERSE);
    }
}

/// Runs the monomorphised loop for Y's field kind over X's table (dispatch once per table).
pub(crate) fn evaluate_table(
    x: &Body,
    y: &Body,
    table: &NodeTable,
    p: &Placement,
    request: Request,
) -> Values {
    let force_only = request == Request::Force;
    match table {
        NodeTable::Solid(t) => {
            let sums = match (p.far, force_only) {
                (true, true) => {
                    with_field!(&y.field, |f| solid_table_sums::<_, true, false>(
                        t, f, &p.map
                    ))
                }
                (false, true) => {
                    with_field!(&y.field, |f| solid_table_sums::<_, false, false>(
                        t, f, &p.map
                    ))
                }
                (true, false) => {
                    with_field!(&y.field, |f| solid_table_sums::<_, true, true>(
                        t, f, &p.map
                    ))
                }
                (false, false) => {
                    with_field!(&y.field, |f| solid_table_sums::<_, false, true>(
                        t, f, &p.map
                    ))
                }
            };
            let mut values = solid_values(sums, x.density, p);
            values.request = request;
            values
        }
        NodeTable::Lamina(t) => {
            let mut s = with_field!(&y.field, |f| lamina_sums(t, f, &p.map));
            if p.half_azimuth {
                s = symmetrise_lamina(&s, 1);
            }
            let r = s.integrals(x.density, &t.normal(), table.len());
            let mut values = assemble(
                p,
                &r.force,
                &r.torque,
                &r.torque_area_form,
                r.potential_energy,
            );
            let sigma = x.density;
            values.rounding = relative_from_absolute(
                &values,
                ROUNDING_PER_TERM * sigma * s.force_magnitude,
                ROUNDING_PER_TERM * sigma * s.moment_magnitude,
                ROUNDING_PER_TERM * values.potential_energy.abs(),
                (p.position_y - p.position_x).norm(),
            );
            values
        }
    }
}
