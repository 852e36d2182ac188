//! The aimed rule: an ellipsoid's surface parametrised by polar angles about a pole aimed at
//! the other body, with the nodes clustered in the polar angle toward that pole, so that the
//! cost does not depend on the pose.
//!
//! # Parametrisation
//!
//! An ellipsoid with semi-axes $A = \operatorname{diag}(a, b, c)$ is the image $\mathbf r = A\mathbf s$
//! of the unit sphere, and its area element is the sphere's mapped by the cofactor matrix:
//! $\mathrm d\mathbf S = \det A\\,A^{-1}\mathbf s\\,\mathrm d\Omega$. The unit sphere is
//! parametrised by polar coordinates $(\theta, \varphi)$ about a pole $\hat{\mathbf p}$,
//! $\mathbf s = R_p(\sin\theta\cos\varphi, \sin\theta\sin\varphi, \cos\theta)$,
//! $\mathrm d\Omega = \sin\theta\\,\mathrm d\theta\\,\mathrm d\varphi$, with $R_p$ a rotation taking
//! $\hat{\mathbf z}$ to $\hat{\mathbf p}$. The pole is the point of X nearest to the singular
//! set of the other body's field (the rim of an oblate spheroid's focal disk or of a disk, a
//! prolate spheroid's focal segment, a triaxial ellipsoid's filled focal ellipse; found by
//! alternating projections between the two convex sets, or between X and the rim's plane and
//! circle), so whatever the pose, the integrand varies fastest near $\theta = 0$ and slowly in
//! $\varphi$ there.
//!
//! Where X is a body of revolution and Y's field is symmetric about X's axis (bodies stacked on
//! a common axis), the nearest singular point is a whole circle about that axis, and the pole
//! goes on the axis instead ([`coaxial_pole`]): the integrand then does not depend on
//! $\varphi$ beyond the area vector's own $e^{\pm i\varphi}$, and 8 azimuths integrate it
//! exactly at every level.
//!
//! # Clustering in the polar angle
//!
//! If the nearest singular point lies at distance $\delta$ from the pole and the surface
//! stretches the sphere's tangent plane there by at most $\ell$, the integrand (after the
//! azimuthal sum) is singular near $\theta = \pm i\theta\_\delta$, with
//! $\cosh\theta\_\delta = 1 + \delta^2/(2\ell(\ell + \delta))$ as for a sphere of radius $\ell$
//! ($\theta\_\delta \approx \delta/\ell$ near contact, $\ln(d/\ell)$ at distance $d = \ell + \delta$).
//! Two polar rules are available, and the start level of each is predicted from the
//! Bernstein ellipse through that singularity (error $\rho^{-2n}$ for $n$ nodes). A singular
//! curve (the rim of a focal disk, a focal ellipse) also passes beside the pole: each of a few
//! points sampled on it has its own singularity $\theta\_L + i\theta\_{\delta'}$ ($\theta\_L$ its
//! angle from the pole, $\delta'$ its height above X), and the far hemisphere, which the
//! clustering maps cover sparsely, one at $\pi + 2i$; the start level is the largest of
//! these predictions, and the grid with the fewest nodes is used:
//!
//! - Gauss–Legendre in $\cos\theta$ (the spherical product rule; with $2n$ azimuths it is
//!   exact for spherical harmonics to degree $2n - 1$): $\rho = e^{\theta\_\delta}$. Best far
//!   away.
//! - The map $\theta = w\sinh(\mu u)$, $\mu = \operatorname{asinh}(\pi/w)$, $u \in [0, 1]$, with
//!   Gauss–Legendre in $u$ (the sinh transformation for nearly singular integrals), for a
//!   tabulated width $w \le \theta\_\delta$ ([`CLUSTER_WIDTHS`]): the singularity moves to
//!   $u = (\operatorname{acosh}(\theta\_\delta/w) + i\pi/2)/\mu$, a distance that shrinks only like
//!   $1/\log(1/\theta\_\delta)$, where Gauss–Legendre in $\theta$ would need $\theta\_\delta^{-1/2}$
//!   times the nodes.
//!
//! The azimuth is a plain periodic trapezoid rule, with half as many nodes as the polar rule
//! ([`CLUSTERED_AZIMUTH_RATIO`]) times the square root of the tangent stretch's anisotropy at
//! the pole (1.5 times as many, at most twice, for the product rule:
//! [`PRODUCT_AZIMUTH_RATIO`]). The unit-sphere grids are built once and cached in the engine;
//! the ellipsoid's nodes and area vectors are made from them on the fly (the pole changes with
//! every pose), a few multiplications per node next to the field.
//!
//! # Certification
//!
//! The engine's ladder: levels $n \to \max(n + 2, \lceil rn\rceil)$ until two agree to the
//! tolerance, the change bounding the coarser level's error. From the third level on, the
//! rate of the last two changes of the force predicts the level whose error is half the
//! tolerance, and the ladder jumps there (at most 1.5 times the level, never twice in a row);
//! the level after it certifies. With the pole on a common axis and Y's singular circle a
//! ring about it, the ring's singular pair $\theta\_L \pm iw$ lies off the pole, the polar
//! rule's error turns in phase from level to level, and two levels can agree by accident near
//! a zero crossing: there the first change counts twice and every estimate is at least the
//! change before it ([`Aim::ring`]).

use super::body::{Body, BodyShape};
use super::kernel::{FrameMap, SolidBlock, SolidSums, BLOCK};
use nalgebra::{Complex, Matrix3};
use std::f64::consts::{PI, TAU};
use std::sync::{Arc, OnceLock};
use surfgrav_potentials::{Field, Potential, Symmetry};
use surfgrav_quadrature::{GaussLegendre, Rule1D};
use surfgrav_surfaces::{EllipsoidSurface, Real, Vec3};

pub(crate) mod lamina;

/// Polar-angle widths $w$ of the tabulated clustering maps (index 0: none, Gauss–Legendre in
/// $\cos\theta$); the map used is the nearest width below the one a pose asks for (stronger
/// clustering costs nodes, never accuracy).
pub(crate) const CLUSTER_WIDTHS: [Real; 22] = [
    Real::INFINITY,
    1.0,
    0.707_106_781_186_547_5,
    0.5,
    0.353_553_390_593_273_8,
    0.25,
    0.176_776_695_296_636_9,
    0.125,
    0.088_388_347_648_318_44,
    0.0625,
    0.044_194_173_824_159_22,
    0.031_25,
    0.022_097_086_912_079_61,
    0.015_625,
    0.011_048_543_456_039_8,
    0.007_812_5,
    0.005_524_271_728_019_9,
    0.003_906_25,
    0.002_762_135_864_009_95,
    0.001_953_125,
    0.001_381_067_932_004_975,
    0.000_976_562_5,
];

/// The largest number of cached grid nodes (all grids together) before the cache is cleared.
const CACHED_NODES: usize = 1 << 20;

/// A unit-sphere grid about the pole $+\hat{\mathbf z}$: directions and weights
/// $w_u w\_\varphi \sin\theta\\,\theta'(u)$, stored by component (struct of arrays) and padded
/// to whole blocks of [`BLOCK`] nodes (direction $\hat{\mathbf z}$, weight 0), so that the node
/// loop reads whole blocks without bounds checks; the padding is never evaluated or summed.
#[derive(Debug)]
pub(crate) struct SphereGrid {
    /// Direction components and weights, [`BLOCK`] nodes per block.
    blocks: Vec<GridBlock>,
    /// The node count (without the padding).
    len: usize,
}

