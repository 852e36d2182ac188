//! What a caller asks of the engine and what it gets back: the options (method, surface,
//! parametrisation, budget), the [`Request`] of one evaluation, and the results with their
//! units and error norms.

use super::error::Side;
use super::rules::Parametrisation;
use surfgrav_surfaces::{Real, Vec3};

/// How to compute an interaction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MethodChoice {
    /// A closed form where one exists (a point mass or a sphere with anything; coplanar
    /// disks), otherwise the fixed-rule ladder.
    #[default]
    Automatic,
    /// The fixed-rule ladder, even where a closed form exists (needs a surface).
    FixedRules,
    /// The adaptive cubature of `surfgrav-quadrature` over the surface's parameter rectangle.
    Adaptive,
    /// The nested doubling rule ([`super::nested`]): the azimuth–height form of an ellipsoid,
    /// clustered trapezoid doubling in azimuth × Fejér doubling in height, refining the
    /// direction whose change is larger; every finer level reuses every evaluation of the
    /// coarser one. Surfaces other than ellipsoids use the ladder.
    Nested,
    /// One fixed table of the ladder, with this transverse count per half range (the
    /// [`Interaction::level`] the ladder reports), for timing studies or a resolution known
    /// to suffice. Nothing certifies its accuracy: its `error_estimate` is $+\infty$.
    FixedLevel(u16),
}

/// Which body's surface to integrate over.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SurfaceChoice {
    /// The engine's rule (see the module docs).
    #[default]
    Automatic,
    /// Over body A's surface, in B's field.
    A,
    /// Over body B's surface, in A's field.
    B,
}

/// What the engine is asked to achieve and how.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InteractionOptions {
    /// Requested relative accuracy of every output (default $10^{-12}$; see
    /// [`Interaction::error_estimate`] for the norms).
    pub relative_tolerance: Real,
    /// The method.
    pub method: MethodChoice,
    /// Which surface to integrate over.
    pub surface: SurfaceChoice,
    /// The ellipsoid parametrisation of the fixed rules.
    pub parametrisation: Parametrisation,
    /// The most potential evaluations one interaction may spend.
    pub max_evaluations: usize,
    /// Evaluate only a half or a quarter of the nodes when both the surface and the field are
    /// mirror-symmetric about a plane through both centroids (exact to rounding).
    pub exploit_symmetry: bool,
    /// Cluster azimuth nodes toward the other body (a conformal map; see [`super::rules`]).
    pub cluster_azimuth: bool,
}

impl Default for InteractionOptions {
    fn default() -> Self {
        Self {
            relative_tolerance: 1e-12,
            method: MethodChoice::Automatic,
            surface: SurfaceChoice::Automatic,
            parametrisation: Parametrisation::Automatic,
            max_evaluations: 4_000_000,
            exploit_symmetry: true,
            cluster_azimuth: true,
        }
    }
}

/// How a result was obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// A point mass or a sphere: the other body's field at its centre (exact).
    AnalyticPoint,
    /// Two coplanar uniform disks: Conway's closed form.
    AnalyticDiskPair,
    /// Fixed rules over A's surface.
    SurfaceOverA,
    /// Fixed rules over B's surface.
    SurfaceOverB,
    /// Adaptive cubature (over the surface named by [`Interaction::integrated_over`]).
    Adaptive,
    /// A user's closed form ([`super::PairRule`]), by its name.
    ClosedForm(&'static str),
}

