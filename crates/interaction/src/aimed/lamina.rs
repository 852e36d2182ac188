//! The aimed lamina rule: a uniform disk's area and rim integrals with the nodes clustered
//! toward the point of the disk nearest the other body's singular set, so that a disk near
//! the other body (near contact, in any attitude) costs about as much as one far away.
//!
//! # Parametrisation
//!
//! Polar coordinates $(s, \varphi)$ about the disk's centre, as the fixed lamina table
//! ([`surfgrav_surfaces::lamina`]), but with both 1-D rules aimed. Let $\mathbf q$ be the singular point of
//! the other body's field nearest to the disk (alternating projections between the filled
//! disk and the singular set, as for the aimed ellipsoid rule, `aimed.rs`), in the disk's
//! frame at azimuth $\varphi_q$, in-plane radius $s_q$ and height $h = |q_z|$. The integrand,
//! continued to complex coordinates, is singular where $|\mathbf r - \mathbf q|^2 = 0$:
//!
//! - along the ray $\varphi = \varphi_q$, at $s = s_q \pm ih$: the radial rule is split at
//!   $s_q$ (or ends there, when $\mathbf q$ lies beyond the rim) and clustered toward it;
//! - on the circle $s = s_c = \min(s_q, R)$, at $\varphi = \varphi_q \pm i\eta$ with
//!   $\cosh\eta = (s_c^2 + s_q^2 + h^2)/(2 s_c s_q)$ ($\eta \approx h/s_q$ near the disk): the
//!   angle is split at $\varphi_q$ and $\varphi_q + \pi$ into two half-ranges clustered
//!   toward $\varphi_q$.
//!   Each radius $s_j$ of the radial rule has its own angular rule, from $\eta$ on its circle
//!   $s = s_j$ (the narrower of the nearest singular point's and the rim's, below), never
//!   with more nodes than the rule for the narrowest circle: inner circles, farther from
//!   the singularity, take fewer angles (the first level is sized by the narrowest one).
//!
//! The rim integral has its own aim: the singular point nearest the rim circle, with the same
//! angular model at $s_c = R$.
//!
//! A singular set that is a curve (a disk's rim, an oblate spheroid's focal circle) or a
//! filled focal ellipse can run near the disk along a stretch, not at one point: each point
//! of it is singular in $s$ and $\varphi$ as $\mathbf q$ is, at its own azimuth, so a rule
//! clustered for $\mathbf q$ alone meets the neighbouring points off its clustering point,
//! where it is sparse. Then ([`near_stretch`]) every 1-D rule is planned against a spread of
//! the stretch's points (the singular points nearest to the rim samples whose angular
//! singularity on the rim is within [`STRETCH`] times the narrowest): the angular rules
//! against their $(\varphi_k - \varphi_q) \pm i\eta_k$, the radial sides against their
//! $s_k \pm ih_k$, the rim rule likewise about its own aim. Each row's angles are clustered
//! toward the narrower of $\mathbf q$ and the singular point nearest the rim on that row, and
//! each entry of the angular table is planned against the stretch's points as the entry's own
//! rows see them: each point's least width over those rows, offset from the rows' centre
//! ([`entry_widths`]; the rows of one entry can lie near $\mathbf q$'s radius and near the
//! rim at once, and a point is at its narrowest on one of them only). Where the stretch is a
//! triaxial body's focal ellipse, each point's angular widths are multiplied by the ratio of
//! the exact row singularity ([`EllipseRows`]) to the point model's on the point's own
//! narrowest row (between 1 and [`EXACT_MAX_RATIO`]): treating each point of a curve as an
//! isolated singular point understates the rows' widths by up to a factor 2. (The radial
//! sides keep the points' own heights: the ratio is the rows' angular singularity.)
//!
//! # A singular circle
//!
//! Where Y's singular set is a circle (a disk's rim, an oblate spheroid's focal circle, not
//! on the disk's axis), the singularities of each row are known exactly ([`CircleRows`]):
//! two pairs $\varphi_j \pm i\eta_j$ from a quadratic in $e^{i\varphi}$, one near each place
//! where the circle comes near the row (a curve that crosses X's plane twice has a second,
//! remote pair that a rule clustered for the nearest point alone misses; a curve that runs
//! near along a stretch has two pairs, not one per point of it). Each row's angles are then
//! clustered toward its own narrower singularity (the lists of angles are shared by the rows
//! of one entry of the table and turned row by row), the entry is chosen by its width, and
//! the entries are planned against that width and the least favourable other singularity
//! of the sampled rows of about that width. Where an entry's plan is set by the other
//! singularity, its rows are split at both ([`SplitRow`]): four pieces, each clustered
//! toward its own singular end. The rim rule is planned from the rim row's two pairs. The
//! radial integrand, a row's angular integral, is singular only where two of the row's
//! singularities meet and pinch its contour ([`circle_pinches`]): a double root of the
//! quadratic, or the circle's crossing of X's plane, continued to complex $s$. (Its plan is at
//! least a fraction, [`CUT_FLOOR`], of the older plan against every point of the circle.)
//!
//! The rule serves where the singular set comes within
//! [`AIMED_LAMINA_REACH`] radii of the disk; farther, the fixed lamina table is cheaper.
//!
//! # Clustering
//!
//! Each side $t \in [0, L]$ ($t$ the distance from the clustering point along the side) uses
//! Gauss–Legendre in $u \in [0, 1]$ after the sinh map $t = w\sinh(\mu u)$,
//! $\mu = \operatorname{asinh}(L/w)$, or plain Gauss–Legendre in $t$. A singularity at
//! complex $t^\ast$ sits at $u^\ast = \operatorname{asinh}(t^\ast/w)/\mu$, and the rule's error falls
//! like $\rho^{-2n}$ with $\rho$ the Bernstein ellipse through $u^\ast$ (for several
//! singularities, the least favourable). Per side, the widest width $w$ (or none) whose
//! predicted count for the tolerance is within
//! [`WIDTH_SLACK`](clustered_side::WIDTH_SLACK) of the fewest is chosen, and
//! that count is the side's share of the first level.
//!
//! # Certification
//!
//! The engine's ladder, as for the aimed ellipsoid rule: every side's count grows in
//! proportion with the level until two levels agree to the tolerance; the change bounds the
//! coarser level's error.

use crate::aimed::{nearest_on_ellipsoid, nearest_singular_point, singular_set, SingularSet};
use crate::body::Body;
use crate::ellipse_rows::EllipseRows;
use crate::error::InteractionError;
use crate::kernel::FrameMap;
use crate::options::Interaction;
use crate::rules::NodeTable;
use crate::strategy::ladder::{evaluate_table, ladder_settings, run_ladder};
use crate::strategy::Problem;
use crate::surface_choice::Placement;
use nalgebra::Complex;
use std::f64::consts::PI;
use std::sync::{Arc, OnceLock};
use surfgrav_quadrature::{GaussLegendre, Rule1D};
use surfgrav_surfaces::{Lamina, LaminaNodes, Real, TurnedRow, Vec3};

mod circle_rows;
mod clustered_side;
mod split_row;

use circle_rows::{circle_pinches, NO_SINGULARITY};
pub(crate) use circle_rows::{CircleRows, RowSingularity};
use clustered_side::{bernstein_rho, ClusteredSide, EXACT_SEARCH, STRETCH_SEARCH};
use split_row::{sin_cos_of_piece, SplitRow, SPLIT_GAIN, SPLIT_MIN_PIECE};

/// Nodes per side (and per angular half-range) at least, at every level.
const MIN_NODES: usize = 4;

/// The factor on the predicted counts of the area rule's sides planned for one point, or
/// for a stretch whose samples do not resolve the curve near $\mathbf q$ (the Bernstein
/// model is that of one pole; a singular curve or a filled focal ellipse converges more
/// slowly). Measured over the 48 disk cases of the random-pose set (`pose_benchmark`, seed
/// 12, four per pair of kinds with a disk, gaps 0.05 to 5): with the bare prediction and the
/// one-point plan the first level's errors were 1e-10 to 7e-6. With the stretch model and
/// [`WIDTH_SLACK`](clustered_side::WIDTH_SLACK) (the `level_errors` tool, `lamina/tools.rs`),
/// the one under-resolved case of the set, disk-disk gap 0.05 #1 (narrowest angular
/// singularity 0.026), needs 0.88 of its first level with this factor; with 1.0 (on every
/// plan) the engine's ladder fell short at the first level there and took 14,952 evaluations
/// (4,500 as now).
const AREA_MARGIN: Real = 1.4;

/// The factor on the predicted counts of the area rule's sides where the stretch model
/// ([`near_stretch`]) resolves the singular curve (its narrowest angular singularity at
/// least the rim samples' spacing $2\pi/48$): the model already holds the curve's slower
/// convergence. Measured with the `level_errors` tool (seeds 12 and 13, 69 cases): with
/// [`AREA_MARGIN`] the first level within 1e-12 was at 0.44 to 0.71 of the first level
/// (median 0.57) in these cases; with this factor at most 0.9 of it.
const STRETCH_MARGIN: Real = 1.1;