/// One block of a [`SphereGrid`]: direction components and weights.
#[derive(Debug, Clone, Copy)]
struct GridBlock {
    x: [Real; BLOCK],
    y: [Real; BLOCK],
    z: [Real; BLOCK],
    weight: [Real; BLOCK],
}

impl GridBlock {
    const PADDING: Self = Self {
        x: [0.0; BLOCK],
        y: [0.0; BLOCK],
        z: [1.0; BLOCK],
        weight: [0.0; BLOCK],
    };
}

impl SphereGrid {
    fn new(polar: usize, azimuth: usize, cluster: u8) -> Result<Self, super::InteractionError> {
        let width = CLUSTER_WIDTHS[usize::from(cluster)];
        let rule = GaussLegendre::new(polar, 0.0, 1.0)?;
        let h = TAU / azimuth as Real;
        let len = polar * azimuth;
        let mut blocks = vec![GridBlock::PADDING; len.div_ceil(BLOCK)];
        let mut index = 0;
        for (&u, &wu) in rule.nodes().iter().zip(rule.weights()) {
            let (theta, dtheta) = if width.is_finite() {
                let mu = cluster_mu(cluster);
                (width * (mu * u).sinh(), width * mu * (mu * u).cosh())
            } else {
                // Gauss–Legendre in cos θ = 1 − 2u: dΩ = 2 du dφ.
                let t: Real = 1.0 - 2.0 * u;
                let theta = t.clamp(-1.0, 1.0).acos();
                (theta, 2.0 / theta.sin().max(Real::MIN_POSITIVE))
            };
            let (sin_t, cos_t) = theta.sin_cos();
            let w = wu * dtheta * sin_t * h;
            for j in 0..azimuth {
                let phi = (j as Real + 0.5) * h;
                let (sin_p, cos_p) = phi.sin_cos();
                let (block, k) = (&mut blocks[index / BLOCK], index % BLOCK);
                block.x[k] = sin_t * cos_p;
                block.y[k] = sin_t * sin_p;
                block.z[k] = cos_t;
                block.weight[k] = w;
                index += 1;
            }
        }
        Ok(Self { blocks, len })
    }

    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// The blocks with their node counts (the last one possibly partial).
    fn blocks(&self) -> impl Iterator<Item = (&GridBlock, usize)> {
        self.blocks
            .iter()
            .enumerate()
            .map(move |(i, b)| (b, (self.len - i * BLOCK).min(BLOCK)))
    }
}

/// What identifies a grid: polar nodes, azimuth nodes, clustering index.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct GridKey {
    polar: u16,
    azimuth: u16,
    cluster: u8,
}

impl GridKey {
    /// Azimuths per polar ring.
    pub(crate) fn azimuth(&self) -> u16 {
        self.azimuth
    }

    /// The grid's node count.
    pub(crate) fn size(&self) -> usize {
        usize::from(self.polar) * usize::from(self.azimuth)
    }
}

/// Azimuth nodes per polar node of a clustered level on an isotropic pole (a sphere's), times
/// the square root of the anisotropy there (a flat body's rim, seen from its side, varies
/// fastest along the rim). Measured over the random-pose set of the `pose_benchmark` example
/// (seed 12, two cases per pair of kinds): 0.5 against 0.75 and 1 saved 10 to 25 % of the
/// median time at every gap.
const CLUSTERED_AZIMUTH_RATIO: Real = 0.5;

/// Azimuth nodes per polar node of the product rule (Gauss–Legendre in cos θ) on an isotropic
/// pole, times the square root of the anisotropy there and at most 1, the spherical product
/// rule's balance (n nodes and 2n azimuths integrate spherical harmonics to degree 2n − 1):
/// about the aimed pole the source lies on the axis, and only X's asphericity and the extent
/// of Y's singular set make the integrand vary in φ. Measured (`pose_benchmark`, seed 12):
/// the pose set's solid pairs 40,672 → 40,148 evaluations, 1999 KW4 in random attitudes 226
/// → 196 in 9 of 20, estimates unchanged to two digits, no violation. Without the
/// anisotropy factor (0.75 flat) KW4 took 180 everywhere, but an extreme pose of
/// `tests/stress.rs` (a needle of aspect 97 beside a flat spheroid) then understated its
/// error: the two sides differed by 5.3e-11, beyond the test's bound.
const PRODUCT_AZIMUTH_RATIO: Real = 0.75;

/// Azimuth nodes per polar node where the pole is on X's axis and Y's centroid is off it by
/// less than [`NEAR_AXIS`] times the distance from the pole to Y's singular set (parallel
/// axes, mostly axial offset): the clustered maps' ratio at an isotropic pole, also for the
/// product rule. Measured with the example `near_axis_sweep` (80 random near-axial pairs per
/// seed: spheroids and disks of random sizes and aspects on parallel axes, axial gaps 0.02 to
/// 1, lateral offsets 0 to 0.75, turned about the axis or flipped; certified 1e-12 and checked
/// against the independent reference), seeds 7 and 99: no estimate exceeded, 70,780 and
/// 71,466 evaluations against 86,628 and 83,144 with the general rule; with 0.35 fewer, but
/// true errors up to 1.4 times their estimates (seeds 2026 and 99).
const NEAR_AXIS_AZIMUTH_RATIO: Real = 0.5;

/// The largest lateral offset of Y's centroid from X's axis, relative to the smaller of the
/// distance from the pole on the axis to Y's singular set and X's equatorial semi-axis, for
/// which the pole stays on the axis. The distance: a prolate pair at gap 0.1 with offsets 0.3
/// and 0.5 (1.3 and 2.2 times it) took 1,836 and 2,396 evaluations with the axis pole against
/// 724 and 758 with the general one. The semi-axis: far apart, the distance alone let the
/// pole stay on the axis with Y 19 to 26 degrees off it (two flat spheroids 5 apart), where
/// 8 azimuths at two successive levels hid the azimuthal error from the level change (the
/// two torque forms caught it: not certified); the test `coaxial.rs` sweeps 0 to 40 degrees.
const NEAR_AXIS: Real = 0.5;

/// Azimuth nodes per polar node of a level (clustered, or [`PRODUCT_AZIMUTH_RATIO`]).
fn azimuth_ratio(aim: &Aim) -> Real {
    if aim.near_axis {
        return NEAR_AXIS_AZIMUTH_RATIO;
    }
    if aim.cluster == 0 {
        return if aim.known {
            (PRODUCT_AZIMUTH_RATIO * aim.anisotropy.sqrt()).min(1.0)
        } else {
            1.0
        };
    }
    (CLUSTERED_AZIMUTH_RATIO * aim.anisotropy.sqrt()).min(2.0)
}

/// The grid of level `polar` (Gauss–Legendre nodes in $u$) for this aim.
pub(crate) fn grid_key(polar: u16, aim: &Aim) -> GridKey {
    let azimuth = if aim.coaxial {
        COAXIAL_AZIMUTHS
    } else {
        (2.0 * (azimuth_ratio(aim) * Real::from(polar)).ceil()).max(8.0) as u16
    };
    GridKey {
        polar,
        azimuth,
        cluster: aim.cluster,
    }
}

/// The Gauss–Legendre count whose error bound $\rho^{-2n}$ meets the tolerance $\tau$
/// (`log_inverse_tolerance`: $\ln(1/\tau)$).
fn polar_count(rho: Real, log_inverse_tolerance: Real) -> u16 {
    let n = log_inverse_tolerance / (2.0 * rho.max(1.0 + 1e-3).ln());
    (n.ceil() as u16).clamp(4, super::rules::MAX_TRANSVERSE)
}

