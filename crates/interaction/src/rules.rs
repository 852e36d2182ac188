//! The resolution ladder: which tensor rule each level uses on each kind of surface, the
//! azimuthal clustering map, and the construction of the (cached) node tables.
//!
//! # Levels
//!
//! A level is named by its transverse count $t$ (Gauss–Legendre nodes on each half of the
//! transverse range, split at the equator: $z \in [0, c]$ and its mirror image for the
//! azimuth–height form, $\theta \in [0, \pi/2]$ and its mirror for the polar-angle form, the
//! radius $[0, R]$ for a lamina, the whole range for a user surface). The azimuth count is
//! $N = 2\lceil t / (2\kappa)\rceil$ with the ratio $\kappa$ chosen from the geometry
//! (below). Splitting at the equator puts Gauss–Legendre's end clustering where
//! a body in the equatorial plane comes closest; it halves the nodes needed there (measured:
//! 2 × 11 instead of 31 for the founding paper's pair at separation 2.1).
//!
//! **The ratio κ**, measured with the node loop for spheroids of $c/a$ from 0.1 to 4 in the
//! field of the founding paper's spheroid at gaps of 0.1, 1 and 5 radii (smallest azimuth
//! count $N$ with the transverse direction converged, and smallest $t$ with the azimuth
//! converged, for $10^{-12}$):
//!
//! | B's position | azimuth–height $t/N$ | polar-angle $t/N$ |
//! |---|---|---|
//! | equatorial plane, flattened A ($c/a \le 0.5$) | 0.35–0.54 | 0.44–0.75 |
//! | equatorial plane, sphere or prolate A | 0.36–0.71 | 0.46–0.89 |
//! | 45° above the plane | 0.42–0.85 | 0.67–1.0 |
//!
//! so $\kappa = 0.38 + 0.3\\,|\sin\beta| + 0.2\\,\min(c/a, a/c)^2$ for elevation β (times 1.5 for
//! the polar-angle form, 0.4 + 0.3|sin β| radially for a lamina), rounded up to a tabulated
//! value. A mismatch costs nodes, never accuracy: both directions are refined at every step.
//!
//! The engine steps $t \to \max(t + 2, \lceil r t\rceil)$ with $r = 1 + 1/\log\_{10}(1/\tau)$ for
//! the tolerance τ (at least 1.08): with geometric convergence, the error of the finer level
//! is then at most a tenth of the coarser one's once the coarser one reaches τ, so the change
//! between them bounds the finer level's error.
//!
//! # Azimuthal clustering
//!
//! Near contact the integrand varies fastest on the side of the surface facing the other body.
//! The trapezoid rule in $\psi$ is applied after the periodic conformal (Möbius) map
//!
//! $$ \varphi(\psi) = 2\arctan\\!\big(\varepsilon\tan\tfrac\psi2\big), \qquad
//!    \varphi'(\psi) = \frac{\varepsilon}{\cos^2\frac\psi2 + \varepsilon^2\sin^2\frac\psi2}, $$
//!
//! a real-analytic bijection of the circle that puts nodes $1/\varepsilon$ times denser at
//! $\varphi = 0$ (facing the other body) and $\varepsilon$ times sparser at $\varphi = \pi$. Being
//! analytic and periodic, it keeps the trapezoid rule's geometric convergence; it moves the
//! integrand's complex singularities near $\varphi = 0$ away from the real axis. Nodes sit at
//! $\psi_j = -\pi + (j + \tfrac12)h$, symmetric about $\psi = 0$ with none on the mirror plane
//! $\varphi \in \\{0, \pi\\}$, so a table can hold only the half $\varphi \in (0, \pi)$ when the field
//! is mirror-symmetric.

use super::body::BodyShape;
use super::error::InteractionError;
use super::kernel::SolidTable;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::sync::Arc;
use surfgrav_quadrature::{GaussLegendre, Rule1D};
use surfgrav_surfaces::{
    BorrowedRule, EllipsoidSurface, Interval, LaminaNodes, Real, Surface, SurfaceNodes,
};