/// The factor on the rim rule's predicted count (the stretch model's, [`near_stretch`], and
/// the exact rim row's of a singular circle, [`CircleRows`]). Measured with the `side_needs`
/// tool (`lamina/tools.rs`; seeds 12 to 16, 84 cases of the stretch model and 85 of a singular
/// circle): the
/// fraction of its plan the rim rule needed alone for 1e-12 was 0.4 to 0.95 (median 0.65) for
/// the stretch model (0.3 to 0.8 with the factor 1.5, 0.2 to 0.4 with the earlier 3) and 0.6
/// to 0.95 (median 0.7) for a circle. Evaluations of the 48 disk cases of `pose_benchmark`,
/// seeds 12 to 16, with the stretch model's factor 3 / 2 / 1.5 / 1.25 (the circle's 1.25):
/// 42,014 / 40,650 / 39,974 / 39,622, 43,824 / 42,402 / 41,684 / 41,328, 44,734 / 43,696 /
/// 43,176 / 42,914, 44,452 / 42,990 / 42,268 / 41,756, 43,252 / 41,942 / 41,286 / 40,964; with
/// 1.1 for a circle: 45,630 / 46,258 / 47,102 / 45,978 / 44,560 (with six cut points).
const RIM_MARGIN: Real = 1.25;

/// The factor on the predicted counts of the angular rules planned from a singular circle's
/// exact row singularities ([`CircleRows`]), and on its radial sides (planned against the
/// circle's pinches, [`circle_pinches`], and before them against 64 samples of the circle as a
/// cut: the measurements below); the rim's is [`RIM_MARGIN`]. Measured with the `side_needs`
/// tool (`lamina/tools.rs`; 85 cases with a singular circle, seeds 12 to 16; each rule alone
/// at a fraction
/// of its plan, the others at three times theirs): with this factor, the fraction each needed
/// for 1e-12 was 0.6 to 1.0 (median 0.7) for the angle and 0.3 to 0.9 (median 0.7) radial
/// (planned against the cut's two least favourable points; 0.4 to 0.75 against the pinches,
/// seeds 12, 13, 32 and 39: 0.25 and 0.95 with the cut there). Evaluations of the 48 disk cases
/// of `pose_benchmark` with factors 1.0 / 1.1 on the angle (six cut points, the rim's factor
/// 1.25 and the stretch model's 3): seeds 12 to 16 46,236 / 43,104, 44,864 / 44,468, 45,254 /
/// 45,384, 44,084 / 43,312, 45,158 / 43,264.
const ROW_MARGIN: Real = 1.1;

/// The aimed lamina rule's plan for one pose: where and how strongly each 1-D rule clusters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LaminaAim {
    /// $\varphi_q$ of the area rule's angular halves.
    angle_centre: Real,
    /// Each angular half-range $[0, \pi]$ away from the centre.
    angle: ClusteredSide,
    /// The radial split point $s_0$ and the sides from it: toward the centre (decreasing
    /// $s$) and toward the rim (increasing $s$).
    radial_origin: Real,
    inward: Option<ClusteredSide>,
    outward: Option<ClusteredSide>,
    /// The rim rule's centre angle and half-ranges.
    rim_centre: Real,
    rim: ClusteredSide,
    /// The first level (the largest predicted side count).
    pub(crate) start: u16,
    /// The area rule's singular points, as $(s_q, h)$: the nearest one and the one nearest
    /// the rim, for the angular rule of each radius.
    singular: [(Real, Real); 2],
    /// The narrowest angular singularity $\eta_0$ (that of [`LaminaAim::angle`]).
    angle_eta: Real,
    /// The number of points the plans weigh where the singular set runs near along a
    /// stretch ([`near_stretch`]); 0: planned for `q` and `q_rim` alone.
    stretch_points: usize,
    /// The angular sides for $\eta = 2^k\eta_0$, $k = 0, 1, \dots$ (each radius takes the
    /// one at or below its own $\eta$).
    angles: [ClusteredSide; ANGLE_TABLE],
    /// Y's field is symmetric about the disk's axis (`aimed::coaxial_pole`): the angular rules
    /// are exact at every level.
    coaxial: bool,
    /// Y's singular set is a circle: each row's angles are clustered toward its own
    /// singularity.
    rows: Option<CircleRows>,
    /// Where the plan is the stretch's ([`near_stretch`]): $(\cos, \sin)$ of the azimuths of
    /// the two row points ([`LaminaAim::singular`]); each row's angles turn toward its
    /// narrower one ([`entry_widths`]).
    turns: Option<[(Real, Real); 2]>,
    /// The stretch's widths are corrected by a focal ellipse's exact rows ([`EllipseRows`]),
    /// and carry [`STRETCH_MARGIN`] where the point model would carry [`AREA_MARGIN`]: the
    /// ladder treats the levels as `LadderSettings::oscillating` (the first change counts
    /// twice, and every later estimate is at least the change before it). Found by 400
    /// random draws of a disk beside a triaxial ellipsoid near contact at 1e-10 (test
    /// `a_corrected_plan_takes_its_first_change_twice`, `tests/stress.rs`): a disk beside an
    /// ellipsoid of semi-axes 0.31, 0.20, 0.077 at 3.7e-3 certified 7.8e-11 from its first
    /// change (levels 55 and 61) while its result was 1.5e-10 from the other surface's
    /// (certified 1.6e-13); with this, the draws' disagreements beyond the estimates fall
    /// from 5 to 4 of 367 (all four over the ellipsoid, as before the correction).
    corrected: bool,
    /// $\ln(1/\tau)$ of the plan (for the split rows, planned row by row).
    log_tolerance: Real,
    /// The entries of [`LaminaAim::angles`] whose rows are tried split (bit $k$: entry $k$).
    split_entries: u16,
}

/// The angular width beyond which a wider singularity no longer lowers the count (about
/// $\rho = e^{\eta}$ on the whole half-range).
const WIDEST_ETA: Real = 4.0;

/// Entries of [`LaminaAim::angles`]: $\eta$ from $\eta_0$ to $2^{9}\eta_0$ (beyond about
/// $\eta = 3$ the count no longer falls).
const ANGLE_TABLE: usize = 10;

/// The angular singularity $\eta$ on the circle of radius $s_c$ for a singular point at
/// in-plane radius $s_q$ and height $h$ (module docs).
pub(crate) fn angular_width(s_c: Real, s_q: Real, h: Real) -> Real {
    width_of_cosh(angular_cosh(s_c, s_q, h))
}

/// $\cosh\eta$ for [`angular_width`] (infinite where a radius is not positive).
fn angular_cosh(s_c: Real, s_q: Real, h: Real) -> Real {
    if s_c <= 0.0 || s_q <= 0.0 {
        return Real::INFINITY;
    }
    (s_c * s_c + s_q * s_q + h * h) / (2.0 * s_c * s_q)
}

/// $\eta$ from $\cosh\eta$, at most 10 (non-decreasing: the narrowest of several widths is
/// that of the least $\cosh\eta$).
fn width_of_cosh(c: Real) -> Real {
    c.max(1.0).acosh().min(10.0)
}

/// Rim samples of the search for the singular point nearest the rim.
const RIM_SAMPLES: usize = 48;

/// The rim samples' $(\sin\varphi_k, \cos\varphi_k)$, $\varphi_k = 2\pi k/$[`RIM_SAMPLES`]
/// (constants of the rule, computed once).
fn rim_sample_angles() -> &'static [(Real, Real); RIM_SAMPLES] {
    static TABLE: OnceLock<[(Real, Real); RIM_SAMPLES]> = OnceLock::new();
    TABLE.get_or_init(|| {
        let step = std::f64::consts::TAU / RIM_SAMPLES as Real;
        std::array::from_fn(|k| (k as Real * step).sin_cos())
    })
}

/// Steps of the search for the rim point nearest Y's singular set between the best rim
/// sample's neighbours, at most.
const RIM_SEARCH_STEPS: usize = 40;