/// The parameter $\rho$ of the Bernstein ellipse of the polar rule's interval $u \in [0, 1]$
/// through the image of a singularity at the complex polar angle `theta` (and its mirror
/// images $-\theta$, $\bar\theta$), for the rule of clustering index `cluster`.
fn bernstein(theta: Complex<Real>, cluster: u8) -> Real {
    let table = CLUSTER_WIDTHS[usize::from(cluster)];
    // The ellipse with foci ±1 through z: semi-major axis a = (|z − 1| + |z + 1|)/2,
    // ρ = a + √(a² − 1) (moduli by square roots: `hypot` is several times slower).
    let rho = |z: Complex<Real>| {
        let modulus = |re: Real, im: Real| (re * re + im * im).sqrt();
        let a = 0.5 * (modulus(z.re - 1.0, z.im) + modulus(z.re + 1.0, z.im));
        a + (a * a - 1.0).max(0.0).sqrt()
    };
    if table.is_finite() {
        let mu = cluster_mu(cluster);
        let u = asinh(theta / table) / mu;
        // Both branches of the map's inverse: the integrand is even in θ, the map odd in u.
        let one = Complex::new(1.0, 0.0);
        rho(u * 2.0 - one).min(rho(-u.conj() * 2.0 - one))
    } else {
        // Gauss–Legendre in t = cos θ = 1 − 2u: z = 2u − 1 = −cos θ.
        rho(-theta.cos())
    }
}

/// The clustering map's $\mu = \operatorname{asinh}(\pi/w)$ for each width $w$ of
/// [`CLUSTER_WIDTHS`] (computed once; NaN for the product rule, which has no map).
fn cluster_mu(cluster: u8) -> Real {
    static TABLE: OnceLock<[Real; CLUSTER_WIDTHS.len()]> = OnceLock::new();
    TABLE.get_or_init(|| {
        CLUSTER_WIDTHS.map(|w| {
            if w.is_finite() {
                (PI / w).asinh()
            } else {
                Real::NAN
            }
        })
    })[usize::from(cluster)]
}

/// $\operatorname{asinh} z = \ln(z + \sqrt{z^2 + 1})$ (either branch serves [`bernstein`],
/// which takes both), with moduli by square roots.
fn asinh(z: Complex<Real>) -> Complex<Real> {
    let w = z * z + Complex::new(1.0, 0.0);
    let r = (w.re * w.re + w.im * w.im).sqrt();
    // The principal square root of w.
    let re = (0.5 * (r + w.re)).max(0.0).sqrt();
    let im = (0.5 * (r - w.re)).max(0.0).sqrt().copysign(w.im);
    let v = z + Complex::new(re, im);
    Complex::new(0.5 * (v.re * v.re + v.im * v.im).ln(), v.im.atan2(v.re))
}

/// A singularity standing for the far hemisphere, which the clustering maps cover with few
/// nodes: with it the predicted first levels of far poses (gap 5 in `pose_benchmark`, where
/// the nearest point alone predicts 11 to 13 polar nodes for the maps of widths 1 to 0.25)
/// match the measured ones (15 to 21: the counts at which each map's error falls below
/// $3\cdot10^{-13}$ against a 64-node reference).
const ANTIPODE: Complex<Real> = Complex::new(PI, 2.0);

/// The Bernstein parameter of [`ANTIPODE`] for each map of [`CLUSTER_WIDTHS`] (a constant
/// of the rule, computed once).
fn antipode_rho(cluster: u8) -> Real {
    static TABLE: OnceLock<[Real; CLUSTER_WIDTHS.len()]> = OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|k| bernstein(ANTIPODE, k as u8)))
        [usize::from(cluster)]
}

/// The factor on the polar count predicted from the rim's singularities: their sphere-model
/// singularities are weaker than the nearest point's, and their count over-predicts the
/// measured one by about 1.25 on the pose set (seed 12, gaps 0.05 to 5). Not where the pole
/// is on a common axis ([`Aim::coaxial`]): the rim is then a ring about the pole, every sample
/// the same complex angle, and after the exact azimuthal sum the ring's singularity is the
/// integrand's own, at full strength (`near_axis_sweep` seed 2, a prolate spheroid 0.02 below
/// an oblate one: ring 17 polar nodes, weighted 14, nearest point 16; levels 16 and 18 changed
/// by 7.4e-14 with a true error of 1.2e-13 at level 18). Unweighted there, the near-axis
/// sweeps of seeds 2026, 7, 99 and 1-5 took 1,224 fewer evaluations in all (+328 to -416 each)
/// and had no estimate exceeded (one before); the stacked oblate pair of the configuration
/// kinds 424 instead of 336.
const RIM_WEIGHT: Real = 0.8;

/// Beyond this width $\theta\_\delta$ of the nearest singularity the rim of a singular set
/// smaller than its distance from X is not sampled: its points are then all seen near the
/// pole's direction; on the pose set (seed 12, gaps 0.05 to 5) thresholds of 1 and 1.5 give
/// the same start levels, and the sampling (a few microseconds) would be a sizeable part of a
/// far interaction's cost (1999 KW4, 226 evaluations). A larger set is sampled at any width:
/// a spheroid of size 0.32 at 0.56 from the rim of a unit disk (`pose_benchmark` seed 20,
/// spheroid-disk gap 0.2 #1, width 1.01) started at 14 polar nodes from the nearest point
/// alone and took 5,458 evaluations (its levels' changes fall below 1e-12 from 30 on); from
/// its rim's start of 15, 4,306.
const RIM_WIDTH: Real = 1.0;

/// Points of the singular set sampled around its rim (besides the nearest point).
const RIM_SAMPLES: usize = 8;

/// The complex polar angles $\theta\_L + i\theta\_{\delta'}$ at which the integrand over X is
/// singular, one per sampled point of Y's singular set (`points`, X's frame): $\theta\_L$ the
/// angle on the unit sphere between the pole and the point's foot on X, $\theta\_{\delta'}$ the
/// sphere model's width for its height $\delta'$ above the foot (module docs), with the
/// largest stretch `stretch`.
fn singular_angle(axes: &Vec3, pole: &Vec3, stretch: Real, q: &Vec3) -> Complex<Real> {
    let foot = nearest_on_ellipsoid(axes, q);
    let height = (q - foot).norm();
    let direction = foot.component_div(axes);
    let lateral = direction.cross(pole).norm().atan2(direction.dot(pole));
    let width = (1.0 + height * height / (2.0 * stretch * (stretch + height))).acosh();
    Complex::new(lateral.max(0.0), width)
}

/// The rim of Y's singular set sampled at [`RIM_SAMPLES`] points, Y's frame (none for a
/// point or a ball).
fn rim_samples(set: &SingularSet) -> ([Vec3; RIM_SAMPLES], usize) {
    let mut points = [Vec3::zeros(); RIM_SAMPLES];
    let (u, v) = match *set {
        SingularSet::Ellipse(s) => {
            // The semi-axes as vectors, the nonzero ones first (a segment: one, a point: none).
            let mut axes = [Vec3::zeros(); 3];
            let mut count = 0;
            for i in (0..3).filter(|&i| s[i] > 0.0) {
                axes[count][i] = s[i];
                count += 1;
            }
            if count == 0 {
                return (points, 0);
            }
            (axes[0], axes[1])
        }
        SingularSet::Circle(radius) => (Vec3::x() * radius, Vec3::y() * radius),
        SingularSet::Ball(_) => return (points, 0),
    };
    static ANGLES: OnceLock<[(Real, Real); RIM_SAMPLES]> = OnceLock::new();
    let angles = ANGLES
        .get_or_init(|| std::array::from_fn(|k| (TAU * k as Real / RIM_SAMPLES as Real).sin_cos()));
    for (point, &(sin, cos)) in points.iter_mut().zip(angles) {
        *point = u * cos + v * sin;
    }
    (points, RIM_SAMPLES)
}