/// The parametrisation of an ellipsoid's surface the fixed rules use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Parametrisation {
    /// The aimed form ([`Self::Aimed`]) for ellipsoids, except where the pose has both
    /// mirror symmetries (the other body in X's equatorial plane and in a plane of symmetry):
    /// there the azimuth–height form, whose tables are then quartered. The default.
    #[default]
    Automatic,
    /// The founding paper's $(\varphi, z)$ form ([`surfgrav_surfaces::EllipsoidAzimuthHeight`]):
    /// Gauss–Legendre in $z$.
    AzimuthHeight,
    /// The smooth $(\theta, \varphi)$ form ([`surfgrav_surfaces::EllipsoidPolarAzimuth`]): Gauss–Legendre in
    /// $\theta$.
    PolarAzimuth,
    /// For ellipsoids, polar angles about a pole aimed at the other body, clustered toward it
    /// (`interaction/aimed.rs` documents the clustering, the start and the certificate);
    /// other surfaces, and tables asked for directly, use the azimuth–height form.
    Aimed,
}

/// Clustering strengths $\varepsilon$ the tables are built with (index 0: uniform).
pub(crate) const CLUSTERING: [Real; 8] = [1.0, 0.9, 0.8, 0.7, 0.6, 0.5, 0.4, 0.3];

/// Transverse-to-azimuth node ratios κ the tables are built with.
pub(crate) const TRANSVERSE_RATIO: [Real; 8] = [0.3, 0.35, 0.4, 0.5, 0.6, 0.7, 0.85, 1.0];

/// The ratio κ of transverse to azimuth nodes that balances the two directions' errors (see
/// the module docs for the measurements).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TransverseRatio;

impl TransverseRatio {
    /// κ for a surface of this shape, seen from a body at elevation `sin_elevation` above its
    /// equatorial plane.
    pub(crate) fn for_geometry(
        shape: &BodyShape,
        parametrisation: Parametrisation,
        sin_elevation: Real,
    ) -> Real {
        let s = sin_elevation.abs().min(1.0);
        match shape {
            BodyShape::Solid(e) => {
                let equatorial = e.x_semi_axis().max(e.y_semi_axis());
                let aspect = e.z_semi_axis() / equatorial;
                let roundness = aspect.min(1.0 / aspect).powi(2);
                let ah = 0.38 + 0.3 * s + 0.2 * roundness;
                match parametrisation {
                    Parametrisation::AzimuthHeight
                    | Parametrisation::Aimed
                    | Parametrisation::Automatic => ah,
                    Parametrisation::PolarAzimuth => 1.5 * ah,
                }
            }
            BodyShape::Disk(_) => 0.4 + 0.3 * s,
            _ => 0.6,
        }
    }

    /// The index of the tabulated ratio nearest to `kappa` from above.
    pub(crate) fn index(kappa: Real) -> u8 {
        TRANSVERSE_RATIO
            .iter()
            .position(|&k| k >= kappa - 0.02)
            .unwrap_or(TRANSVERSE_RATIO.len() - 1) as u8
    }
}

/// What identifies a node table of a body.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) struct TableKey {
    pub(crate) parametrisation: Parametrisation,
    /// Transverse count $t$ per half range.
    pub(crate) transverse: u16,
    /// Index into [`TRANSVERSE_RATIO`].
    pub(crate) ratio: u8,
    /// Index into [`CLUSTERING`].
    pub(crate) clustering: u8,
    /// Only the half $z \ge 0$ (the field is symmetric about the body's x–y plane).
    pub(crate) half_transverse: bool,
    /// Only the half $y \ge 0$ (the field is symmetric about the body's x–z plane).
    pub(crate) half_azimuth: bool,
}

/// A node table of either kind, shared.
#[derive(Debug, Clone)]
pub(crate) enum NodeTable {
    Solid(Arc<SolidTable>),
    Lamina(Arc<LaminaNodes>),
}

impl NodeTable {
    pub(crate) fn len(&self) -> usize {
        match self {
            NodeTable::Solid(t) => t.len(),
            NodeTable::Lamina(t) => t.area_points().len() + t.rim_points().len(),
        }
    }
}

