//! The interaction engine: force, torque and mutual potential energy of two extended bodies by
//! Conway's (2016) surface integrals, for any potential paired with any surface.
//!
//! # Physics (sign convention of the workspace: $\Phi < 0$, $\mathbf a = -\nabla\Phi$)
//!
//! A homogeneous solid A (density $\rho_A$, closed surface $S_A$ with outward $\mathrm d\mathbf S$,
//! centroid $\mathbf c_A$, $\mathbf x = \mathbf r - \mathbf c_A$) in the field $\Phi_B$ of a body B whose
//! matter lies outside A feels
//!
//! $$ \mathbf F_A = \rho_A\\!\int_A \mathbf a_B\\,\mathrm dV = -\rho_A\oint\_{S_A}\Phi_B\\,\mathrm d\mathbf S
//!    \qquad\text{(the paper's Eq. 2)}, $$
//!
//! $$ \mathbf M_A = \rho_A\\!\int_A \mathbf x\times\mathbf a_B\\,\mathrm dV
//!    = -\rho_A\oint\Phi_B\\,\mathbf x\times\mathrm d\mathbf S
//!    = \frac{\rho_A}{2}\oint|\mathbf x|^2\\,\mathrm d\mathbf S\times\mathbf a_B , $$
//!
//! the two torque forms (its torque1, torque2) following from $\mathbf x\times\mathbf a = \nabla\times(\Phi\mathbf x)$
//! and $\mathbf x\times\mathbf a = \tfrac12\nabla\times(|\mathbf x|^2\mathbf a)$ (as $\nabla\times\mathbf a = 0$), and the
//! mutual potential energy
//!
//! $$ V = \rho_A\\!\int_A\Phi_B\\,\mathrm dV = \frac{\rho_A}{3}\oint\Big[\Phi_B\\,\mathbf x + \tfrac12|\mathbf x|^2\\,\mathbf a_B\Big]\cdot\mathrm d\mathbf S < 0 $$
//!
//! (the paper's pot_energy with $U = -V$), from $\nabla\cdot(\Phi\mathbf x + \tfrac12|\mathbf x|^2\mathbf a) = 3\Phi - \tfrac12|\mathbf x|^2\nabla^2\Phi$,
//! **valid only when $\nabla^2\Phi_B = 0$ inside A**, i.e. B's matter outside A. B feels
//! $\mathbf F_B = -\mathbf F_A$ and, about its own centroid, by the balance of angular momentum
//! (the pair's internal torques about any point sum to zero),
//!
//! $$ \mathbf M_B = -\mathbf M_A - (\mathbf c_A - \mathbf c_B)\times\mathbf F_A . $$
//!
//! A uniform disk (surface density σ, normal $\hat{\mathbf n}$) is a lamina: $V = \sigma\iint\Phi_B\\,\mathrm dA$,
//! the normal force $\sigma\hat{\mathbf n}\iint\mathbf a_B\cdot\hat{\mathbf n}\\,\mathrm dA$, the in-plane force
//! $-\sigma\oint\Phi_B\\,\hat{\boldsymbol\nu}\\,\mathrm dl$ around the rim, the torque
//! $\sigma\iint(\mathbf a_B\cdot\hat{\mathbf n})\\,\mathbf x\times\hat{\mathbf n}\\,\mathrm dA$ ([`surfgrav_surfaces::lamina`]).
//!
//! Every sign above is checked by the tests: finite differences of $V$ in B's position and
//! orientation, independent volume integrals, and the closed forms below.
//!
//! # Methods, in order
//!
//! 1. **Point formula.** If A or B is a point mass or a homogeneous sphere S (mass $m_S$, centre
//!    $\mathbf c_S$) and the other body O lies outside it, then since $\Phi_O$ is harmonic in S its
//!    ball averages are centre values: $\mathbf F_S = m_S\\,\mathbf a_O(\mathbf c_S)$,
//!    $V = m_S\\,\Phi_O(\mathbf c_S)$, no torque on S (only the degree-2 harmonic could contribute
//!    and its contribution is $\epsilon\_{ijk}Q\_{kj} = 0$), and O's torque from the balance.
//! 2. **Coplanar disks.** Conway's closed form ([`surfgrav_potentials::disk_pair`]); no torques.
//! 3. **Surface integral by fixed rules** over one body's surface in the other's field, on a
//!    ladder of tensor rules (trapezoid in azimuth after a clustering map, Gauss–Legendre across;
//!    [`rules`] docs); levels grow by about $1.44\times$ in node count, starting from a level
//!    predicted from the gap and the tolerance, and stop when two successive levels agree to the
//!    tolerance (and the two torque forms agree). Over an ellipsoid, unless the pose has both
//!    mirror symmetries (the founding paper's pair), the tables are those of the aimed rule
//!    ([`Parametrisation::Automatic`]; `aimed.rs`): polar angles about a pole aimed at the
//!    nearest point of the other body's singular set, clustered toward it, so that the cost
//!    does not depend on the pose. The finer value is returned with the change
//!    as its error estimate, an upper estimate because each level's error is far below the
//!    previous one's. Mirror symmetries about planes through both centroids, when the
//!    surface's table and the field both have them to rounding, halve or quarter the nodes.
//! 4. **Adaptive cubature** ([`surfgrav_quadrature::AdaptiveCubature`]) on request, and as the
//!    fallback when the ladder runs out of levels: the 10 integrand components (force, both
//!    torques, energy) in one pass, over the polar-angle form of an ellipsoid (the
//!    azimuth–height form's $\sqrt{c^2 - z^2}$ end point at the poles is removed only by a full
//!    azimuthal trapezoid sum).
//!
//! 5. **Nested doubling rule** ([`nested`], [`MethodChoice::Nested`]) on request, for
//!    ellipsoid surfaces: the azimuth–height form with clustered trapezoid doubling in
//!    azimuth and Fejér doubling in height, so each finer level reuses every evaluation and
//!    the estimate (the rate estimate $\delta_2^2/\delta_1$ of the last two changes per
//!    direction) costs nothing. Measured at $10^{-12}$ for the founding paper's pair (example
//!    `work_precision`, summary table): 1.8–2.7 times the time of the cheapest single table
//!    of equal true error at separations 2.1 to 7, 2.8–4.4 at 30 (99 evaluations against a
//!    35-node table: the smallest nested grid that certifies), and 1.0–1.5 times the ladder,
//!    which stays the default (cheaper at every separation measured).
//!
//! [`MethodChoice::FixedLevel`] evaluates one table of the ladder, uncertified.
//!
//! Methods 1 and 2 are the built-in [`PairRule`]s ([`PointFormula`], [`CoplanarDisks`]),
//! asked in order before any surface integral; [`InteractionEngine::with_pair_rule`] puts a
//! user's closed form in front of them. A pair no rule answers goes to the surface integral,
//! one with no surface to integrate over is [`InteractionError::NoSurface`]. Methods 3 to 5 are
//! strategies behind one trait (`strategy/`: the ladder, the aimed ladder, the nested rule,
//! the adaptive rule), over the surface `surface_choice.rs` picks; `assembly.rs` turns their
//! sums into world-frame results.
//!
//! # Body kinds
//!
//! The engine asks a body's potential what it is ([`surfgrav_potentials::Potential`]): its
//! typed view ([`Potential::as_typed`](surfgrav_potentials::Potential::as_typed), a built-in
//! kind or `Custom`), its symmetry (mirror halving of the nodes, the point formula when
//! spherical, central pairs in the dynamics), the radius of its singular set (the start
//! resolution and the surface choice) and the relative cost of its field (the surface choice).
//! A [`Body::custom`] potential that reports these gets the same methods, evaluation counts and
//! results as the built-in kind it describes (`tests/interaction_custom.rs`); one that reports
//! nothing is integrated without those shortcuts.
//!
//! **Polyhedra** ([`Body::polyhedron`]) go to [`mesh_pair`]: their own contact test, the point
//! formula with a sphere, and either the mesh's triangle rules in the partner's field or the
//! partner's surface in the polyhedron's certified expansion, whichever is predicted cheaper.
//!
//! **Which surface.** The integrand $\Phi_B$ continued into B is singular only on B's focal set
//! (the focal disk of an oblate spheroid, the focal segment of a prolate one, the focal ellipse
//! of a triaxial ellipsoid, a point for a sphere, the disk itself for a disk), so convergence
//! over A's surface is set by the gap between A and that set relative to A's size, not by the
//! gap between the surfaces (two of the paper's spheroids 0.0005 apart need only a thousand
//! nodes; a spheroid 0.003 from a disk's rim needs 24 000 over the spheroid, 2 000 over the
//! disk). The engine predicts the cost of both choices from these gap ratios, the elevation
//! of each body above the other's equator, the available symmetries and the cost of each
//! field (measured: a triaxial ellipsoid's field costs 2–3, a disk's 3.5 spheroid fields) and
//! takes the cheaper. Measured on six configurations (small and large, flat and round,
//! prolate above oblate, tilted pairs, triaxial with spheroid) it picked the faster side five
//! times, by factors of 1.6 to 28; the sixth (triaxial A, spheroid B) took the side twice as
//! slow, the two predictions being within 10 % of each other.
//!
//! **Rounding.** Since $\oint\mathrm d\mathbf S = 0$ and $\oint\mathbf x\times\mathrm d\mathbf S = 0$,
//! the potential at the integrated body's centroid is subtracted from $\Phi_B$ in the force and
//! torque sums (and around a lamina's rim): the terms shrink by the ratio of size to distance,
//! and so does their rounding. What remains is bounded by $4\epsilon\sum_k|t_k|$ per sum and
//! enters the error estimate ([`ROUNDING_PER_TERM`]); the force's bound adds the absolute
//! rounding of $\Phi_B$ itself, $4\epsilon\sum_k|\Phi_k||\mathbf W_k|$, which the difference
//! keeps. That term dominates far away and for flat bodies (whose faces' terms cancel), where
//! the acceleration form $\rho\oint\mathbf x\\,(\mathbf a\cdot\mathrm d\mathbf S)$ is summed
//! too and used when its bound is lower ([`FAR_FIELD_RATIO`], [`CANCELLATION_RATIO`]).
//!
//! # Cost
//!
//! A certified result costs the nodes of two levels of a rule (the certificate, a second and
//! finer table, is most of the price); the evaluations are reported with every result. The
//! node loop's cost is mostly the source body's field; through `dyn Potential` it costs more
//! than through a built-in kind. [`InteractionEngine::force`] (the force alone, for
//! integrator stages) skips the torque and energy terms. Measured figures live where they are
//! re-measured: `cargo bench -p surfgrav-interaction`, the examples `work_precision` and
//! `pose_benchmark`, `surfgrav bench`, and the README's Benchmarks.
//!
//! # Overlap
//!
//! Overlapping or touching bodies are an error, never a number: exactly for points, ellipsoids
//! and disks (Perram–Wertheim contact function, [`overlap`] docs), on the integration nodes and
//! centroids for bodies of unknown shape.