/// The engine's cache of unit-sphere grids.
#[derive(Debug, Clone, Default)]
pub(crate) struct GridCache {
    grids: Vec<(GridKey, Arc<SphereGrid>)>,
    nodes: usize,
    /// The aimed lamina rule's workspace ([`lamina`]).
    pub(crate) lamina: lamina::LaminaWorkspace,
}

impl GridCache {
    pub(crate) fn get(&mut self, key: GridKey) -> Result<Arc<SphereGrid>, super::InteractionError> {
        if let Some((_, grid)) = self.grids.iter().find(|(k, _)| *k == key) {
            return Ok(grid.clone());
        }
        let grid = Arc::new(SphereGrid::new(
            usize::from(key.polar),
            usize::from(key.azimuth),
            key.cluster,
        )?);
        if self.nodes + grid.len() > CACHED_NODES {
            self.grids.clear();
            self.nodes = 0;
        }
        self.nodes += grid.len();
        self.grids.push((key, grid.clone()));
        Ok(grid)
    }
}

/// Where the pole goes and how strongly to cluster, for X (an ellipsoid in its integration
/// frame) in the field of Y (`map`: X's frame into Y's).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Aim {
    /// Rotation taking the grid's pole $\hat{\mathbf z}$ to the unit-sphere pole (columns
    /// $\mathbf e_1, \mathbf e_2, \hat{\mathbf p}$).
    pub(crate) frame: Matrix3<Real>,
    /// Index into [`CLUSTER_WIDTHS`].
    pub(crate) cluster: u8,
    /// The first level's polar count.
    pub(crate) start: u16,
    /// The largest over the smallest stretch of the sphere's tangent plane at the pole.
    pub(crate) anisotropy: Real,
    /// Whether Y's singular set is known (not a [`SingularSet::Ball`]): only then are the
    /// rim, the far hemisphere and [`PRODUCT_AZIMUTH_RATIO`] used, as measured; a body of
    /// unknown shape (a polyhedron, a custom field) keeps the nearest point's prediction and
    /// the balanced product rule.
    pub(crate) known: bool,
    /// Whether the integrand is symmetric about the pole's axis ([`coaxial_pole`]): then
    /// [`COAXIAL_AZIMUTHS`] azimuths integrate it exactly, whatever the polar count.
    pub(crate) coaxial: bool,
    /// Whether the pole is on X's axis with Y's centroid a little off it ([`NEAR_AXIS`]): the
    /// azimuthal content is then small, and [`NEAR_AXIS_AZIMUTH_RATIO`] azimuths per polar
    /// node serve.
    pub(crate) near_axis: bool,
    /// Whether the pole is on a common axis ([`Aim::coaxial`] or [`Aim::near_axis`]) and Y's
    /// singular set is a circle about it: a ring off the pole, whose singularity makes the
    /// polar rule's error oscillate from level to level (see `run_ladder`'s `oscillating`).
    pub(crate) ring: bool,
}

/// The set where a body's exterior field, continued toward X, is singular (its body frame):
/// a filled ellipse in a coordinate plane (semi-axes along the body axes, one of them zero; a
/// segment if two are), the circle bounding a disk (the continuation of an oblate spheroid's
/// or a disk's exterior potential through the face of its focal disk is analytic: only the rim
/// is singular), or a ball.
#[derive(Debug, Clone, Copy)]
pub(crate) enum SingularSet {
    /// Semi-axes along body x, y, z (the triaxial focal ellipse, filled, or a prolate
    /// spheroid's focal segment, or a point).
    Ellipse(Vec3),
    /// A circle of this radius in the body's x–y plane about the centroid.
    Circle(Real),
    /// A ball of this radius about the centroid (shape unknown).
    Ball(Real),
}

impl SingularSet {
    /// The largest distance of a point of the set from Y's centroid.
    fn extent(&self) -> Real {
        match *self {
            SingularSet::Ellipse(s) => s.max(),
            SingularSet::Circle(radius) | SingularSet::Ball(radius) => radius,
        }
    }

    /// The point of the set nearest to `r_y` (Y's frame); for a circle seen from its axis,
    /// a point of it.
    pub(crate) fn nearest(&self, r_y: &Vec3) -> Vec3 {
        match *self {
            SingularSet::Ellipse(s) => nearest_on_ellipsoid(&s, r_y),
            SingularSet::Circle(radius) => {
                let planar = r_y.xy().norm();
                if planar > 0.0 {
                    Vec3::new(r_y.x * radius / planar, r_y.y * radius / planar, 0.0)
                } else {
                    Vec3::new(radius, 0.0, 0.0)
                }
            }
            SingularSet::Ball(radius) => {
                let n = r_y.norm();
                if n <= radius {
                    *r_y
                } else {
                    r_y * (radius / n)
                }
            }
        }
    }
}

pub(crate) fn singular_set(y: &Body) -> SingularSet {
    match y.shape() {
        BodyShape::Point => SingularSet::Ellipse(Vec3::zeros()),
        BodyShape::Solid(e) => {
            let axes = e.semi_axes();
            let smallest = axes.min();
            let mut set = axes.map(|s| ((s - smallest) * (s + smallest)).max(0.0).sqrt());
            // The focal set lies in the plane normal to the smallest axis.
            let i = axes.imin();
            set[i] = 0.0;
            let oblate = i == 2 && axes.x == axes.y;
            if oblate {
                SingularSet::Circle(set.x)
            } else {
                SingularSet::Ellipse(set)
            }
        }
        BodyShape::Disk(l) => SingularSet::Circle(l.radius()),
        BodyShape::Surface(_) | BodyShape::FieldOnly | BodyShape::Mesh(_) => {
            SingularSet::Ball(y.bounding_radius())
        }
    }
}

/// The relative Newton step of [`nearest_on_ellipsoid`] after which it stops (one step fewer
/// than stopping at $10^{-15}$, which only took a last step of rounding size).
const NEAREST_STEP: Real = 1e-9;

/// The point of the axis-aligned ellipsoid (or ellipse, for a zero semi-axis: the filled
/// region) with semi-axes `axes` nearest to `q` (`q` itself if inside).
pub(crate) fn nearest_on_ellipsoid(axes: &Vec3, q: &Vec3) -> Vec3 {
    // Components along zero axes are clamped to zero (the set is flat there).
    let q = Vec3::new(
        if axes.x > 0.0 { q.x } else { 0.0 },
        if axes.y > 0.0 { q.y } else { 0.0 },
        if axes.z > 0.0 { q.z } else { 0.0 },
    );
    let f = |t: Real| -> (Real, Real) {
        let (mut value, mut slope) = (-1.0, 0.0);
        for i in 0..3 {
            if axes[i] > 0.0 {
                let inverse = 1.0 / (axes[i] * axes[i] + t);
                let r = axes[i] * q[i] * inverse;
                value += r * r;
                slope -= 2.0 * r * r * inverse;
            }
        }
        (value, slope)
    };
    if f(0.0).0 <= 0.0 {
        return q;
    }
    // f is convex and decreasing for t > 0: Newton from the left converges monotonically.
    // Start at a lower bound of the root: with a_i² + t ≤ a_max² + t, f(t) = 0 gives
    // (a_max² + t)² ≥ Σ a_i² q_i² (far points need few steps from there, not ~log₁.₅(t/a²)).
    let (mut weighted, mut largest) = (0.0, 0.0);
    for i in 0..3 {
        if axes[i] > 0.0 {
            weighted += (axes[i] * q[i]).powi(2);
            largest = Real::max(largest, axes[i] * axes[i]);
        }
    }
    let mut t = (weighted.sqrt() - largest).max(0.0);
    for _ in 0..100 {
        let (value, slope) = f(t);
        if slope >= 0.0 || slope.is_nan() {
            break;
        }
        let next = t - value / slope;
        // Newton from the left converges monotonically and quadratically: after a step of
        // 1e-9 relative the remaining error is at rounding level.
        if next <= t || next.is_nan() || (next - t) <= NEAREST_STEP * next {
            t = next.max(t);
            break;
        }
        t = next;
    }
    Vec3::from_fn(|i, _| {
        if axes[i] > 0.0 {
            let a2 = axes[i] * axes[i];
            a2 * q[i] / (a2 + t)
        } else {
            0.0
        }
    })
}

