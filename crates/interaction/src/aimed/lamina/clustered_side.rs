//! One side of a 1-D rule clustered toward one end by the sinh map, and its plan against a
//! set of complex singularities from the Bernstein-ellipse model of Gauss–Legendre's error
//! ("Clustering" in the module docs of [`super`]).

use nalgebra::Complex;
use surfgrav_surfaces::Real;

/// A side's sinh width is the widest of the candidates whose predicted count is within this
/// factor of the fewest. The one-pole model's optimum is too narrow for the rule as used: each
/// angular side serves radii whose singularity is up to twice as wide as the one it was
/// planned for, and a singular curve puts further singular points beside the nearest one.
/// Measured with the true error of each level (the `level_errors` tool, `tools.rs`; 35 disk
/// cases of the seed-12 pose set, the stretch model with up to 8 points and
/// [`AREA_MARGIN`](super::AREA_MARGIN) on every plan): the evaluations of the first levels within 1e-12 total 15,094 with factor
/// 1.25, 13,458 with 1.5, 13,928 with 1.75 and 14,212 with 2 (seed 13: 13,764 with 1.5,
/// 14,816 with 2; with the one-point plan and no slack, 20,754 and 20,124).
pub(super) const WIDTH_SLACK: Real = 1.5;

/// How a plan searches the sinh widths ([`ClusteredSide::plan_many`]): every `step`-th of the
/// candidates $w = 2^{(i - 7)/2}$ times the nearest singularity's distance ($i = 1, \dots, 9$,
/// and plain Gauss–Legendre), and the widest within `slack` of the fewest predicted nodes.
#[derive(Debug, Clone, Copy)]
pub(super) struct Search {
    pub(super) slack: Real,
    pub(super) step: usize,
}

/// The search of the plans against a singular curve's sampled points (or one point): width
/// steps of $\sqrt2$ and [`WIDTH_SLACK`].
pub(super) const STRETCH_SEARCH: Search = Search {
    slack: WIDTH_SLACK,
    step: 1,
};

/// The search of the plans against a singular circle's exact row singularities (the
/// angular table and the rim): the fewest nodes, width steps of 2. Measured against steps of
/// $\sqrt2$: planning a disk side 6.5 → 5.3 µs (`plan_timing`), the 96 cases of
/// `pose_benchmark` 79,644 → 79,860 evaluations (seed 12) and 87,578 → 88,192 (seed 16), the
/// disk–disk cases 1.1 and 2.0 µs faster on average (best of three).
pub(super) const EXACT_SEARCH: Search = Search {
    slack: 1.0,
    step: 2,
};

/// A side $t \in [0, L]$ of a 1-D rule, clustered toward $t = 0$ (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ClusteredSide {
    /// $L$.
    pub(super) length: Real,
    /// The sinh map's width $w$; infinite: plain Gauss–Legendre in $t$.
    pub(super) width: Real,
    /// The predicted node count for the tolerance.
    pub(super) predicted: Real,
    /// The sinh map's $\mu = \operatorname{asinh}(L/w)$ (0 for plain Gauss–Legendre).
    pub(super) mu: Real,
}

/// The Bernstein parameter $\rho$ of the ellipse with foci 0 and 1 through $u^\ast$ = `u`
/// (at least $1 + 10^{-3}$): the Gauss–Legendre error on $u \in [0, 1]$ falls like
/// $\rho^{-2n}$.
#[inline]
pub(super) fn bernstein_rho(u: Complex<Real>) -> Real {
    // The semi-major axis (in units of the half-length) a = (|u| + |u - 1|), and
    // rho = a + sqrt(a^2 - 1). Moduli by square roots (`Complex::norm` calls the C library's
    // `hypot`, several times slower, and the plans evaluate this for every point and
    // candidate width).
    let modulus = |re: Real, im: Real| (re * re + im * im).sqrt();
    let a = modulus(u.re, u.im) + modulus(u.re - 1.0, u.im);
    (a + (a * a - 1.0).max(0.0).sqrt()).max(1.0 + 1e-3)
}