mod aimed;
mod assembly;
mod body;
mod closed_form;
mod ellipse_rows;
mod engine;
mod error;
mod kernel;
pub mod mesh_pair;
pub mod nested;
mod options;
pub mod overlap;
pub mod rules;
mod strategy;
mod surface_choice;
pub mod work_precision;

pub use body::{Body, BodyShape};
pub use closed_form::{CoplanarDisks, Pair, PairRule, PointFormula};
pub use engine::{
    InteractionEngine, ANALYTIC_RELATIVE_ERROR, CANCELLATION_RATIO, FAR_FIELD_RATIO,
    ROUNDING_PER_TERM,
};
pub use error::{InteractionError, Side};
pub use kernel::{
    integrate_over_lamina, integrate_over_solid, FrameMap, LaminaIntegrals, LaminaSums,
    SolidIntegrals, SolidSums, BLOCK,
};
pub use options::{
    Evaluation, ForceInteraction, Interaction, InteractionOptions, Method, MethodChoice, Request,
    SurfaceChoice,
};
pub use rules::Parametrisation;

use surfgrav_potentials::Pose;

/// [`InteractionEngine::interact`] with the default options (relative tolerance $10^{-12}$).
pub fn interact(
    a: &Body,
    pose_a: &Pose,
    b: &Body,
    pose_b: &Pose,
) -> Result<Interaction, InteractionError> {
    InteractionEngine::default().interact(a, pose_a, b, pose_b)
}