/// The nearest pair between a convex set X of the integration frame (`project_x`: the nearest
/// point of X; or a circle, whose projection is not convex but whose alternating projections
/// still settle at a locally nearest pair) and the singular set of Y's field (`map`: X's frame
/// into Y's), by alternating projections (convergent to a nearest pair for two convex sets),
/// stopped once a step moves the point on Y's set by less than $10^{-6}$ `scale` or $10^{-3}$
/// of the distance between the two points. Returns the
/// point of X and the singular point, both in X's frame.
pub(crate) fn nearest_singular_point(
    y: &Body,
    map: &FrameMap,
    project_x: impl Fn(&Vec3) -> Vec3,
    scale: Real,
) -> (Vec3, Vec3) {
    let set = singular_set(y);
    let to_y = |r: &Vec3| map.apply(r);
    let to_x = |r: &Vec3| map.back(&(r - map.offset));
    let project_set = |r_y: &Vec3| set.nearest(r_y);
    let mut y_point = Vec3::zeros();
    let mut x_point = Vec3::zeros();
    for _ in 0..12 {
        x_point = project_x(&to_x(&y_point));
        let next = project_set(&to_y(&x_point));
        let moved = (next - y_point).norm();
        y_point = next;
        // Far from contact the pole need not be placed to 1e-6 of X's size: to 1e-3 of the
        // gap it moves the singularity off the pole by 1e-3 of its own width, which no
        // polar count notices.
        if moved <= 1e-6 * scale || moved <= 1e-3 * (to_x(&y_point) - x_point).norm() {
            break;
        }
    }
    (x_point, to_x(&y_point))
}

/// Azimuths of a level whose integrand is symmetric about the pole's axis: the area vector
/// and the moment arms bring the azimuthal modes $e^{\pm i\varphi}$ into the integrands
/// (force, both torque forms, energy), which the periodic trapezoid rule with 8 nodes
/// integrates exactly (every mode below 8).
const COAXIAL_AZIMUTHS: u16 = 8;

/// How far (relative to the distance between the centroids) Y's centroid may lie off X's
/// axis, and how far (in radians) Y's axis may turn from it, for the integrand to count as
/// symmetric about that axis: an offset $\varepsilon$ puts modes of relative size about
/// $\varepsilon^k$ into the azimuthal content, and the first one the 8 nodes alias ($k = 8$) is
/// then below $10^{-70}$.
const COAXIAL_TOLERANCE: Real = 1e-9;

/// The pole on X's symmetry axis, toward Y, where the integrand over X is symmetric about
/// that axis: X a body of revolution about its $z$ axis (equal $x$ and $y$ semi-axes) and Y's
/// field symmetric about the same line (a sphere or point centred on it, or a spheroid or
/// disk whose axis lies along it). The nearest point of Y's singular set is then a whole
/// circle about the axis (an oblate spheroid's focal circle, a disk's rim), or a point on it
/// (a prolate spheroid's focal segment), and the pole the general rule would aim at one
/// point of that circle would break the symmetry (`stacked` configurations: two oblate
/// spheroids on a common axis at gap 0.1 took 2,338 evaluations).
pub(crate) fn coaxial_pole(axes: &Vec3, y: &Body, map: &FrameMap) -> Option<Vec3> {
    axis_pole(axes, y, map)
        .filter(|&(_, offset, distance)| offset <= COAXIAL_TOLERANCE * distance)
        .map(|(pole, _, _)| pole)
}

/// The pole on X's symmetry axis toward Y, where X is a body of revolution and Y's field is
/// symmetric about a line parallel to that axis (a sphere or point, or a spheroid or disk
/// whose axis is parallel to X's): with the lateral offset of Y's centroid from X's axis and
/// the distance between the centroids.
fn axis_pole(axes: &Vec3, y: &Body, map: &FrameMap) -> Option<(Vec3, Real, Real)> {
    if axes.x != axes.y {
        return None;
    }
    // Y's centroid and axis in X's frame.
    let centre = map.back(&(-map.offset));
    let distance = centre.norm();
    if distance.is_nan() || distance <= 0.0 || centre.z == 0.0 {
        return None;
    }
    let parallel = match y.symmetry() {
        Symmetry::Spherical => true,
        Symmetry::Axisymmetric => map.back(&Vec3::z()).xy().norm() <= COAXIAL_TOLERANCE,
        _ => false,
    };
    parallel.then(|| (Vec3::z() * centre.z.signum(), centre.xy().norm(), distance))
}