/// The singular point of Y's field nearest to the circle of radius `radius` in X's x–y plane
/// (X's frame; `map` into Y's): the best of [`RIM_SAMPLES`] rim points, then the zero of the
/// distance's slope between its neighbours (Illinois steps; golden-section search on the
/// distance where the slope does not change sign there). (Alternating projections between
/// two curves stall where they run nearly parallel, which is where the rim matters most.)
/// Also the singular points nearest to the rim samples (X's frame), which trace where a
/// singular curve runs near.
fn nearest_to_rim(radius: Real, y: &Body, map: &FrameMap) -> (Vec3, [Vec3; RIM_SAMPLES]) {
    let set = singular_set(y);
    // At the rim point of angle φ (given by its sine and cosine): the distance d to the set,
    // the nearest point and the slope ½ d(d²)/dφ = (r − n)·∂r/∂φ (where the nearest point is
    // unique, r − n is normal to the set there, so n's own motion adds nothing).
    let gap_at = |sin: Real, cos: Real| {
        let r_y = map.apply(&Vec3::new(radius * cos, radius * sin, 0.0));
        let nearest = set.nearest(&r_y);
        let tangent = map.rotation * Vec3::new(-radius * sin, radius * cos, 0.0);
        let offset = r_y - nearest;
        ((nearest - r_y).norm(), nearest, offset.dot(&tangent))
    };
    let gap = |phi: Real| {
        let (sin, cos) = phi.sin_cos();
        gap_at(sin, cos)
    };
    let step = std::f64::consts::TAU / RIM_SAMPLES as Real;
    let mut samples = [Vec3::zeros(); RIM_SAMPLES];
    let mut slopes = [0.0; RIM_SAMPLES];
    let mut best = (Real::INFINITY, 0);
    for (k, (&(sin, cos), (sample, slope))) in rim_sample_angles()
        .iter()
        .zip(samples.iter_mut().zip(slopes.iter_mut()))
        .enumerate()
    {
        let (distance, nearest, g) = gap_at(sin, cos);
        *sample = map.back(&(nearest - map.offset));
        *slope = g;
        if distance < best.0 {
            best = (distance, k);
        }
    }
    let k = best.1;
    let phi = k as Real * step;
    // The slope's zero about the best sample: in [φ_k − step, φ_k] where the slope there is
    // positive, in [φ_k, φ_k + step] where it is negative.
    let (before, at, after) = (
        slopes[(k + RIM_SAMPLES - 1) % RIM_SAMPLES],
        slopes[k],
        slopes[(k + 1) % RIM_SAMPLES],
    );
    let bracket = if at > 0.0 && before < 0.0 {
        Some(((phi - step, before), (phi, at)))
    } else if at < 0.0 && after > 0.0 {
        Some(((phi, at), (phi + step, after)))
    } else {
        None
    };
    let nearest = match bracket {
        _ if at == 0.0 => gap(phi).1,
        Some(((mut lo, mut g_lo), (mut hi, mut g_hi))) => {
            // Illinois steps (regula falsi, halving the value kept twice in a row): the
            // bracket shrinks to 1e-12 of the sample spacing.
            let (mut found, mut side) = (None, 0);
            for _ in 0..RIM_SEARCH_STEPS {
                if hi - lo <= 1e-12 * step {
                    break;
                }
                let secant = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
                let x = if secant > lo && secant < hi {
                    secant
                } else {
                    0.5 * (lo + hi)
                };
                let (_, nearest, g) = gap(x);
                found = Some((x, nearest));
                if g < 0.0 {
                    (lo, g_lo) = (x, g);
                    if side == -1 {
                        g_hi *= 0.5;
                    }
                    side = -1;
                } else if g > 0.0 {
                    (hi, g_hi) = (x, g);
                    if side == 1 {
                        g_lo *= 0.5;
                    }
                    side = 1;
                } else {
                    break;
                }
            }
            match found {
                Some((_, nearest)) => nearest,
                None => gap(0.5 * (lo + hi)).1,
            }
        }
        None => golden_section(&|phi| gap(phi).0, phi - step, phi + step)
            .map_or_else(|| gap(phi).1, |phi| gap(phi).1),
    };
    (map.back(&(nearest - map.offset)), samples)
}

/// The minimum of `f` between `lo` and `hi` by 40 golden-section steps (its abscissa).
fn golden_section(f: &dyn Fn(Real) -> Real, lo: Real, hi: Real) -> Option<Real> {
    let (mut lo, mut hi) = (lo, hi);
    let ratio = 0.5 * (5.0_f64.sqrt() - 1.0);
    let (mut c, mut d) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..40 {
        if fc < fd {
            hi = d;
            d = c;
            fd = fc;
            c = hi - ratio * (hi - lo);
            fc = f(c);
        } else {
            lo = c;
            c = d;
            fc = fd;
            d = lo + ratio * (hi - lo);
            fd = f(d);
        }
    }
    let x = 0.5 * (lo + hi);
    x.is_finite().then_some(x)
}

/// The most singular points a plan weighs (the nearest, the one nearest the rim and a
/// spread of the rim samples' nearest points).
const MAX_SINGULAR: usize = 5;

/// The singular points, as (azimuth, in-plane radius, height) in X's frame, that the 1-D
/// rules are planned against: `q`, `q_rim` and, where Y's singular set is a curve or a
/// filled ellipse that runs near the disk along a stretch, the points of it nearest to the
/// rim samples whose angular width on the rim is within [`STRETCH`] times the narrowest
/// (every other one, or sparser, so that at most [`MAX_SINGULAR`] are kept). Returns the
/// points and their count.
fn near_stretch(
    radius: Real,
    q: &Vec3,
    q_rim: &Vec3,
    samples: &[Vec3; RIM_SAMPLES],
) -> ([(Real, Real, Real); MAX_SINGULAR], usize) {
    let polar = |p: &Vec3| (p.y.atan2(p.x), p.xy().norm(), p.z.abs());
    let mut points = [(0.0, 0.0, 0.0); MAX_SINGULAR];
    points[0] = polar(q);
    points[1] = polar(q_rim);
    let eta = |p: &Vec3| angular_width(radius, p.xy().norm(), p.z.abs());
    let narrowest = eta(q_rim).min(eta(q));
    // Points that are not (nearly) q or q_rim themselves: a point singular set gives the
    // same point for every sample.
    let distinct = |p: &Vec3| {
        let close = 1e-3 * radius + 0.05 * (p - q_rim).norm().min((p - q).norm());
        (p - q).norm() > close && (p - q_rim).norm() > close
    };
    let mut near = [0usize; RIM_SAMPLES];
    let mut count = 0;
    for (k, p) in samples.iter().enumerate() {
        if eta(p) <= STRETCH * narrowest && distinct(p) {
            near[count] = k;
            count += 1;
        }
    }
    let stride = count.div_ceil(MAX_SINGULAR - 2).max(1);
    let mut len = 2;
    for &k in near[..count].iter().step_by(stride) {
        points[len] = polar(&samples[k]);
        len += 1;
    }
    (points, len)
}

/// The least angular width of each point of a stretch (`stretch`, as (azimuth, in-plane
/// radius, height)) over the rows $s \in (0, R]$ of entry `k` of the angular table, for each
/// of the two points `rows` (q and the point nearest the rim) over the rows it is the
/// narrower of, written to `out[f]`; `any[f]`: some row of positive radius is entry `k`'s
/// with point `f` the narrower. A row's entry is that of its narrower width $\eta(s)$
/// (the rows' own choice, [`LaminaAim::angle_at`]): $2^k\eta_0 \le \eta(s) < 2^{k+1}\eta_0$.
/// A point's width on the circle of radius $s$, $\cosh\eta = (s^2 + \rho^2)/(2 s s_p)$ with
/// $\rho^2 = s_p^2 + h_p^2$, is least at $s = \rho$ and grows away from it on both sides, so
/// over a union of intervals it is least at $\rho$ or at an end of one; the ends are where a
/// row point's width crosses $2^k\eta_0$ or $2^{k+1}\eta_0$ (the roots of
/// $s^2 - 2 s s_p\cosh\eta + \rho^2 = 0$), where the two row points are equally wide, and
/// the rim.
fn entry_widths(
    radius: Real,
    rows: &[(Real, Real); 2],
    eta: Real,
    k: usize,
    stretch: &[(Real, Real, Real)],
    out: &mut [[Real; MAX_SINGULAR]; 2],
) -> [bool; 2] {
    // η ≥ X for η = min(acosh c, 10) (width_of_cosh): c ≥ cosh X, and no row beyond 10.
    let cosh_of = |x: Real| if x <= 10.0 { x.cosh() } else { Real::INFINITY };
    let bound = |j: usize| eta * Real::from(j as i32).exp2();
    let low = if k == 0 { 1.0 } else { cosh_of(bound(k)) };
    let high = if k + 1 == ANGLE_TABLE {
        Real::INFINITY
    } else {
        cosh_of(bound(k + 1))
    };
    // Ends computed to rounding lie on a boundary: admitted on either side.
    let slack = 1e-12;
    let mut best = [[Real::INFINITY; MAX_SINGULAR]; 2];
    let mut any = [false; 2];
    let mut visit = |s: Real| {
        if !(s > 0.0 && s <= radius) {
            return;
        }
        let c = rows.map(|(s_p, h_p)| angular_cosh(s, s_p, h_p));
        let least = c[0].min(c[1]);
        if !(least.is_finite() && least >= low * (1.0 - slack) && least < high * (1.0 + slack)) {
            return;
        }
        for f in 0..2 {
            if c[f] <= least * (1.0 + slack) {
                any[f] = true;
                for (b, &(_, s_j, h_j)) in best[f].iter_mut().zip(stretch) {
                    *b = b.min(angular_cosh(s, s_j, h_j));
                }
            }
        }
    };
    visit(radius);
    for &(_, s_j, h_j) in stretch {
        visit((s_j * s_j + h_j * h_j).sqrt());
    }
    for c in [low, high] {
        if !c.is_finite() {
            continue;
        }
        for &(s_p, h_p) in rows {
            // The larger root, and the smaller from the roots' product ρ² (b − √(b² − ρ²)
            // cancels where the width is large).
            let (b, rho2) = (s_p * c, s_p * s_p + h_p * h_p);
            let disc = b * b - rho2;
            if disc >= 0.0 {
                let larger = b + disc.sqrt();
                visit(larger);
                visit(rho2 / larger);
            }
        }
    }
    // Equal widths: s_r (s² + ρ_q²) = s_q (s² + ρ_r²).
    let [(s_q, h_q), (s_r, h_r)] = *rows;
    if s_r != s_q {
        let square = (s_q * (s_r * s_r + h_r * h_r) - s_r * (s_q * s_q + h_q * h_q)) / (s_r - s_q);
        if square > 0.0 {
            visit(square.sqrt());
        }
    }
    for (o, b) in out.iter_mut().zip(&best) {
        for (o, &b) in o.iter_mut().zip(b) {
            *o = width_of_cosh(b);
        }
    }
    any
}