/// The complex $\operatorname{asinh}$, by real functions on the imaginary axis (the plans'
/// singularities at the clustering point itself: $\operatorname{asinh}(iy) = i\arcsin y$
/// for $y \le 1$, $\operatorname{acosh} y + i\pi/2$ beyond), otherwise `aimed::asinh`.
#[inline]
pub(super) fn asinh_of(z: Complex<Real>) -> Complex<Real> {
    if z.re == 0.0 && z.im >= 0.0 {
        if z.im <= 1.0 {
            Complex::new(0.0, z.im.asin())
        } else {
            Complex::new(z.im.acosh(), std::f64::consts::FRAC_PI_2)
        }
    } else {
        crate::aimed::asinh(z)
    }
}

/// The Gauss–Legendre count whose error bound $\rho^{-2n}$ meets the tolerance $\tau$, from
/// `log_tolerance` $= \ln(1/\tau) \ge 0$: $\ln(1/\tau) / (2\ln\rho)$. It falls as $\rho$
/// grows, so the largest count over several points is that of the least $\rho$.
#[inline]
pub(super) fn bernstein_count(log_tolerance: Real, rho: Real) -> Real {
    log_tolerance / (2.0 * rho.ln())
}

/// A candidate width of [`ClusteredSide::plan_many`], evaluated point by point.
#[derive(Debug, Clone, Copy)]
pub(super) struct Candidate {
    /// The sinh map's width (infinite: plain Gauss–Legendre; 0: not a candidate).
    pub(super) width: Real,
    /// $\mu = \operatorname{asinh}(L/w)$ (0 for plain Gauss–Legendre).
    pub(super) mu: Real,
    /// The least $\rho$ over the points evaluated so far, its count and its point.
    pub(super) least: Real,
    pub(super) count: Real,
    pub(super) worst: usize,
    /// The point evaluated first, and how many have been.
    pub(super) start: usize,
    pub(super) done: usize,
}

impl Default for Candidate {
    fn default() -> Self {
        Self {
            width: 0.0,
            mu: 0.0,
            least: Real::INFINITY,
            count: 0.0,
            worst: 0,
            start: 0,
            done: 0,
        }
    }
}

impl Candidate {
    /// Evaluates the remaining points (from `start`, cyclically) until all are done (true:
    /// `count` is the largest count over the points) or the count exceeds `bound` (false:
    /// `count` is a lower bound, the evaluation can go on later with a larger bound).
    pub(super) fn advance(
        &mut self,
        singular: &[Complex<Real>],
        length: Real,
        log_tolerance: Real,
        bound: Real,
    ) -> bool {
        if self.count > bound {
            return false;
        }
        let n = singular.len();
        while self.done < n {
            let k = (self.start + self.done) % n;
            self.done += 1;
            let t = singular[k];
            let rho = if self.width.is_finite() {
                bernstein_rho(asinh_of(t / self.width) / self.mu)
            } else {
                bernstein_rho(t / length)
            };
            // The count falls as ρ grows: only a new least ρ raises it.
            if rho < self.least {
                self.least = rho;
                self.worst = k;
                self.count = bernstein_count(log_tolerance, rho);
                if self.count > bound {
                    return false;
                }
            }
        }
        true
    }
}

impl ClusteredSide {
    /// The side of length `length` whose integrand is singular at complex $t^\ast$ =
    /// `singular`: the width (or none) with the fewest predicted nodes.
    pub(super) fn plan(length: Real, singular: Complex<Real>, tolerance: Real) -> Self {
        Self::plan_many(length, &[singular], tolerance, STRETCH_SEARCH)
    }