/// The aim for integrating over the ellipsoid `e` (integration frame) in Y's field, where
/// another rule may compete: `loses(cluster, size)` tells whether a candidate of this
/// clustering index with a level of `size` nodes (or more: it must hold for every larger size
/// once it holds for one) would not be chosen over it. Candidates that lose are not planned
/// further; `None` means every candidate loses (without a rival, `|_, _| false`, there is
/// always an aim).
pub(crate) fn aim(
    e: &EllipsoidSurface,
    y: &Body,
    map: &FrameMap,
    tolerance: Real,
    loses: &dyn Fn(u8, usize) -> bool,
) -> Option<Aim> {
    let log_inverse_tolerance = (1.0 / tolerance).ln();
    let axes = e.semi_axes();
    // On (or near) a common axis: the pole's point on the axis and Y's singular point nearest
    // to it, if Y's centroid lies within NEAR_AXIS of that distance from the axis.
    let on_axis = axis_pole(&axes, y, map).and_then(|(pole, offset, distance)| {
        let x_point = pole * axes.z;
        let set = singular_set(y);
        let singular = map.back(&(set.nearest(&map.apply(&x_point)) - map.offset));
        let exact = offset <= COAXIAL_TOLERANCE * distance;
        (exact || offset <= NEAR_AXIS * (singular - x_point).norm().min(axes.x))
            .then_some((x_point, singular, exact))
    });
    let (coaxial, near_axis) = match on_axis {
        Some((_, _, exact)) => (exact, !exact),
        None => (false, false),
    };
    let (x_point, singular) = match on_axis {
        Some((x_point, singular, _)) => (x_point, singular),
        None => nearest_singular_point(y, map, |r| nearest_on_ellipsoid(&axes, r), axes.max()),
    };
    let delta = (singular - x_point).norm();
    let pole = x_point.component_div(&axes).normalize();
    // Tangent basis at the pole; e1 along the direction the surface stretches most.
    let helper = if pole.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::y()
    };
    let t1 = pole.cross(&helper).normalize();
    let t2 = pole.cross(&t1);
    let (m1, m2) = (axes.component_mul(&t1), axes.component_mul(&t2));
    let (g11, g12, g22) = (m1.dot(&m1), m1.dot(&m2), m2.dot(&m2));
    let half_trace = 0.5 * (g11 + g22);
    let root = (0.25 * (g11 - g22) * (g11 - g22) + g12 * g12).sqrt();
    let stretch = (half_trace + root).sqrt();
    let anisotropy = stretch / (half_trace - root).max(Real::MIN_POSITIVE).sqrt();
    let angle = 0.5 * (2.0 * g12).atan2(g11 - g22);
    let (sin, cos) = angle.sin_cos();
    let e1 = t1 * cos + t2 * sin;
    let e2 = pole.cross(&e1);
    // The singularity of the integrand in θ, as for a sphere of radius ℓ whose nearest
    // singular point is δ above it: cosh θ* = 1 + δ²/(2ℓ(ℓ + δ)) (θ* ≈ δ/ℓ near contact,
    // ln(d/ℓ) far away, d = ℓ + δ).
    let width = (1.0 + delta * delta / (2.0 * stretch * (stretch + delta))).acosh();
    let clustered = CLUSTER_WIDTHS
        .iter()
        .position(|&w| w <= width)
        .unwrap_or(CLUSTER_WIDTHS.len() - 1)
        .max(1) as u8;
    // The singularities in θ: the nearest point's, on the pole's axis, and those of the rim
    // of Y's singular set (a curve running past the pole converges more slowly than its
    // nearest point alone predicts).
    let set = singular_set(y);
    if matches!(set, SingularSet::Ball(_)) {
        let polar_for = |cluster: u8| {
            polar_count(
                bernstein(Complex::new(0.0, width), cluster),
                log_inverse_tolerance,
            )
        };
        let cluster = if polar_for(0) <= polar_for(clustered) {
            0
        } else {
            clustered
        };
        return Some(Aim {
            frame: Matrix3::from_columns(&[e1, e2, pole]),
            cluster,
            start: polar_for(cluster),
            anisotropy,
            known: false,
            coaxial,
            near_axis,
            ring: false,
        });
    }
    let mut angles = [Complex::new(0.0, width); RIM_SAMPLES];
    let (rim, count) = if width < RIM_WIDTH || set.extent() > delta {
        rim_samples(&set)
    } else {
        ([Vec3::zeros(); RIM_SAMPLES], 0)
    };
    for (angle, q) in angles.iter_mut().zip(&rim[..count]) {
        *angle = singular_angle(&axes, &pole, stretch, &map.back(&(q - map.offset)));
    }
    let angles = &angles[..count];
    let template = Aim {
        frame: Matrix3::from_columns(&[e1, e2, pole]),
        cluster: 0,
        start: 0,
        anisotropy,
        known: true,
        coaxial,
        near_axis,
        ring: (coaxial || near_axis) && matches!(set, SingularSet::Circle(_)),
    };
    let rim_weight = if coaxial { 1.0 } else { RIM_WEIGHT };
    let cost = |cluster: u8, start: u16| {
        grid_key(
            start,
            &Aim {
                cluster,
                start,
                ..template
            },
        )
        .size()
    };
    // A candidate's first level: the largest of the nearest point's count, the far
    // hemisphere's and the rim's (RIM_WEIGHT times the count of its least favourable point,
    // or the whole count about a common axis).
    // The cost grows with the level, so a candidate whose level so far already costs at
    // least the best one's (more, or as much with a higher index: ties go to the lower
    // index), or loses to the rival, cannot be chosen, and its remaining points are not
    // evaluated.
    let candidate = |cluster: u8, best: Option<(usize, u8)>| -> Option<(u16, usize)> {
        let beats = |c: usize| {
            best.is_none_or(|(b, k)| c < b || (c == b && cluster < k)) && !loses(cluster, c)
        };
        // The far hemisphere's count is tabulated: checked before any other point.
        let antipode = polar_count(antipode_rho(cluster), log_inverse_tolerance);
        if !beats(cost(cluster, antipode)) {
            return None;
        }
        let nearest = polar_count(
            bernstein(Complex::new(0.0, width), cluster),
            log_inverse_tolerance,
        );
        let mut start = nearest.max(antipode);
        if !beats(cost(cluster, start)) {
            return None;
        }
        for &theta in angles {
            let rho = bernstein(theta, cluster);
            if rho.is_nan() {
                continue;
            }
            let rim =
                (rim_weight * Real::from(polar_count(rho, log_inverse_tolerance))).ceil() as u16;
            if rim > start {
                start = rim;
                if !beats(cost(cluster, start)) {
                    return None;
                }
            }
        }
        Some((start, cost(cluster, start)))
    };
    // Candidates: the product rule and the tabulated maps from the weakest to two steps
    // stronger than the nearest point asks for; the cheapest (the lowest index among equals).
    // The one the nearest point asks for first: usually the cheapest or near it, it prunes
    // the others early.
    let strongest = (usize::from(clustered) + 2).min(CLUSTER_WIDTHS.len() - 1) as u8;
    let mut best: Option<(usize, u8, u16)> = None;
    for cluster in std::iter::once(clustered).chain((0..=strongest).filter(|&c| c != clustered)) {
        if let Some((start, c)) = candidate(cluster, best.map(|(b, k, _)| (b, k))) {
            best = Some((c, cluster, start));
        }
    }
    best.map(|(_, cluster, start)| Aim {
        cluster,
        start,
        ..template
    })
}

/// The node sums over the ellipsoid `e` on the grid `grid` turned by `aim` (the same terms as
/// the tables' loop, [`add_solid_node`](super::kernel::add_solid_node), each rounded the same
/// way and added in the same order); `FULL`: torques and energy too, otherwise the force.
///
/// Each block of [`BLOCK`] nodes goes in three passes: the nodes (point, area vector, point in
/// Y's frame) lane by lane over arrays, the batched field, then each node's terms lane by lane
/// over arrays (compiled with AVX where the CPU has it: no FMA, so every operation rounds as
/// in the scalar code), and only the additions into the sums in node order.
#[inline(never)]
pub(crate) fn aimed_sums<P: Potential + ?Sized, const FAR: bool, const FULL: bool>(
    e: &EllipsoidSurface,
    grid: &SphereGrid,
    aim: &Aim,
    source: &P,
    map: &FrameMap,
) -> SolidSums {
    #[cfg(target_arch = "x86_64")]
    let avx = std::arch::is_x86_feature_detected!("avx");
    #[cfg(not(target_arch = "x86_64"))]
    let avx = false;
    aimed_sums_lanes::<P, FAR, FULL>(e, grid, aim, source, map, avx)
}

/// [`aimed_sums`] with the lane passes compiled with AVX (`avx`, which the CPU must then
/// support) or without.
#[inline(always)]
fn aimed_sums_lanes<P: Potential + ?Sized, const FAR: bool, const FULL: bool>(
    e: &EllipsoidSurface,
    grid: &SphereGrid,
    aim: &Aim,
    source: &P,
    map: &FrameMap,
    avx: bool,
) -> SolidSums {
    let axes = e.semi_axes();
    let mut lanes = NodeLanes::new(
        axes,
        Vec3::new(axes.y * axes.z, axes.x * axes.z, axes.x * axes.y),
        aim.frame,
        *map,
        source.potential(&map.apply(&Vec3::zeros())),
    );
    let mut totals = super::kernel::SolidTotals::new();
    let mut sizes = super::kernel::SolidMagnitudes::default();
    let mut potentials = [0.0; BLOCK];
    let mut fields = [Field {
        potential: 0.0,
        acceleration: Vec3::zeros(),
    }; BLOCK];
    for (d, n) in grid.blocks() {
        if avx {
            // SAFETY: `avx` only where AVX was detected on this CPU (std caches the answer).
            #[cfg(target_arch = "x86_64")]
            unsafe {
                lanes.nodes_avx(d)
            };
        } else {
            lanes.nodes(d);
        }
        if FULL || FAR {
            source.fields_into(&lanes.mapped[..n], &mut fields[..n]);
        } else {
            source.potentials_into(&lanes.mapped[..n], &mut potentials[..n]);
            for k in 0..n {
                fields[k].potential = potentials[k];
            }
        }
        if avx {
            // SAFETY: as above.
            #[cfg(target_arch = "x86_64")]
            unsafe {
                lanes.terms_avx::<FAR, FULL>(&fields)
            };
        } else {
            lanes.terms::<FAR, FULL>(&fields);
        }
        totals.add::<FULL>(&lanes.sum::<FAR, FULL>(&mut sizes, n));
    }
    totals.finish(&sizes)
}