/// A root of [`EllipseRows`] stands for a stretch point's row singularity where it lies within
/// this many widths (at least 0.1 rad) of the point's azimuth: one farther is another place's.
const EXACT_NEAR: Real = 3.0;

/// A stretch point's exact width is taken at most this many times its point model's.
const EXACT_MAX_RATIO: Real = 2.0;

/// A rim sample's nearest singular point joins the plan where its angular width on the rim
/// is within this factor of the narrowest.
const STRETCH: Real = 4.0;

/// Gauss–Legendre nodes per angular half-range $[0, \pi]$ at the first level where Y's field is
/// symmetric about the disk's axis (`aimed::coaxial_pole`): the area integrands are then a
/// constant plus $\cos\varphi$ and $\sin\varphi$ terms, which 8 nodes integrate to about
/// $5\cdot10^{-15}$ (the error bound $\pi^{17}(8!)^4/(17\\,(16!)^3)$ for the cosine), and later
/// levels scale the count with the radial ones.
const COAXIAL_ANGLES: Real = 8.0;

/// The aimed rule is used only where Y's singular set comes within this many disk radii of
/// the disk; farther, the fixed lamina table (azimuth clustered toward Y, halved by a mirror
/// symmetry) is cheaper. Chosen by timing the 48 disk cases of the random-pose set
/// (`pose_benchmark`, seed 12) with the aimed rule everywhere and within 1, 2 and 3 radii:
/// within 2 was as fast as within 3 and faster than the others (within 1, a spheroid beside a
/// small disk at gap 0.05 took five times longer; everywhere, the far cases paid the aim).
pub(crate) const AIMED_LAMINA_REACH: Real = 2.0;

