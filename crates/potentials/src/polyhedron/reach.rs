//! The exterior expansion taken closer to the body: degree up to [`REACH_DEGREE`], for
//! callers that need the field only to a stated relative accuracy (the interaction engine at
//! its tolerance) and would otherwise pay the direct sum over every face.
//!
//! The moments, the recurrences and the truncation bounds are those of [`super::multipole`];
//! only the highest degree differs (and with it the cost of the moments, built once on first
//! use). At $q = R/r$ the degree chosen is the smallest whose bounds on $|T_N|/|\Phi|$ and
//! $|\nabla T_N|/|\mathbf a|$ are both below the caller's `relative_bound`; for
//! `relative_bound` = $10^{-13}$ that is degree 52 at 2 radii, 43 at 2.3, 35 at 2.7, 27 at
//! 3.5 and 21 at 5 (test `polyhedron_reach`, which also checks the bound against the direct
//! sum on KW4 Beta and Didymos: the worst difference is 0.21 of the bound plus 3e-14).
//!
//! **Why not closer than 2 radii.** A moment $M_n^m$ is a Fourier coefficient of terms of size
//! up to $1/n!$ while its value can be $2^n$ times smaller ($m = n$), so it carries an absolute
//! rounding of about $\varepsilon/n!$; the irregular harmonic it multiplies is at most
//! $(2n-1)!!/x^{n+1}$, and $(2n-1)!!/n! < 2^n$. The rounding each degree adds to the potential
//! is therefore below $\varepsilon\\,(2/x)^n$ in units of $GM/R$: bounded for $x \ge 2$, growing
//! geometrically inside. [`REACH_RADII`] keeps the expansion out there.

use super::multipole::{self, Multipole};
use super::Polyhedron;
use crate::{Field, Real, Vec3};

/// Highest degree of the near-reaching expansion.
pub const REACH_DEGREE: usize = 60;

/// The expansion is never used closer than this many circumscribing radii to the centroid
/// (see the module docs for the rounding reason).
pub const REACH_RADII: Real = 2.0;

impl Polyhedron {
    pub(super) fn reach_multipole(&self) -> &Multipole {
        self.reach.get_or_init(|| {
            Multipole::new(
                &self.vertices,
                &self.faces,
                self.density,
                self.centroid,
                self.circumscribing_radius,
                REACH_DEGREE,
            )
        })
    }

    /// The degree of the expansion that meets `relative_bound` (on $|T_N|/|\Phi|$ and
    /// $|\nabla T_N|/|\mathbf a|$, the rigorous truncation bounds of the far-field expansion,
    /// [`super`] docs) at `radii` circumscribing radii from the centroid; `None` inside
    /// [`REACH_RADII`] or where [`REACH_DEGREE`] does not suffice.
    pub fn expansion_degree(&self, radii: Real, relative_bound: Real) -> Option<usize> {
        let usable = radii >= REACH_RADII && relative_bound > 0.0;
        if !usable {
            return None;
        }
        let q = 1.0 / radii;
        (0..=REACH_DEGREE).find(|&n| {
            let (phi, acc) = multipole::relative_bounds(q, n);
            phi <= relative_bound && acc <= relative_bound
        })
    }

    /// The smallest distance from the centroid (in circumscribing radii, at least
    /// [`REACH_RADII`]) at which [`Self::field_expansion`] meets `relative_bound`.
    pub fn expansion_reach(&self, relative_bound: Real) -> Real {
        // The bounds fall monotonically with distance: bisect on the distance.
        let (mut lo, mut hi) = (REACH_RADII, 1e3);
        if self.expansion_degree(lo, relative_bound).is_some() {
            return lo;
        }
        if self.expansion_degree(hi, relative_bound).is_none() {
            return Real::INFINITY;
        }
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if self.expansion_degree(mid, relative_bound).is_some() {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        hi
    }

    /// The field at body-frame `p` by the exterior expansion, to the smallest degree whose
    /// truncation bounds relative to $|\Phi|$ and $|\mathbf a|$ are below `relative_bound`,
    /// with that degree; `None` where no degree up to [`REACH_DEGREE`] meets it or `p` is
    /// within [`REACH_RADII`] (then use [`crate::Potential::field`]). So
    /// $|\Phi\_{\text{returned}} - \Phi| \le$ `relative_bound` $|\Phi|$ up to rounding, and
    /// likewise for the acceleration.
    pub fn field_expansion(&self, p: &Vec3, relative_bound: Real) -> Option<(Field, usize)> {
        let radii = (p - self.centroid).norm() / self.circumscribing_radius;
        let degree = self.expansion_degree(radii, relative_bound)?;
        let mp = self.reach_multipole();
        Some((self.multipole_field(mp, p, degree), degree))
    }
}