/// One block of [`aimed_sums`] by component (struct of arrays): the nodes' points
/// $\mathbf x$, weighted area vectors $\mathbf W$, points in Y's frame and terms.
#[derive(Debug, Clone, Copy)]
struct NodeLanes {
    axes: Vec3,
    cofactor: Vec3,
    frame: Matrix3<Real>,
    map: FrameMap,
    reference: Real,
    x: [[Real; BLOCK]; 3],
    w: [[Real; BLOCK]; 3],
    mapped: [Vec3; BLOCK],
    flux: [[Real; BLOCK]; 3],
    moment: [[Real; BLOCK]; 3],
    gradient: [[Real; BLOCK]; 3],
    acceleration: [[Real; BLOCK]; 3],
    energy: [Real; BLOCK],
    size_potential: [Real; BLOCK],
    size_flux: [Real; BLOCK],
    size_moment: [Real; BLOCK],
    size_energy: [Real; BLOCK],
    size_acceleration: [Real; BLOCK],
}

impl NodeLanes {
    fn new(
        axes: Vec3,
        cofactor: Vec3,
        frame: Matrix3<Real>,
        map: FrameMap,
        reference: Real,
    ) -> Self {
        let zero = [0.0; BLOCK];
        Self {
            axes,
            cofactor,
            frame,
            map,
            reference,
            x: [zero; 3],
            w: [zero; 3],
            mapped: [Vec3::zeros(); BLOCK],
            flux: [zero; 3],
            moment: [zero; 3],
            gradient: [zero; 3],
            acceleration: [zero; 3],
            energy: zero,
            size_potential: zero,
            size_flux: zero,
            size_moment: zero,
            size_energy: zero,
            size_acceleration: zero,
        }
    }

    /// The block's nodes: $\mathbf s = F\mathbf d$, $\mathbf x = \mathrm{diag}(a, b, c)\\,\mathbf s$,
    /// $\mathbf W = w\\,\mathrm{diag}(bc, ac, ab)\\,\mathbf s$, $\mathbf r\_Y = M\mathbf x + \mathbf t$.
    #[inline(always)]
    fn nodes(&mut self, d: &GridBlock) {
        let f = &self.frame;
        let (axes, cofactor) = (&self.axes, &self.cofactor);
        for k in 0..BLOCK {
            let (dx, dy, dz) = (d.x[k], d.y[k], d.z[k]);
            let sx = f[(0, 0)] * dx + f[(0, 1)] * dy + f[(0, 2)] * dz;
            let sy = f[(1, 0)] * dx + f[(1, 1)] * dy + f[(1, 2)] * dz;
            let sz = f[(2, 0)] * dx + f[(2, 1)] * dy + f[(2, 2)] * dz;
            let (px, py, pz) = (axes.x * sx, axes.y * sy, axes.z * sz);
            self.x[0][k] = px;
            self.x[1][k] = py;
            self.x[2][k] = pz;
            self.w[0][k] = cofactor.x * sx * d.weight[k];
            self.w[1][k] = cofactor.y * sy * d.weight[k];
            self.w[2][k] = cofactor.z * sz * d.weight[k];
            self.mapped[k] = self.map.apply_components(px, py, pz);
        }
    }