/// The aim for integrating over the lamina `lamina` (integration frame: the disk in its x–y
/// plane about the origin) in Y's field (`map`: X's frame into Y's); `None` where Y's
/// singular set is farther than [`AIMED_LAMINA_REACH`] radii from the disk.
pub(crate) fn lamina_aim(
    lamina: &Lamina,
    y: &Body,
    map: &FrameMap,
    tolerance: Real,
) -> Option<LaminaAim> {
    let radius = lamina.radius();
    let axes = Vec3::new(radius, radius, 0.0);
    let (p, q) = nearest_singular_point(y, map, |r| nearest_on_ellipsoid(&axes, r), radius);
    if (q - p).norm() > AIMED_LAMINA_REACH * radius {
        return None;
    }
    let s_q = q.xy().norm();
    let h = q.z.abs();
    let angle_centre = q.y.atan2(q.x);
    // The narrowest angular singularity of q over the circles s ≤ R (at s = |q|), and that
    // of the singular point nearest the rim (a singular set that is a curve or a filled
    // ellipse comes nearer the rim elsewhere than at q).
    // On a common axis the singular points nearest the disk form a circle about its centre,
    // all at the same radius and height: q alone stands for them.
    let coaxial = super::coaxial_pole(&axes, y, map).is_some();
    // Where Y's singular set is a circle, each row's singularities are known exactly
    // ([`CircleRows`]): each row's angles are clustered toward its own narrower singularity,
    // and the table's entry k (for rows whose narrower singularity is at least 2^k η₀ wide)
    // is planned against that and the least favourable other singularity of the sampled rows
    // of about that width; the rim and the radial sides likewise from the circle itself.
    let circle_radius = match singular_set(y) {
        SingularSet::Circle(c) if !coaxial => Some(c),
        _ => None,
    };
    let circle = circle_radius.map(|c| CircleRows::new(c, map));
    // Otherwise: the singular point nearest the rim and, where the singular set runs near
    // along a stretch, points spread along it (a curve's neighbouring points, off the
    // clustering point, limit a rule clustered for the nearest one) against which every 1-D
    // rule is planned; without a stretch, against q and q_rim alone.
    let (q_rim, samples) = match circle {
        Some(_) => (q, [q; RIM_SAMPLES]),
        None => nearest_to_rim(radius, y, map),
    };
    let rim_eta = angular_width(radius, q_rim.xy().norm(), q_rim.z.abs());
    let eta = angular_width(q.norm().min(radius), s_q, h).min(rim_eta);
    let (points, len) = if coaxial || circle.is_some() {
        ([(0.0, 0.0, 0.0); MAX_SINGULAR], 0)
    } else {
        near_stretch(radius, &q, &q_rim, &samples)
    };
    let stretch = &points[..if len > 2 { len } else { 0 }];
    // The stretch model needs no margin for a curve where its samples resolve the curve near
    // q (the narrowest angular singularity at least the samples' spacing).
    let margin = if !stretch.is_empty() && eta >= std::f64::consts::TAU / RIM_SAMPLES as Real {
        STRETCH_MARGIN
    } else {
        AREA_MARGIN
    };
    let offset = |phi: Real, centre: Real| {
        let d = (phi - centre).rem_euclid(std::f64::consts::TAU);
        d.min(std::f64::consts::TAU - d)
    };
    // The angular singularities of the stretch on its narrowest circles, widened by 2^k.
    let mut narrowest = [Complex::new(0.0, 0.0); MAX_SINGULAR];
    for (o, &(phi, s_k, h_k)) in narrowest.iter_mut().zip(stretch) {
        let width = angular_width((s_k * s_k + h_k * h_k).sqrt().min(radius), s_k, h_k);
        *o = Complex::new(offset(phi, angle_centre), width);
    }
    // Where the stretch is a triaxial body's focal ellipse, each point's width on its own
    // narrowest row, exact ([`EllipseRows`]) over the point model's (at least 1).
    let mut exact_ratio = [1.0; MAX_SINGULAR];
    let mut exact_rows = false;
    if let (SingularSet::Ellipse(axes), false) = (singular_set(y), coaxial) {
        if let Some(rows) = EllipseRows::of_axes(&axes, map) {
            exact_rows = !stretch.is_empty();
            for (r, &(phi, s_k, h_k)) in exact_ratio.iter_mut().zip(stretch) {
                let s = (s_k * s_k + h_k * h_k).sqrt().min(radius);
                let width = angular_width(s, s_k, h_k);
                let (sin, cos) = phi.sin_cos();
                let t = rows.parameter_of(&map.apply(&Vec3::new(s * cos, s * sin, 0.0)));
                if let Some(root) = rows.solve(s, Complex::new(phi, width), Complex::new(t, 0.0)) {
                    let moved = (root.phi.re - phi + PI).rem_euclid(std::f64::consts::TAU) - PI;
                    if moved.abs() <= EXACT_NEAR * width.max(0.1) {
                        *r = (root.phi.im / width).clamp(1.0, EXACT_MAX_RATIO);
                    }
                }
            }
        }
    }
    // With the exact rows' correction the point model's narrowest widths no longer need the
    // unresolved stretch's margin: seeds 24 and 34, ellipsoid-disk gap 0.05 #0 and #1 (narrowest
    // widths 0.110 and 0.120, below the rim samples' spacing), needed at most 0.95 of each 1-D
    // rule's plan with STRETCH_MARGIN (`side_needs`), and take 4,820 and 5,086 evaluations
    // instead of 7,466 and 7,484 (pose sets 12-72: -0.2 %, 0 estimates exceeded).
    let margin = if exact_rows { STRETCH_MARGIN } else { margin };
    // The two points whose narrower width picks a row's table entry and, for the stretch, its
    // turn ([`LaminaAim::angle_at`]), as (in-plane radius, height) and azimuth.
    let row_points = [(s_q, h), (q_rim.xy().norm(), q_rim.z.abs())];
    let row_centres = [angle_centre, q_rim.y.atan2(q_rim.x)];
    let angular = |k: i32| {
        let mut out = narrowest;
        for o in &mut out {
            o.im *= Real::from(k).exp2();
        }
        out
    };
    // Equally spaced rows, the row through q, and rows on either side of q's radius at
    // offsets growing from q's height ([`NEAR_ROW_SAMPLES`]), where the rows change fastest.
    let mut sampled = [[RowSingularity::NONE; 2]; ROW_SAMPLES + 1 + 2 * NEAR_ROW_SAMPLES];
    if let Some(rows) = &circle {
        let step = h.max(1e-6 * radius);
        for (m, o) in sampled.iter_mut().enumerate() {
            let s = if m < ROW_SAMPLES {
                radius * (m + 1) as Real / ROW_SAMPLES as Real
            } else if m == ROW_SAMPLES {
                q.norm().min(radius)
            } else {
                let j = m - ROW_SAMPLES - 1;
                let offset = step * NEAR_ROW_RATIO.powi((j / 2) as i32);
                let s = if j.is_multiple_of(2) {
                    s_q - offset
                } else {
                    s_q + offset
                };
                if s <= 0.0 || s >= radius {
                    continue;
                }
                s
            };
            *o = rows.at(s);
        }
    }
    // The table's first entry: the narrowest sampled row's singularity, or the model's.
    let eta = match circle {
        Some(_) => sampled
            .iter()
            .map(|r| r[0].width)
            .fold(NO_SINGULARITY, Real::min)
            .max(1e-12),
        None => eta,
    };
    // Each sampled row's table entry and its other singularity relative to its own centre,
    // with that singularity's Bernstein parameter for plain Gauss–Legendre on the half-range.
    let mut others = [(usize::MAX, Real::INFINITY, Complex::new(0.0, 0.0));
        ROW_SAMPLES + 1 + 2 * NEAR_ROW_SAMPLES];
    if circle.is_some() {
        for (o, [near, other]) in others.iter_mut().zip(&sampled) {
            if other.width < NO_SINGULARITY {
                let t = Complex::new(other.offset_from(near), other.width);
                *o = (table_entry(near.width, eta), bernstein_rho(t / PI), t);
            }
        }
    }
    let plan_exact = |k: usize| {
        // The other singularity least favourable to plain Gauss–Legendre of the sampled rows
        // in about this entry.
        let mut other_least = (Real::INFINITY, Complex::new(0.0, 0.0));
        for &(entry, proxy, t) in &others {
            if entry.abs_diff(k) <= 1 && proxy < other_least.0 {
                other_least = (proxy, t);
            }
        }
        let points = [Complex::new(0.0, eta * (k as Real).exp2()), other_least.1];
        let len = if other_least.0.is_finite() { 2 } else { 1 };
        ClusteredSide::plan_many(PI, &points[..len], tolerance, EXACT_SEARCH)
    };
    let plan_angle = |k: i32| {
        if circle.is_some() {
            plan_exact(k as usize)
        } else if stretch.is_empty() {
            ClusteredSide::plan(PI, Complex::new(0.0, eta * Real::from(k).exp2()), tolerance)
        } else {
            // Each point at its least width over the rows of this entry where it has any
            // (`entry_widths`); otherwise every point at its narrowest, widened by 2^k.
            // Rows turn toward their narrower row point (q or the one nearest the rim):
            // each family's rows see the points at offsets from its own centre.
            let mut widths = [[0.0; MAX_SINGULAR]; 2];
            let any = entry_widths(radius, &row_points, eta, k as usize, stretch, &mut widths);
            for family in &mut widths {
                for (w, &r) in family.iter_mut().zip(&exact_ratio) {
                    *w *= r;
                }
            }
            if !any[0] && !any[1] {
                return ClusteredSide::plan_many(
                    PI,
                    &angular(k)[..stretch.len()],
                    tolerance,
                    STRETCH_SEARCH,
                );
            }
            let mut points = [Complex::new(0.0, 0.0); 2 * MAX_SINGULAR];
            let mut len = 0;
            for f in 0..2 {
                if !any[f] {
                    continue;
                }
                for (&(phi, ..), &width) in stretch.iter().zip(&widths[f]) {
                    points[len] = Complex::new(offset(phi, row_centres[f]), width);
                    len += 1;
                }
            }
            ClusteredSide::plan_many(PI, &points[..len], tolerance, STRETCH_SEARCH)
        }
    };
    // A radial side from `origin` (`sign` -1: inward, +1: outward) of `length`, singular at
    // `singular` (q's model) and at every point of the stretch, or at a singular circle's
    // pinches ([`circle_pinches`]).
    let pinches = match (circle_radius, &circle) {
        (Some(c), Some(rows)) => circle_pinches(c, rows, map),
        _ => ([Complex::new(0.0, 0.0); 8], 0),
    };
    // And at least CUT_FLOOR of the plan against the circle's two least favourable points
    // taken as a cut ([`circle_cut`]).
    let mut cut = [(0.0, 0.0); CUT_SAMPLES + 2];
    let cut_len = circle_radius.map_or(0, |c| circle_cut(c, map, &mut cut));
    let radial = |origin: Real, sign: Real, length: Real, singular: Complex<Real>| {
        let (pinches, len) = pinches;
        if len > 0 {
            let mut all = [singular; 9];
            for (o, &p) in all.iter_mut().skip(1).zip(&pinches[..len]) {
                *o = Complex::new(sign * (p.re - origin), p.im.abs().max(1e-12 * radius));
            }
            let side = ClusteredSide::plan_many(length, &all[..=len], tolerance, STRETCH_SEARCH);
            // The cut's points least favourable to plain Gauss–Legendre on the side.
            let mut chosen = [(Real::INFINITY, Complex::new(0.0, 0.0)); CUT_PLANNED];
            for &(rho, z) in &cut[..cut_len] {
                let t = Complex::new(sign * (rho - origin), z.max(1e-12 * radius));
                let proxy = bernstein_rho(t / length);
                let worst = chosen
                    .iter_mut()
                    .max_by(|a, b| a.0.total_cmp(&b.0))
                    .expect("CUT_PLANNED > 0");
                if proxy < worst.0 {
                    *worst = (proxy, t);
                }
            }
            let mut all = [singular; CUT_PLANNED + 1];
            let mut len = 1;
            for &(proxy, t) in &chosen {
                if proxy.is_finite() {
                    all[len] = t;
                    len += 1;
                }
            }
            let cut_side = ClusteredSide::plan_many(length, &all[..len], tolerance, STRETCH_SEARCH)
                .with_margin(CUT_FLOOR);
            return if cut_side.predicted > side.predicted {
                cut_side
            } else {
                side
            };
        }
        if stretch.is_empty() {
            return ClusteredSide::plan(length, singular, tolerance);
        }
        let mut all = [singular; MAX_SINGULAR + 1];
        // The stretch's points at their own heights: the exact rows' ratio ([`EllipseRows`])
        // is the rows' angular singularity, not the radial integrand's. Measured: seed 62,
        // ellipsoid-disk gap 0.05 #0, with the heights widened by it, the radial sides
        // needed 0.95 of their plan (`side_needs`) and the ladder took 37,176 evaluations
        // through six levels; at their own heights, 15,234 (pose sets 12-72: -0.35 %).
        for (o, &(_, s_k, h_k)) in all.iter_mut().skip(1).zip(stretch) {
            *o = Complex::new(sign * (s_k - origin), h_k.max(1e-12 * radius));
        }
        ClusteredSide::plan_many(length, &all[..=stretch.len()], tolerance, STRETCH_SEARCH)
    };
    let (radial_origin, inward, outward) = if s_q >= radius {
        // Beyond the rim: one side from the rim inward, the singularity beyond its end.
        let singular = Complex::new(-(s_q - radius), h.max(1e-12 * radius));
        (radius, Some(radial(radius, -1.0, radius, singular)), None)
    } else if s_q <= 0.5 * h {
        // Over the centre: one side from the centre outward.
        let singular = Complex::new(s_q, h);
        (0.0, None, Some(radial(0.0, 1.0, radius, singular)))
    } else {
        let singular = Complex::new(0.0, h.max(1e-12 * radius));
        (
            s_q,
            Some(radial(s_q, -1.0, s_q, singular)),
            Some(radial(s_q, 1.0, radius - s_q, singular)),
        )
    };
    // A singular circle's rim row.
    let rim_row = circle.map(|rows| rows.at(radius));
    let rim_centre = match &rim_row {
        Some([near, _]) => near.azimuth(),
        None => q_rim.y.atan2(q_rim.x),
    };
    let radial_margin = if circle.is_some() { ROW_MARGIN } else { margin };
    let (inward, outward) = (
        inward.map(|side| side.with_margin(radial_margin)),
        outward.map(|side| side.with_margin(radial_margin)),
    );
    let log_tolerance = (1.0 / tolerance).ln().max(0.0);
    let mut split_entries = 0u16;
    let (angle, angles, rim) = if coaxial {
        // The integrand does not depend on the angle beyond the moment arm's cos φ and sin φ:
        // plain Gauss–Legendre with COAXIAL_ANGLES nodes on each half-range.
        let plain = ClusteredSide {
            length: PI,
            width: Real::INFINITY,
            predicted: COAXIAL_ANGLES,
            mu: 0.0,
        };
        (plain, [plain; ANGLE_TABLE], plain)
    } else {
        // The exact rows need no margin for a curve's slower convergence.
        let angle_margin = if circle.is_some() { ROW_MARGIN } else { margin };
        let angle = plan_angle(0).with_margin(angle_margin);
        let mut angles = [angle; ANGLE_TABLE];
        for k in 1..ANGLE_TABLE {
            if eta * Real::from(k as i32 - 1).exp2() > WIDEST_ETA {
                // Beyond this the count no longer falls: the wider entries repeat the last.
                angles[k] = angles[k - 1];
                continue;
            }
            let planned = plan_angle(k as i32).with_margin(angle_margin);
            if planned.predicted < angle.predicted || (!stretch.is_empty() && circle.is_none()) {
                angles[k] = planned;
            }
        }
        // The stretch's entries are planned from their own rows: a wider entry can take more
        // nodes than the first (a stretch point at its narrowest on rows far from q's
        // radius). The sizes and the start count the dearest.
        let angle =
            angles
                .iter()
                .copied()
                .fold(angle, |a, b| if b.predicted > a.predicted { b } else { a });
        // The entries whose plan the other singularity of their rows sets: planned for the
        // narrower singularity alone, they would take at most SPLIT_GAIN of the nodes; only
        // their rows are tried split (planning a split row costs about as much as a few of
        // its nodes).
        if circle.is_some() {
            for (k, side) in angles.iter().enumerate() {
                let width = eta * Real::from(k as i32).exp2();
                let alone = ClusteredSide::toward_end(PI, width, Real::INFINITY, log_tolerance)
                    .with_margin(angle_margin);
                // Four pieces of at least SPLIT_MIN_PIECE nodes, two of them about as many
                // as the half-range alone.
                let least = 2.0 * (alone.predicted.max(SPLIT_MIN_PIECE) + SPLIT_MIN_PIECE);
                if least <= SPLIT_GAIN * 2.0 * side.predicted {
                    split_entries |= 1 << k;
                }
            }
        }
        let rim = if let Some([near, other]) = &rim_row {
            let all = [
                Complex::new(0.0, near.width),
                Complex::new(other.offset_from(near), other.width),
            ];
            ClusteredSide::plan_many(PI, &all, tolerance, EXACT_SEARCH).with_margin(RIM_MARGIN)
        } else if stretch.is_empty() {
            ClusteredSide::plan(PI, Complex::new(0.0, rim_eta), tolerance).with_margin(RIM_MARGIN)
        } else {
            let mut all = [Complex::new(0.0, 0.0); MAX_SINGULAR];
            for (o, &(phi, s_k, h_k)) in all.iter_mut().zip(stretch) {
                *o = Complex::new(offset(phi, rim_centre), angular_width(radius, s_k, h_k));
            }
            ClusteredSide::plan_many(PI, &all[..stretch.len()], tolerance, STRETCH_SEARCH)
                .with_margin(RIM_MARGIN)
        };
        (angle, angles, rim)
    };
    let largest = [Some(angle), inward, outward]
        .iter()
        .flatten()
        .map(|side| side.predicted)
        .fold(MIN_NODES as Real, Real::max);
    Some(LaminaAim {
        angle_centre,
        angle,
        radial_origin,
        inward,
        outward,
        rim_centre,
        rim,
        start: (largest.ceil() as u16).min(crate::rules::MAX_TRANSVERSE),
        singular: row_points,
        angle_eta: eta,
        stretch_points: stretch.len(),
        angles,
        coaxial,
        rows: circle,
        turns: (!stretch.is_empty() && circle.is_none() && !coaxial).then(|| {
            row_centres.map(|phi| {
                let (sin, cos) = phi.sin_cos();
                (cos, sin)
            })
        }),
        log_tolerance,
        split_entries,
        corrected: exact_rows,
    })
}