    /// The side of length `length` whose integrand is singular at each of `singular`: of the
    /// widths `search` tries, the widest whose predicted count for the least favourable point
    /// is within its slack of the fewest (plain Gauss–Legendre counts as the widest of all).
    pub(super) fn plan_many(
        length: Real,
        singular: &[Complex<Real>],
        tolerance: Real,
        search: Search,
    ) -> Self {
        let length = length.max(Real::MIN_POSITIVE);
        // ln(1/τ) once per plan (τ in (0, 1), the engine's check; otherwise every count is 0).
        let log_tolerance = (1.0 / tolerance).ln().max(0.0);
        let scale = singular
            .iter()
            .map(|t| (t.re * t.re + t.im * t.im).sqrt())
            .fold(Real::INFINITY, Real::min)
            .max(1e-12 * length);
        // Candidate 0: plain Gauss–Legendre; candidate i = 1..=9: the sinh map of width
        // scale·2^((i − 7)/2), if narrower than the side.
        let mut candidates = [Candidate::default(); 10];
        for (i, c) in candidates.iter_mut().enumerate().skip(1) {
            let width = scale * (0.5 * (i as Real - 7.0)).exp2();
            if width < length && (i - 1) % search.step == 0 {
                *c = Candidate {
                    width,
                    mu: (length / width).asinh(),
                    ..Candidate::default()
                };
            }
        }
        candidates[0].width = Real::INFINITY;
        // Only the fewest count and the chosen width's count are needed exactly: every other
        // candidate stops at the first point whose count exceeds the bound. The fewest
        // first, the likeliest candidates first (measured on the pose set: the width of the
        // scale, plain Gauss–Legendre, then the wider ones), each starting at the point
        // that was least favourable for the one before (usually again the least favourable).
        let mut fewest = Real::INFINITY;
        let mut first = 0;
        for i in [7, 0, 8, 9, 6, 5, 4, 3, 2, 1] {
            let c = &mut candidates[i];
            if c.width == 0.0 {
                continue;
            }
            c.start = first;
            if c.advance(singular, length, log_tolerance, fewest) {
                fewest = fewest.min(c.count);
            }
            first = c.worst;
        }
        // Then the widest within the slack of the fewest (plain first: it is the widest); the
        // candidate of the fewest always qualifies.
        let bound = search.slack * fewest;
        let chosen = [0, 9, 8, 7, 6, 5, 4, 3, 2, 1].into_iter().find(|&i| {
            let c = &mut candidates[i];
            c.width != 0.0 && c.count <= bound && c.advance(singular, length, log_tolerance, bound)
        });
        // None (not reached: the fewest qualifies): plain Gauss–Legendre.
        let c = match chosen {
            Some(i) => candidates[i],
            None => {
                let mut plain = candidates[0];
                plain.advance(singular, length, log_tolerance, Real::INFINITY);
                plain
            }
        };
        Self {
            length,
            width: c.width,
            predicted: c.count,
            mu: c.mu,
        }
    }

    /// A piece of length `length` clustered toward its start, where the integrand is singular
    /// at $t^\ast = i\\,$`width`, with another singularity `far` beyond its end: the sinh map
    /// of that width, and the count of the less favourable of the two (the far one taken on
    /// the real axis, which only overstates it).
    pub(super) fn toward_end(length: Real, width: Real, far: Real, log_tolerance: Real) -> Self {
        let length = length.max(Real::MIN_POSITIVE);
        let width = width.max(1e-12 * length);
        let mu = (length / width).asinh();
        let own = bernstein_rho(Complex::new(0.0, std::f64::consts::FRAC_PI_2 / mu));
        let beyond = bernstein_rho(Complex::new(((length + far) / width).asinh() / mu, 0.0));
        Self {
            length,
            width,
            predicted: bernstein_count(log_tolerance, own.min(beyond)),
            mu,
        }
    }

    pub(super) fn with_margin(self, margin: Real) -> Self {
        Self {
            predicted: self.predicted * margin,
            ..self
        }
    }

    /// $t(u)$ and $t'(u)$.
    #[inline]
    pub(super) fn map(&self, u: Real) -> (Real, Real) {
        if self.width.is_finite() {
            let mu = self.mu;
            // cosh from sinh (one call to the C library instead of two; within a few ulp).
            let sinh = (mu * u).sinh();
            let cosh = (sinh * sinh + 1.0).sqrt();
            (self.width * sinh, self.width * mu * cosh)
        } else {
            (self.length * u, self.length)
        }
    }
}