impl Method {
    /// The method's name as the command-line tool prints it.
    pub fn name(&self) -> &'static str {
        match self {
            Method::AnalyticPoint => "analytic-point",
            Method::AnalyticDiskPair => "analytic-disk-pair",
            Method::SurfaceOverA => "surface-over-A",
            Method::SurfaceOverB => "surface-over-B",
            Method::Adaptive => "adaptive",
            Method::ClosedForm(name) => name,
        }
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Forces, torques and mutual potential energy of two bodies, in the world frame; torques
/// about each body's own centroid. Units: those of G · mass² / length (energy, torque) and
/// G · mass² / length² (force).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interaction {
    /// Force on A.
    pub force_on_a: Vec3,
    /// Force on B ($= -$`force_on_a`).
    pub force_on_b: Vec3,
    /// Torque on A about A's centroid.
    pub torque_on_a: Vec3,
    /// Torque on B about B's centroid, $\mathbf M_B = -\mathbf M_A - (\mathbf c_A - \mathbf c_B)\times\mathbf F_A$.
    pub torque_on_b: Vec3,
    /// Mutual potential energy $V$ (negative).
    pub potential_energy: Real,
    /// How it was computed.
    pub method: Method,
    /// The body whose surface was integrated over (`None` for a closed form).
    pub integrated_over: Option<Side>,
    /// Potential (field) evaluations spent.
    pub evaluations: usize,
    /// Estimated relative error: the largest of $|\delta\mathbf F|/|\mathbf F|$,
    /// $|\delta V|/|V|$ and, for each torque, $|\delta\mathbf M|/\max(|\mathbf M|, |V|)$ (a torque
    /// is measured against the energy, its natural scale: force times lever arm). For the
    /// fixed rules, the change between the last two levels and the disagreement of the two
    /// torque forms, whichever is larger: an upper estimate, since each level's error is far
    /// below the previous one's.
    pub error_estimate: Real,
    /// The transverse node count (per half range) of the returned value's table, naming its
    /// level on the ladder (fixed rules only).
    pub level: Option<u16>,
}

/// The force between two bodies without torques or energy ([`InteractionEngine::force`](super::InteractionEngine::force));
/// units and conventions as [`Interaction`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceInteraction {
    /// Force on A.
    pub force_on_a: Vec3,
    /// Force on B ($= -$`force_on_a`).
    pub force_on_b: Vec3,
    /// How it was computed.
    pub method: Method,
    /// The body whose surface was integrated over (`None` for a closed form).
    pub integrated_over: Option<Side>,
    /// Potential (field) evaluations spent.
    pub evaluations: usize,
    /// Estimated relative error of the force, $|\delta\mathbf F|/|\mathbf F|$ (for the fixed
    /// rules; other methods report their estimate over all outputs).
    pub error_estimate: Real,
}

/// What a caller needs from one evaluation ([`InteractionEngine::evaluate`](super::InteractionEngine::evaluate)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Request {
    /// The force alone (translation stages): the fixed rules skip the torque and energy terms
    /// of the node loop and certify the force.
    Force,
    /// The force and both torques (rigid-body stages): every term is summed (the energy is the
    /// torques' scale in the error norm), and force and torques are certified.
    Wrench,
    /// Force, both torques and the mutual potential energy, all certified.
    #[default]
    Everything,
}

/// The result of [`InteractionEngine::evaluate`](super::InteractionEngine::evaluate): what the [`Request`] asked for (the rest is
/// `None`); units and conventions as [`Interaction`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Evaluation {
    /// What was asked for.
    pub request: Request,
    /// Force on A.
    pub force_on_a: Vec3,
    /// Force on B ($= -$`force_on_a`).
    pub force_on_b: Vec3,
    /// Torque on A about A's centroid ([`Request::Wrench`], [`Request::Everything`]).
    pub torque_on_a: Option<Vec3>,
    /// Torque on B about B's centroid ([`Request::Wrench`], [`Request::Everything`]).
    pub torque_on_b: Option<Vec3>,
    /// Mutual potential energy ([`Request::Everything`]).
    pub potential_energy: Option<Real>,
    /// How it was computed.
    pub method: Method,
    /// The body whose surface was integrated over (`None` for a closed form).
    pub integrated_over: Option<Side>,
    /// Potential (field) evaluations spent.
    pub evaluations: usize,
    /// Estimated relative error of what was asked for, in the norms of
    /// [`Interaction::error_estimate`] (the nested and adaptive rules estimate everything).
    pub error_estimate: Real,
    /// The level of the returned value's table (fixed rules only).
    pub level: Option<u16>,
}