/// Samples of a singular circle for the radial plan ([`circle_cut`]).
const CUT_SAMPLES: usize = 64;

/// Points of the cut the floor of a radial side is planned against ([`CUT_FLOOR`]; besides the
/// nearest singular point's model): the least favourable ones for plain Gauss–Legendre on the
/// side. Measured when the cut plan was the plan itself, on the 48
/// disk cases of `pose_benchmark`, seeds 12 to 16, evaluations with 1 / 2 / 3 / 6 points:
/// 42,014 / 42,014 / 42,782 / 43,104, 46,046 / 43,824 / 44,110 / 44,460, 43,614 / 44,734 /
/// 45,340 / 45,384, 45,252 / 44,452 / 44,140 / 44,140, 43,056 / 43,252 / 42,526 / 43,220;
/// with 2 the radial sides needed 0.3 to 0.9 of their plans (`side_needs`; 0.2 to 0.9 with
/// 6), and planning a disk side took 7.1 µs (8.6 µs with 6; `plan_timing`).
const CUT_PLANNED: usize = 2;

/// The singular circle of radius `c` (Y's x–y plane about Y's centroid) in X's frame as
/// (in-plane radius ρ, height |z|) at [`CUT_SAMPLES`] equally spaced points and at its
/// crossings of X's plane (where it crosses it), written to `out`; returns the count.
fn circle_cut(c: Real, map: &FrameMap, out: &mut [(Real, Real); CUT_SAMPLES + 2]) -> usize {
    let centre = map.back(&(-map.offset));
    let (e1, e2) = (
        map.back(&Vec3::new(c, 0.0, 0.0)),
        map.back(&Vec3::new(0.0, c, 0.0)),
    );
    let at = |(sin, cos): (Real, Real)| {
        let p = centre + e1 * cos + e2 * sin;
        (p.xy().norm(), p.z.abs())
    };
    static ANGLES: OnceLock<[(Real, Real); CUT_SAMPLES]> = OnceLock::new();
    let angles = ANGLES.get_or_init(|| {
        let step = std::f64::consts::TAU / CUT_SAMPLES as Real;
        std::array::from_fn(|k| (k as Real * step).sin_cos())
    });
    for (o, &angle) in out.iter_mut().zip(angles) {
        *o = at(angle);
    }
    let mut len = CUT_SAMPLES;
    // z(θ) = z₀ + A cos(θ − θ₀) = 0.
    let amplitude = e1.z.hypot(e2.z);
    if amplitude > 0.0 && centre.z.abs() <= amplitude {
        let theta0 = e2.z.atan2(e1.z);
        let half = (-centre.z / amplitude).clamp(-1.0, 1.0).acos();
        for theta in [theta0 + half, theta0 - half] {
            out[len] = (at(theta.sin_cos()).0, 0.0);
            len += 1;
        }
    }
    len
}

/// The least fraction of the cut plan a radial side planned against a singular circle's
/// pinches ([`circle_pinches`]) takes: the plan against the circle's two least favourable
/// points as a cut ([`circle_cut`], [`CUT_PLANNED`]; before the pinches, the plan itself) times
/// this. The pinches are where the exact row integral is singular, but the rows are summed by
/// rules whose errors vary with the radius, and near contact the radial rule then needs more
/// than the pinches predict. Measured: a disk of radius 0.47 held 3.7e-4 from a unit disk (a
/// case of the property test `disks_near_contact`, `tests/stress.rs`), over the unit disk at
/// 1e-10: planned against the pinches alone (55 nodes inward, 25 outward; the cut's 255 and
/// 352), the radial rule needed about 1.25 times its plan, and two levels at 0.8 and 0.88 of
/// it changed by 1.0e-12 with a true error of 2.3e-12 (the errors fall by 0.7 per step
/// there); with this floor it certifies 1.1e-11 with a true error of 1.2e-12 (48,702
/// evaluations; 193,854 with the cut plan itself). On the random-pose sets of seeds 12 to 16,
/// 32 and 39 the floor raises no plan but a few (587,733 evaluations, 588,659 with it; 590,632
/// with 0.35): there the pinch plans' sides needed 0.4 to 0.75 of them.
const CUT_FLOOR: Real = 0.25;

/// Sampled radii of [`CircleRows`] for the plan of the angular table (equally spaced).
const ROW_SAMPLES: usize = 16;

/// Sampled rows of [`CircleRows`] on each side of the nearest singular point's radius $s_q$
/// for the plan of the angular table, at offsets $h, 3h, 9h, \dots$ ($h$ its height;
/// [`NEAR_ROW_RATIO`]). Near $s_q$ both singularities of a row are narrow and move fast with
/// $s$, and the radial rule, clustered toward $s_q$, puts many rows there; equally spaced
/// samples alone missed them. Measured: a disk of radius 0.61 held 3.0e-4 from a unit disk
/// (a case of the property test `disks_near_contact`; `tests/stress.rs`), over the unit disk
/// at 1e-11: the angular rule's error wandered between 4e-13 and 2.4e-10 over levels 200 to
/// 280 (rows just beyond $s_q$, whose other singularity lies 0.4-0.9 rad off and 0.09-0.14
/// wide, were less favourable to their angular rules than any sampled row), and the ladder
/// certified an estimate of 1.7e-12 with a true error of 4.7e-11; with these rows the error
/// falls steadily (4.4e-13 at level 200, 2.0e-15 at 240), and it certifies 2.8e-14 with a
/// true error of 9.1e-15. The random-pose set (`pose_benchmark`, seeds 12-16): 78,430 /
/// 77,004 / 85,160 / 79,306 / 86,144 evaluations before, +8 / +12 / 0 / +108 / 0 with them,
/// 0 violations; `near_axis_sweep` (seeds 2026, 7, 99) unchanged.
const NEAR_ROW_SAMPLES: usize = 8;