/// Largest transverse count per half range (Gauss–Legendre orders are built up to 1000).
pub const MAX_TRANSVERSE: u16 = 600;

/// Azimuth nodes over a full turn for transverse count `t` and ratio κ.
pub(crate) fn azimuth_count(transverse: u16, kappa: Real) -> usize {
    2 * (Real::from(transverse) / (2.0 * kappa)).ceil().max(2.0) as usize
}

/// Number of nodes of the table `key` of `shape`, without building it.
pub(crate) fn table_size(shape: &BodyShape, key: &TableKey) -> usize {
    let kappa = TRANSVERSE_RATIO[usize::from(key.ratio).min(TRANSVERSE_RATIO.len() - 1)];
    let n = azimuth_count(key.transverse, kappa);
    let azimuth = if key.half_azimuth { n / 2 } else { n };
    let t = usize::from(key.transverse.max(1));
    match shape {
        BodyShape::Solid(_) => azimuth * if key.half_transverse { t } else { 2 * t },
        BodyShape::Disk(_) => azimuth * (t + 1),
        BodyShape::Surface(_) => azimuth * t,
        BodyShape::Point | BodyShape::FieldOnly | BodyShape::Mesh(_) => 0,
    }
}

/// The next transverse count of the ladder for growth factor `growth`: at least two more
/// nodes, because Gauss–Legendre errors on a half range can stall from one count to the next
/// (measured: 11 and 12 nodes give the same error for the founding paper's pair at separation
/// 2.1) but always drop over two.
pub(crate) fn next_transverse(t: u16, growth: Real) -> u16 {
    (t + 2).max((growth * Real::from(t)).ceil() as u16)
}

/// The clustered azimuth rule of the module docs: `count` nodes in $[0, 2\pi)$ over a full turn
/// (or only those in $(0, \pi)$ when `half`) and their weights, for clustering strength
/// `clustering` $= \varepsilon \in (0, 1]$ (1: the plain periodic trapezoid rule).
pub fn azimuth_rule(count: usize, clustering: Real, half: bool) -> (Vec<Real>, Vec<Real>) {
    let h = TAU / count as Real;
    let eps = clustering;
    let mut nodes = Vec::with_capacity(count);
    let mut weights = Vec::with_capacity(count);
    let first = if half { count / 2 } else { 0 };
    for j in first..count {
        let psi = -PI + (j as Real + 0.5) * h;
        let (s, c) = (0.5 * psi).sin_cos();
        let mut phi = 2.0 * (eps * s).atan2(c);
        if phi < 0.0 {
            phi += TAU;
        }
        nodes.push(phi.clamp(0.0, TAU));
        weights.push(h * eps / (c * c + eps * eps * s * s));
    }
    (nodes, weights)
}

fn gauss(order: usize, lower: Real, upper: Real) -> Result<GaussLegendre, InteractionError> {
    Ok(GaussLegendre::new(order, lower, upper)?)
}

/// Builds the table of `shape` for `key` (body frame).
pub(crate) fn build_table(shape: &BodyShape, key: TableKey) -> Result<NodeTable, InteractionError> {
    let kappa = TRANSVERSE_RATIO[usize::from(key.ratio).min(TRANSVERSE_RATIO.len() - 1)];
    let n_azimuth = azimuth_count(key.transverse, kappa);
    let n_transverse = usize::from(key.transverse.max(1));
    let eps = CLUSTERING[usize::from(key.clustering).min(CLUSTERING.len() - 1)];
    let (phi, w_phi) = azimuth_rule(n_azimuth, eps, key.half_azimuth);
    let azimuth = BorrowedRule::new(&phi, &w_phi, Interval::FULL_TURN)?;
    match shape {
        BodyShape::Solid(e) => Ok(NodeTable::Solid(Arc::new(SolidTable::new(
            ellipsoid_table(e, key, azimuth, n_transverse)?,
        )))),
        BodyShape::Disk(lamina) => {
            let radial = gauss(n_transverse, 0.0, lamina.radius())?;
            let radial_rule = BorrowedRule::new(
                radial.nodes(),
                radial.weights(),
                Interval::new(0.0, lamina.radius())?,
            )?;
            Ok(NodeTable::Lamina(Arc::new(lamina.nodes(
                azimuth,
                radial_rule,
                azimuth,
            )?)))
        }
        BodyShape::Surface(surface) => Ok(NodeTable::Solid(Arc::new(SolidTable::new(
            surface_table(surface.as_ref(), azimuth, n_transverse)?,
        )))),
        BodyShape::Point | BodyShape::FieldOnly | BodyShape::Mesh(_) => {
            Err(InteractionError::NoSurface {
                reason: "a node table was requested for a body without a surface",
            })
        }
    }
}