    /// [`NodeLanes::nodes`] compiled with AVX.
    ///
    /// # Safety
    ///
    /// The CPU must support AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    unsafe fn nodes_avx(&mut self, d: &GridBlock) {
        self.nodes(d);
    }

    /// Each node's terms (those of [`add_solid_node`](super::kernel::add_solid_node), the
    /// same operations in the same order), from the block's fields.
    #[inline(always)]
    fn terms<const FAR: bool, const FULL: bool>(&mut self, fields: &[Field; BLOCK]) {
        let m = &self.map.rotation;
        for (k, field) in fields.iter().enumerate() {
            let phi = field.potential;
            let (xx, xy, xz) = (self.x[0][k], self.x[1][k], self.x[2][k]);
            let (wx, wy, wz) = (self.w[0][k], self.w[1][k], self.w[2][k]);
            let w_norm = (wx * wx + wy * wy + wz * wz).sqrt();
            let relative = phi - self.reference;
            self.size_potential[k] = phi.abs() * w_norm;
            self.flux[0][k] = wx * relative;
            self.flux[1][k] = wy * relative;
            self.flux[2][k] = wz * relative;
            self.size_flux[k] = relative.abs() * w_norm;
            if FULL || FAR {
                // a = Mᵀ g: the acceleration in X's frame.
                let g = &field.acceleration;
                let ax = m[(0, 0)] * g.x + m[(1, 0)] * g.y + m[(2, 0)] * g.z;
                let ay = m[(0, 1)] * g.x + m[(1, 1)] * g.y + m[(2, 1)] * g.z;
                let az = m[(0, 2)] * g.x + m[(1, 2)] * g.y + m[(2, 2)] * g.z;
                let a_dot_w = ax * wx + ay * wy + az * wz;
                if FAR {
                    self.acceleration[0][k] = xx * a_dot_w;
                    self.acceleration[1][k] = xy * a_dot_w;
                    self.acceleration[2][k] = xz * a_dot_w;
                    let x_norm = (xx * xx + xy * xy + xz * xz).sqrt();
                    self.size_acceleration[k] = x_norm * a_dot_w.abs();
                }
                if FULL {
                    let half_x2 = 0.5 * (xx * xx + xy * xy + xz * xz);
                    let x_dot_w = xx * wx + xy * wy + xz * wz;
                    let (mx, my, mz) = (xy * wz - xz * wy, xz * wx - xx * wz, xx * wy - xy * wx);
                    let moment_norm = (mx * mx + my * my + mz * mz).sqrt();
                    let (e_potential, e_gradient) = (phi * x_dot_w, half_x2 * a_dot_w);
                    self.moment[0][k] = mx * relative;
                    self.moment[1][k] = my * relative;
                    self.moment[2][k] = mz * relative;
                    self.gradient[0][k] = (wy * az - wz * ay) * half_x2;
                    self.gradient[1][k] = (wz * ax - wx * az) * half_x2;
                    self.gradient[2][k] = (wx * ay - wy * ax) * half_x2;
                    self.energy[k] = e_potential + e_gradient;
                    self.size_moment[k] = relative.abs() * moment_norm;
                    self.size_energy[k] = e_potential.abs() + e_gradient.abs();
                }
            }
        }
    }

    /// [`NodeLanes::terms`] compiled with AVX.
    ///
    /// # Safety
    ///
    /// The CPU must support AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    unsafe fn terms_avx<const FAR: bool, const FULL: bool>(&mut self, fields: &[Field; BLOCK]) {
        self.terms::<FAR, FULL>(fields);
    }

    /// The first `n` nodes' terms added in node order: the block's sums, and the magnitudes
    /// into `sizes`.
    #[inline(always)]
    fn sum<const FAR: bool, const FULL: bool>(
        &self,
        sizes: &mut super::kernel::SolidMagnitudes,
        n: usize,
    ) -> SolidBlock {
        let mut block = SolidBlock::default();
        for k in 0..n.min(BLOCK) {
            sizes.potential += self.size_potential[k];
            block.flux += Vec3::new(self.flux[0][k], self.flux[1][k], self.flux[2][k]);
            sizes.flux += self.size_flux[k];
            if FAR {
                block.acceleration_flux += Vec3::new(
                    self.acceleration[0][k],
                    self.acceleration[1][k],
                    self.acceleration[2][k],
                );
                sizes.acceleration += self.size_acceleration[k];
            }
            if FULL {
                block.moment += Vec3::new(self.moment[0][k], self.moment[1][k], self.moment[2][k]);
                block.gradient_moment += Vec3::new(
                    self.gradient[0][k],
                    self.gradient[1][k],
                    self.gradient[2][k],
                );
                block.energy += self.energy[k];
                sizes.moment += self.size_moment[k];
                sizes.energy += self.size_energy[k];
            }
        }
        block
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::{add_solid_node, NodeConstants, SolidMagnitudes, SolidTotals};
    use nalgebra::{Rotation3, Vector3};
    use surfgrav_potentials::{Ellipsoid, PointMass};

    /// The node loop node by node through [`add_solid_node`] (the form before the loop went
    /// by arrays): the reference for the bit-for-bit test.
    fn node_by_node<P: Potential + ?Sized, const FAR: bool, const FULL: bool>(
        e: &EllipsoidSurface,
        grid: &SphereGrid,
        aim: &Aim,
        source: &P,
        map: &FrameMap,
    ) -> SolidSums {
        let axes = e.semi_axes();
        let cofactor = Vec3::new(axes.y * axes.z, axes.x * axes.z, axes.x * axes.y);
        let mut totals = SolidTotals::new();
        let mut sizes = SolidMagnitudes::default();
        let reference = source.potential(&map.apply(&Vec3::zeros()));
        for (d, n) in grid.blocks() {
            let mut block = SolidBlock::default();
            for k in 0..n {
                let s = aim.frame * Vec3::new(d.x[k], d.y[k], d.z[k]);
                let x = axes.component_mul(&s);
                let w = cofactor.component_mul(&s) * d.weight[k];
                let field = if FULL || FAR {
                    source.field(&map.apply(&x))
                } else {
                    Field {
                        potential: source.potential(&map.apply(&x)),
                        acceleration: Vec3::zeros(),
                    }
                };
                let constants = NodeConstants::new(x, &w);
                add_solid_node::<FAR, FULL>(
                    &mut block, &mut sizes, &field, map, &w, &constants, reference,
                );
            }
            totals.add::<FULL>(&block);
        }
        totals.finish(&sizes)
    }

    fn bits(s: &SolidSums) -> Vec<u64> {
        let v = [
            s.potential_flux,
            s.potential_moment,
            s.gradient_moment,
            s.acceleration_flux,
        ];
        v.iter()
            .flat_map(|v| v.iter().map(|c| c.to_bits()).collect::<Vec<_>>())
            .chain(
                [
                    s.energy_flux,
                    s.potential_flux_magnitude,
                    s.potential_moment_magnitude,
                    s.energy_flux_magnitude,
                    s.acceleration_flux_magnitude,
                    s.potential_magnitude,
                ]
                .iter()
                .map(|c| c.to_bits()),
            )
            .collect()
    }

    /// The array form of [`aimed_sums`] equals the node-by-node form bit for bit (every sum
    /// and magnitude, all four variants), on grids whose last block is partial and full, for
    /// an ellipsoid source (batched field) and a point mass, in a general pose.
    #[test]
    fn the_array_loop_equals_the_node_loop_bit_for_bit() -> Result<(), Box<dyn std::error::Error>> {
        let e = EllipsoidSurface::new(1.3, 0.8, 0.5)?;
        let frame = *Rotation3::new(Vector3::new(0.3, -1.1, 0.7)).matrix();
        let map = FrameMap::new(
            &Rotation3::new(Vector3::new(-0.4, 0.9, 2.1)),
            &Vec3::new(2.9, -1.7, 0.6),
        )?;
        let ellipsoid = Ellipsoid::new(1.1, 0.7, 0.4, 2.0)?;
        let point = PointMass::new(1.5)?;
        // Only the aim's frame enters the sums: any aim, turned to a general frame.
        let aimed = aim(&e, &Body::ellipsoid(ellipsoid)?, &map, 1e-12, &|_, _| false).unwrap();
        for (polar, azimuth, cluster) in [(7, 9, 0), (8, 16, 2), (13, 5, 4)] {
            let grid = SphereGrid::new(polar, azimuth, cluster)?;
            assert_eq!(grid.len(), polar * azimuth);
            assert_eq!(
                grid.blocks().map(|(_, n)| n).sum::<usize>(),
                polar * azimuth
            );
            let aim = Aim { frame, ..aimed };
            #[cfg(target_arch = "x86_64")]
            let avx = std::arch::is_x86_feature_detected!("avx");
            #[cfg(not(target_arch = "x86_64"))]
            let avx = false;
            // Without AVX too, where the CPU has it (the plain lane passes).
            let plain = |s: &dyn Potential, far: bool, full: bool| match (far, full) {
                (true, true) => aimed_sums_lanes::<_, true, true>(&e, &grid, &aim, s, &map, false),
                (false, true) => {
                    aimed_sums_lanes::<_, false, true>(&e, &grid, &aim, s, &map, false)
                }
                (true, false) => {
                    aimed_sums_lanes::<_, true, false>(&e, &grid, &aim, s, &map, false)
                }
                (false, false) => {
                    aimed_sums_lanes::<_, false, false>(&e, &grid, &aim, s, &map, false)
                }
            };
            for far in [false, true] {
                for full in [false, true] {
                    let s: &dyn Potential = &ellipsoid;
                    let reference = match (far, full) {
                        (true, true) => node_by_node::<_, true, true>(&e, &grid, &aim, s, &map),
                        (false, true) => node_by_node::<_, false, true>(&e, &grid, &aim, s, &map),
                        (true, false) => node_by_node::<_, true, false>(&e, &grid, &aim, s, &map),
                        (false, false) => node_by_node::<_, false, false>(&e, &grid, &aim, s, &map),
                    };
                    assert_eq!(bits(&plain(s, far, full)), bits(&reference), "avx {avx}");
                }
            }
            macro_rules! check {
                ($source:expr) => {
                    let (s, g) = ($source, &grid);
                    assert_eq!(
                        bits(&aimed_sums::<_, true, true>(&e, g, &aim, s, &map)),
                        bits(&node_by_node::<_, true, true>(&e, g, &aim, s, &map))
                    );
                    assert_eq!(
                        bits(&aimed_sums::<_, false, true>(&e, g, &aim, s, &map)),
                        bits(&node_by_node::<_, false, true>(&e, g, &aim, s, &map))
                    );
                    assert_eq!(
                        bits(&aimed_sums::<_, true, false>(&e, g, &aim, s, &map)),
                        bits(&node_by_node::<_, true, false>(&e, g, &aim, s, &map))
                    );
                    assert_eq!(
                        bits(&aimed_sums::<_, false, false>(&e, g, &aim, s, &map)),
                        bits(&node_by_node::<_, false, false>(&e, g, &aim, s, &map))
                    );
                };
            }
            check!(&ellipsoid);
            check!(&point);
        }
        Ok(())
    }
}