/// See [`NEAR_ROW_SAMPLES`].
const NEAR_ROW_RATIO: Real = 3.0;

/// The entry of the angular table for a row whose narrowest singularity is `width` wide, with
/// `eta` that of the table's first entry: the largest $k$ with $2^k\eta \le$ `width`.
fn table_entry(width: Real, eta: Real) -> usize {
    let steps = (width / eta).log2().floor();
    if steps.is_finite() && steps > 0.0 {
        (steps as usize).min(ANGLE_TABLE - 1)
    } else {
        0
    }
}

impl LaminaAim {
    /// A side's count at `level` (its predicted share, scaled with the level).
    fn count(&self, side: &ClusteredSide, level: u16) -> usize {
        self.scaled(side.predicted, level)
    }

    /// A predicted count scaled to `level`.
    fn scaled(&self, predicted: Real, level: u16) -> usize {
        let scaled = predicted * Real::from(level) / Real::from(self.start.max(1));
        (scaled.ceil() as usize).max(MIN_NODES)
    }

    /// The angular side at radius `s`: the narrowest angular singularity of the two singular
    /// points on the circle of radius `s`, never wider clustered than the whole rule's.
    /// With the turn of its angles: toward the narrower point where the plan is the
    /// stretch's ([`LaminaAim::turns`]; the shared lists are then about 0), none otherwise
    /// (about [`LaminaAim::angle_centre`]).
    fn angle_at(&self, s: Real) -> (ClusteredSide, (Real, Real)) {
        let c = self.singular.map(|(s_q, h)| angular_cosh(s, s_q, h));
        let eta = width_of_cosh(c[0].min(c[1]));
        // The tabulated side of the largest η not above this one (narrower: at least as
        // many nodes as the circle's own plan would take).
        let side = self.angles[table_entry(eta, self.angle_eta)];
        let turn = match self.turns {
            Some(turns) if c[0] <= c[1] => turns[0],
            Some(turns) => turns[1],
            None => (1.0, 0.0),
        };
        (side, turn)
    }

    /// Whether every 1-D rule of the table has more nodes at level `to` than at `from` (see
    /// [`run_ladder`]): the radial sides and, unless Y's field is symmetric about the disk's
    /// axis (the angular rules are then exact), every angular side of the table (the first is
    /// [`LaminaAim::angle`]) and the rim's.
    /// `split`: level `from` has split rows ([`SplitRow`]).
    pub(crate) fn refines(&self, from: u16, to: u16, split: bool) -> bool {
        let more = |side: &ClusteredSide| self.count(side, to) > self.count(side, from);
        // The split rows' pieces, planned row by row, each at least SPLIT_MIN_PIECE nodes at
        // the first level: a node more on each where the step adds one to the least of them
        // (p·(to − from)/start ≥ 1).
        let pieces = match self.rows {
            Some(_) if split => {
                self.scaled(SPLIT_MIN_PIECE, to) > self.scaled(SPLIT_MIN_PIECE, from)
                    && SPLIT_MIN_PIECE * Real::from(to.saturating_sub(from))
                        >= Real::from(self.start.max(1))
            }
            _ => true,
        };
        [self.inward, self.outward].iter().flatten().all(more)
            && (self.coaxial || (more(&self.rim) && pieces && self.angles.iter().all(more)))
    }

    /// The number of field evaluations at `level` (area nodes and rim nodes): at most this
    /// (the angular count of each radius is at most that of the whole rule).
    pub(crate) fn size(&self, level: u16) -> usize {
        let radial: usize = [self.inward, self.outward]
            .iter()
            .flatten()
            .map(|side| self.count(side, level))
            .sum();
        2 * self.count(&self.angle, level) * radial + 2 * self.count(&self.rim, level)
    }
}

/// The fraction of the plan's first level ([`LaminaAim::start`]) at which the engine's
/// ladder starts ([`LaminaAim::ladder_start`]). The plan's margins make its first level meet
/// the tolerance on its own, in the least favourable cases only just, and mostly by far: the
/// first level within 1e-12 of the random-pose set's disk cases (`level_errors` below, seeds
/// 12 to 14) is 0.57 to 0.89 of the plan's (median 0.72; two cases above it, 1.07 and 1.24).
/// Every level refines every side of the rule (`run_ladder`), so the certificate does not
/// rest on the start (test `a_low_start_still_certifies_honestly`). Evaluations of the 48 disk
/// cases of `pose_benchmark` (four per pair of kinds) for fractions 1.0 / 0.85 / 0.8 / 0.75 /
/// 0.7: seed 12 60,068 / 49,466 / 46,314 / 44,486 / 48,260, seed 13 66,860 / 56,126 / 56,756 /
/// 54,188 / 59,036, seed 14 75,276 / 65,990 / 63,132 / 62,084 / 66,212, seed 15 (held out)
/// 74,806 / 66,334 / 66,544 / 69,516 / 73,114; no estimate exceeded at any of them. (Before
/// every level refined every side, a start one growth step below the plan was the lowest that
/// kept every estimate: two steps let a true error of 2.5e-14 pass an estimate of 5.7e-15.)
const START_FRACTION: Real = 0.8;

/// Plans of at most this many nodes per side start at [`SMALL_PLAN_FRACTION`] instead of
/// [`START_FRACTION`]: the smaller the plan, the nearer its first level is to what the least
/// favourable 1-D rule needs alone (`side_needs`, 169 disk cases of seeds 12 to 16: 0.87 of
/// plans of up to 16 nodes on average, 0.70 to 1.10; 0.75 of 17 to 30, 0.71 above), and a
/// start below that takes a third level. Evaluations with 0.8 / 0.95 for these plans: the 48
/// disk cases of `pose_benchmark`, seeds 12 to 16, 39,838 / 39,116, 41,548 / 40,794, 44,092 /
/// 43,708, 41,098 / 40,718, 41,578 / 41,448; `near_axis_sweep`, seeds 2026 / 7 / 99, 98,174 /
/// 97,360, 53,588 / 54,270, 62,876 / 61,516; 0 violations. (Starting larger plans lower too,
/// at 0.7 times the plan plus 2.5, saved 2-5 % on the first set and cost 14 % on the second:
/// a pair of parallel disks 0.02 apart needed 0.8 of its plan of 268.)
const SMALL_PLAN: u16 = 16;

/// See [`SMALL_PLAN`].
const SMALL_PLAN_FRACTION: Real = 0.95;

impl LaminaAim {
    /// Whether the plan is for a singular curve that runs near the disk along a stretch
    /// narrower than the rim samples' spacing (it then carries [`AREA_MARGIN`], not
    /// [`STRETCH_MARGIN`]): the plan's first level is then just enough (disk-disk gap 0.05 #1 of
    /// the random-pose set, seed 12: 4,500 evaluations from there, 9,190 from one step below),
    /// and the ladder starts at it. (A singular circle has no stretch: its rows are planned
    /// exactly.)
    fn unresolved_stretch(&self) -> bool {
        self.stretch_points > 0 && self.angle_eta < std::f64::consts::TAU / RIM_SAMPLES as Real
    }

    /// The engine ladder's first level: [`START_FRACTION`] of the plan's first level
    /// ([`SMALL_PLAN_FRACTION`] for a small plan), except for an unresolved stretch
    /// ([`LaminaAim::unresolved_stretch`]).
    pub(crate) fn ladder_start(&self) -> u16 {
        if self.unresolved_stretch() {
            return self.start;
        }
        let fraction = if self.start <= SMALL_PLAN {
            SMALL_PLAN_FRACTION
        } else {
            START_FRACTION
        };
        let below = Real::from(self.start) * fraction;
        (below.round() as u16).clamp(MIN_NODES as u16, self.start)
    }
}

/// The aimed lamina rule's workspace, kept by the engine: Gauss–Legendre rules on $[0, 1]$ by
/// order, the 1-D node lists and the node table of the last level (rebuilt for every pose
/// and level, in place).
#[derive(Debug, Clone, Default)]
pub(crate) struct LaminaWorkspace {
    rules: Vec<Option<GaussLegendre>>,
    angles: Vec<(Real, Real, Real)>,
    radial: Vec<(Real, Real)>,
    rim: Vec<(Real, Real, Real)>,
    rows: Vec<TurnedRow>,
    /// The number of split rows ([`SplitRow`]) of the last level.
    split_rows: usize,
    /// The last level's table; shared with the node loop only during an evaluation, so it is
    /// refilled in place.
    nodes: Arc<LaminaNodes>,
}