/// Gauss–Legendre on `[start, centre]`-mirrored panels: `t` nodes on $[m, \text{upper}]$ and, unless
/// `half`, their mirror images about $m$.
fn split_rule(
    t: usize,
    mirror: Real,
    upper: Real,
    half: bool,
) -> Result<(Vec<Real>, Vec<Real>), InteractionError> {
    let g = gauss(t, mirror, upper)?;
    let mut nodes = g.nodes().to_vec();
    let mut weights = g.weights().to_vec();
    if !half {
        for (&x, &w) in g.nodes().iter().zip(g.weights()) {
            nodes.push((2.0 * mirror - x).max(2.0 * mirror - upper));
            weights.push(w);
        }
    }
    Ok((nodes, weights))
}

fn ellipsoid_table(
    e: &EllipsoidSurface,
    key: TableKey,
    azimuth: BorrowedRule<'_>,
    n_transverse: usize,
) -> Result<SurfaceNodes, InteractionError> {
    match key.parametrisation {
        Parametrisation::AzimuthHeight | Parametrisation::Aimed | Parametrisation::Automatic => {
            let c = e.z_semi_axis();
            let (nodes, weights) = split_rule(n_transverse, 0.0, c, key.half_transverse)?;
            let rule = BorrowedRule::new(&nodes, &weights, Interval::new(-c, c)?)?;
            Ok(SurfaceNodes::with_periodic_rule(
                &e.azimuth_height(),
                azimuth,
                rule,
            )?)
        }
        Parametrisation::PolarAzimuth => {
            let (nodes, weights) = split_rule(n_transverse, FRAC_PI_2, PI, key.half_transverse)?;
            // θ measured from the +z pole: the upper panel is θ ∈ [0, π/2].
            let nodes: Vec<Real> = nodes.iter().map(|&x| PI - x).collect();
            let rule = BorrowedRule::new(&nodes, &weights, Interval::new(0.0, PI)?)?;
            Ok(SurfaceNodes::with_periodic_rule(
                &e.polar_azimuth(),
                azimuth,
                rule,
            )?)
        }
    }
}

fn surface_table(
    surface: &dyn Surface,
    azimuth: BorrowedRule<'_>,
    n_transverse: usize,
) -> Result<SurfaceNodes, InteractionError> {
    let domain = surface.parameter_domain();
    let transverse_interval = match domain.periodicity {
        surfgrav_surfaces::Periodicity::U => domain.v,
        _ => domain.u,
    };
    let t = gauss(
        n_transverse,
        transverse_interval.start(),
        transverse_interval.end(),
    )?;
    let transverse = BorrowedRule::new(t.nodes(), t.weights(), transverse_interval)?;
    Ok(SurfaceNodes::with_periodic_rule(
        surface, azimuth, transverse,
    )?)
}

/// The volume enclosed by a surface, by $\tfrac13\oint\mathbf r\cdot\mathrm d\mathbf S$ on a
/// 300 × 150 table (for user surfaces that do not know it).
pub(crate) fn surface_volume(surface: &dyn Surface) -> Option<Real> {
    let (phi, w) = azimuth_rule(300, 1.0, false);
    let azimuth = BorrowedRule::new(&phi, &w, Interval::FULL_TURN).ok()?;
    surface_table(surface, azimuth, 150)
        .ok()
        .map(|t| t.enclosed_volume())
}