impl LaminaWorkspace {
    fn rule(&mut self, order: usize) -> Result<&GaussLegendre, InteractionError> {
        if self.rules.len() <= order {
            self.rules.resize(order + 1, None);
        }
        let slot = &mut self.rules[order];
        if slot.is_none() {
            *slot = Some(GaussLegendre::new(order, 0.0, 1.0)?);
        }
        Ok(slot.as_ref().expect("the rule was just built"))
    }

    /// The node table of `level` for `aim` over `lamina` (integration frame).
    pub(crate) fn nodes(
        &mut self,
        lamina: &Lamina,
        aim: &LaminaAim,
        level: u16,
    ) -> Result<&Arc<LaminaNodes>, InteractionError> {
        let mut angles = std::mem::take(&mut self.angles);
        let mut radial = std::mem::take(&mut self.radial);
        let mut rim = std::mem::take(&mut self.rim);
        angles.clear();
        radial.clear();
        rim.clear();
        let both_halves = |this: &mut Self,
                           side: &ClusteredSide,
                           centre: Real,
                           out: &mut Vec<(Real, Real, Real)>|
         -> Result<(), InteractionError> {
            let rule = this.rule(aim.count(side, level))?;
            // The angles centre ± t by the addition theorems: one sine and cosine per
            // node for both halves (within a few ulp of those of centre ± t).
            let (sin_c, cos_c) = centre.sin_cos();
            for (&u, &w) in rule.nodes().iter().zip(rule.weights()) {
                let (t, dt) = side.map(u);
                let (sin_t, cos_t) = t.sin_cos();
                let (cc, ss, sc, cs) = (cos_c * cos_t, sin_c * sin_t, sin_c * cos_t, cos_c * sin_t);
                out.push((cc - ss, sc + cs, w * dt));
                out.push((cc + ss, sc - cs, w * dt));
            }
            Ok(())
        };
        // A split row's angles about its narrower singularity (turned with the row).
        let split_row = |this: &mut Self,
                         split: &SplitRow,
                         out: &mut Vec<(Real, Real, Real)>|
         -> Result<(), InteractionError> {
            for (piece, ((cos_o, sin_o), direction)) in split.pieces.iter().zip(split.origins()) {
                let rule = this.rule(aim.count(piece, level))?;
                let first = out.len();
                for (&u, &w) in rule.nodes().iter().zip(rule.weights()) {
                    // The piece's sinh map by one exponential (sinh and cosh from e^{μu}; near
                    // u = 0 within 1e-16·w of the library's sinh, far below the width).
                    let e = (piece.mu * u).exp();
                    let (sinh, cosh) = (0.5 * (e - e.recip()), 0.5 * (e + e.recip()));
                    let (t, dt) = (piece.width * sinh, piece.width * piece.mu * cosh);
                    out.push((direction * t, 0.0, w * dt));
                }
                // The angle origin + direction·t, mirrored by the row's sign (a loop of its
                // own: no calls, so the nodes' polynomials overlap).
                for node in &mut out[first..] {
                    let (sin_t, cos_t) = sin_cos_of_piece(node.0);
                    let (cos, sin) = (cos_o * cos_t - sin_o * sin_t, sin_o * cos_t + cos_o * sin_t);
                    *node = (cos, split.sign * sin, node.2);
                }
            }
            Ok(())
        };
        both_halves(self, &aim.rim, aim.rim_centre, &mut rim)?;
        let mut rows = std::mem::take(&mut self.rows);
        rows.clear();
        for (side, sign) in [(aim.inward, -1.0), (aim.outward, 1.0)] {
            let Some(side) = side else { continue };
            let rule = self.rule(aim.count(&side, level))?;
            for (&u, &w) in rule.nodes().iter().zip(rule.weights()) {
                let (t, dt) = side.map(u);
                let s = (aim.radial_origin + sign * t).clamp(0.0, lamina.radius());
                radial.push((s, w * dt));
            }
        }
        // A radius's angular side is one of the aim's few tabulated sides, so rows share
        // their angles: each distinct side's list is built once (the same nodes, computed
        // once instead of once per row). Kept on the stack: a warm evaluation allocates
        // nothing.
        // Rows clustered toward their own angle (a singular circle) share lists about 0,
        // turned row by row; the others share lists about the aim's centre.
        let list_centre = if aim.rows.is_some() || aim.turns.is_some() {
            0.0
        } else {
            aim.angle_centre
        };
        self.split_rows = 0;
        let mut built = [(aim.angle, 0, 0); ANGLE_TABLE];
        let mut distinct = 0;
        for &(s, weight) in &radial {
            // A singular circle's row: split at both its singularities where its entry's plan
            // is the other singularity's and the split takes fewer nodes; otherwise the
            // entry's shared list, turned toward the row's narrower singularity.
            let (side, turn) = match &aim.rows {
                Some(circle) => {
                    let [near, other] = circle.at(s);
                    let entry = table_entry(near.width, aim.angle_eta);
                    let shared = aim.angles[entry];
                    if aim.split_entries & (1 << entry) != 0 && other.width < NO_SINGULARITY {
                        let split = SplitRow::new(&near, &other, aim.log_tolerance, ROW_MARGIN);
                        // Decided on the plans, not the level's counts: a radius takes the
                        // same kind of row at every level, so that the levels' errors fall
                        // together. (Decided on the counts, a disk of radius 0.69 0.03 from a
                        // unit disk, over the unit disk at 1e-10, certified 2.5e-11 with a true
                        // error of 4.1e-11; the next level changed by 4.1e-11.)
                        let nodes: Real = split.pieces.iter().map(|p| p.predicted).sum();
                        if nodes <= SPLIT_GAIN * 2.0 * shared.predicted {
                            let first = angles.len();
                            split_row(self, &split, &mut angles)?;
                            self.split_rows += 1;
                            rows.push(TurnedRow {
                                radius: s,
                                weight,
                                turn: (near.cos, near.sin),
                                angles: first..angles.len(),
                            });
                            continue;
                        }
                    }
                    (shared, (near.cos, near.sin))
                }
                None => aim.angle_at(s),
            };
            let range = match built[..distinct].iter().rev().find(|(b, ..)| *b == side) {
                Some(&(_, first, end)) => first..end,
                None => {
                    let first = angles.len();
                    both_halves(self, &side, list_centre, &mut angles)?;
                    if distinct < ANGLE_TABLE {
                        built[distinct] = (side, first, angles.len());
                        distinct += 1;
                    }
                    first..angles.len()
                }
            };
            rows.push(TurnedRow {
                radius: s,
                weight,
                turn,
                angles: range,
            });
        }
        match Arc::get_mut(&mut self.nodes) {
            Some(nodes) => lamina.fill_turned_rows(&angles, &rows, &rim, nodes),
            None => {
                let mut nodes = LaminaNodes::default();
                lamina.fill_turned_rows(&angles, &rows, &rim, &mut nodes);
                self.nodes = Arc::new(nodes);
            }
        }
        self.rows = rows;
        self.angles = angles;
        self.radial = radial;
        self.rim = rim;
        Ok(&self.nodes)
    }
}

/// The ladder of the aimed lamina rule over the disk `lamina` (X) with the aim `aim`: the
/// engine's ladder with jumps ([`run_ladder`]), each level's table built in `workspace` and
/// summed by the lamina node loop of the fixed tables.
pub(crate) fn refine(
    workspace: &mut LaminaWorkspace,
    problem: &Problem<'_>,
    lamina: &Lamina,
    aim: &LaminaAim,
) -> Result<Interaction, InteractionError> {
    refine_from(workspace, problem, lamina, aim, aim.ladder_start())
}

/// [`refine`] from the level `start`.
fn refine_from(
    workspace: &mut LaminaWorkspace,
    problem: &Problem<'_>,
    lamina: &Lamina,
    aim: &LaminaAim,
    start: u16,
) -> Result<Interaction, InteractionError> {
    let Problem {
        x,
        y,
        placement,
        options,
        request,
        budget,
    } = *problem;
    // The aimed nodes have no mirror symmetry.
    let p = &Placement {
        half_azimuth: false,
        half_transverse: false,
        ..*placement
    };
    let settings = ladder_settings(options, budget);
    let settings = crate::strategy::ladder::LadderSettings {
        jump: true,
        geometric: true,
        // A plan corrected by exact rows ([`LaminaAim::corrected`]) certifies its first change
        // only at half the tolerance.
        oscillating: aim.corrected,
        ..settings
    };
    // Whether the last level evaluated had split rows (for `refines`).
    let split = std::cell::Cell::new(false);
    run_ladder(
        &settings,
        p,
        start,
        |level| aim.size(level),
        |from, to| aim.refines(from, to, split.get()),
        |level| {
            let table = NodeTable::Lamina(workspace.nodes(lamina, aim, level)?.clone());
            split.set(workspace.split_rows > 0);
            let values = evaluate_table(x, y, &table, p, request);
            Ok((values, table.len()))
        },
    )
}

#[cfg(test)]
mod tests;

#[cfg(test)]
pub(crate) mod tools;

#[cfg(test)]
pub(crate) use tools::{engine_map, row_rate};
