//! Four `f64` lanes operated on together: the batched paths of [`crate::ellipsoid`] and
//! [`crate::carlson`] write each scalar operation once for all lanes, so the compiler emits one
//! vector instruction per operation (two with SSE2, one with AVX).
//!
//! Every operation rounds lane by lane exactly as the scalar operation does: IEEE addition,
//! multiplication, division and square root, `f64::max` and `f64::abs`; nothing is fused (no
//! FMA is enabled anywhere), so a lane's result is bit for bit the scalar code's when the same
//! operations are applied in the same order.

use crate::{Field, Real, Vec3};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Number of lanes.
pub(crate) const LANES: usize = 4;

/// One `f64` per lane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct F4(pub(crate) [f64; LANES]);

/// One flag per lane, as an all-ones or all-zeros bit pattern (the form a vector comparison
/// produces, so that selections compile to bitwise operations rather than branches).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct M4(pub(crate) [u64; LANES]);

/// The bit pattern of a flag.
#[inline(always)]
fn flag(v: bool) -> u64 {
    if v {
        u64::MAX
    } else {
        0
    }
}

impl F4 {
    /// The same value in every lane.
    #[inline(always)]
    pub(crate) fn splat(v: f64) -> Self {
        Self([v; LANES])
    }

    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        Self([f(self.0[0]), f(self.0[1]), f(self.0[2]), f(self.0[3])])
    }

    #[inline(always)]
    fn zip(self, other: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        Self([
            f(self.0[0], other.0[0]),
            f(self.0[1], other.0[1]),
            f(self.0[2], other.0[2]),
            f(self.0[3], other.0[3]),
        ])
    }

    #[inline(always)]
    fn compare(self, other: Self, f: impl Fn(f64, f64) -> bool) -> M4 {
        M4([
            flag(f(self.0[0], other.0[0])),
            flag(f(self.0[1], other.0[1])),
            flag(f(self.0[2], other.0[2])),
            flag(f(self.0[3], other.0[3])),
        ])
    }

    /// Lane-wise `f64::sqrt`.
    #[inline(always)]
    pub(crate) fn sqrt(self) -> Self {
        self.map(f64::sqrt)
    }

    /// Lane-wise `f64::abs`.
    #[inline(always)]
    pub(crate) fn abs(self) -> Self {
        self.map(f64::abs)
    }

    /// Lane-wise `f64::max` (a NaN loses to a number, as there).
    #[inline(always)]
    pub(crate) fn max(self, other: Self) -> Self {
        self.zip(other, f64::max)
    }

    /// Lane-wise `self <= other` (false where either is NaN).
    #[inline(always)]
    pub(crate) fn le(self, other: Self) -> M4 {
        self.compare(other, |a, b| a <= b)
    }

    /// Lane-wise `self < other` (false where either is NaN).
    #[inline(always)]
    pub(crate) fn lt(self, other: Self) -> M4 {
        self.compare(other, |a, b| a < b)
    }

    /// Lane-wise `self > other` (false where either is NaN).
    #[inline(always)]
    pub(crate) fn gt(self, other: Self) -> M4 {
        self.compare(other, |a, b| a > b)
    }
}

impl M4 {
    /// Lanes set where `flags` is true.
    #[inline(always)]
    pub(crate) fn from_flags(flags: [bool; LANES]) -> Self {
        Self(flags.map(flag))
    }

    /// The lanes as flags.
    #[inline(always)]
    pub(crate) fn flags(self) -> [bool; LANES] {
        self.0.map(|m| m != 0)
    }

    /// Whether any lane is set.
    #[inline(always)]
    pub(crate) fn any(self) -> bool {
        ((self.0[0] | self.0[1]) | (self.0[2] | self.0[3])) != 0
    }

    /// Whether every lane is set.
    #[inline(always)]
    pub(crate) fn all(self) -> bool {
        ((self.0[0] & self.0[1]) & (self.0[2] & self.0[3])) == u64::MAX
    }

    /// Lane-wise negation.
    #[inline(always)]
    pub(crate) fn not(self) -> Self {
        Self([!self.0[0], !self.0[1], !self.0[2], !self.0[3]])
    }

    /// Lane-wise and.
    #[inline(always)]
    pub(crate) fn and(self, other: Self) -> Self {
        Self([
            self.0[0] & other.0[0],
            self.0[1] & other.0[1],
            self.0[2] & other.0[2],
            self.0[3] & other.0[3],
        ])
    }

    /// Lane-wise or.
    #[inline(always)]
    pub(crate) fn or(self, other: Self) -> Self {
        Self([
            self.0[0] | other.0[0],
            self.0[1] | other.0[1],
            self.0[2] | other.0[2],
            self.0[3] | other.0[3],
        ])
    }

    /// `if_set` where the lane is set, `otherwise` elsewhere.
    #[inline(always)]
    pub(crate) fn select(self, if_set: F4, otherwise: F4) -> F4 {
        let pick = |l: usize| {
            if self.0[l] != 0 {
                if_set.0[l]
            } else {
                otherwise.0[l]
            }
        };
        F4([pick(0), pick(1), pick(2), pick(3)])
    }
}

macro_rules! lane_operator {
    ($trait:ident, $method:ident, $op:tt) => {
        impl $trait for F4 {
            type Output = F4;
            #[inline(always)]
            fn $method(self, other: F4) -> F4 {
                self.zip(other, |a, b| a $op b)
            }
        }

        impl $trait<f64> for F4 {
            type Output = F4;
            #[inline(always)]
            fn $method(self, other: f64) -> F4 {
                self.map(|a| a $op other)
            }
        }

        impl $trait<F4> for f64 {
            type Output = F4;
            #[inline(always)]
            fn $method(self, other: F4) -> F4 {
                other.map(|b| self $op b)
            }
        }
    };
}

lane_operator!(Add, add, +);
lane_operator!(Sub, sub, -);
lane_operator!(Mul, mul, *);
lane_operator!(Div, div, /);

impl Neg for F4 {
    type Output = F4;
    #[inline(always)]
    fn neg(self) -> F4 {
        self.map(|a| -a)
    }
}

/// A field that evaluates up to [`LANES`] points side by side: `batch` stores `pick` of each
/// point's field, bit for bit [`Potential::field`](crate::Potential::field)'s. The entry points
/// below compile it once without extra target features and once with AVX (four lanes per
/// register; no FMA, so every operation rounds as in the scalar code), and
/// [`fields_into`] / [`potentials_into`] take the second where the CPU has AVX.
pub(crate) trait Batched {
    /// `pick` of the field at each of `points`, into `out` (the shorter of the two).
    fn batch<T>(&self, points: &[Vec3], out: &mut [T], pick: impl Fn(Field) -> T);
}

/// [`Batched::batch`] compiled without extra target features (any x86_64, and the only
/// instantiation elsewhere).
pub(crate) fn fields_plain<B: Batched>(body: &B, points: &[Vec3], out: &mut [Field]) {
    body.batch(points, out, |f| f);
}

/// [`fields_plain`] for potentials only.
fn potentials_plain<B: Batched>(body: &B, points: &[Vec3], out: &mut [Real]) {
    body.batch(points, out, |f| f.potential);
}

/// [`Batched::batch`] compiled with AVX.
///
/// # Safety
///
/// The CPU must support AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
pub(crate) unsafe fn fields_avx<B: Batched>(body: &B, points: &[Vec3], out: &mut [Field]) {
    body.batch(points, out, |f| f);
}

/// [`fields_avx`] for potentials only.
///
/// # Safety
///
/// The CPU must support AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
unsafe fn potentials_avx<B: Batched>(body: &B, points: &[Vec3], out: &mut [Real]) {
    body.batch(points, out, |f| f.potential);
}

/// The fields at `points`, four at a time (AVX where the CPU has it).
pub(crate) fn fields_into<B: Batched>(body: &B, points: &[Vec3], out: &mut [Field]) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx") {
        // SAFETY: AVX was just detected on this CPU (std caches the answer).
        unsafe { fields_avx(body, points, out) };
        return;
    }
    fields_plain(body, points, out);
}

/// The potentials at `points`, four at a time (AVX where the CPU has it).
pub(crate) fn potentials_into<B: Batched>(body: &B, points: &[Vec3], out: &mut [Real]) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx") {
        // SAFETY: as above.
        unsafe { potentials_avx(body, points, out) };
        return;
    }
    potentials_plain(body, points, out);
}

/// A field that computes [`LANES`] points side by side, where any lane may decline (a point
/// the lane code does not serve: inside the body, beyond its far-field limit, not a number):
/// [`batch_lanes`] then evaluates that point alone.
pub(crate) trait LaneField {
    /// The fields at the four points and which lanes took the lane path (the others'
    /// entries are meaningless).
    fn field_lanes(&self, points: [Vec3; LANES]) -> ([Field; LANES], [bool; LANES]);
    /// One point's field, kept out of line so that the lane code beside it stays small
    /// enough for the compiler to vectorise whole.
    fn field_outlined(&self, r: &Vec3) -> Field;
}

/// [`Batched::batch`] for a [`LaneField`]: [`LANES`] points at a time, the declined lanes and
/// the remainder point by point; `pick` keeps what the caller stores.
#[inline(always)]
pub(crate) fn batch_lanes<L: LaneField, T>(
    body: &L,
    points: &[Vec3],
    out: &mut [T],
    pick: impl Fn(Field) -> T,
) {
    let n = points.len().min(out.len());
    let (points, out) = (&points[..n], &mut out[..n]);
    let mut point_chunks = points.chunks_exact(LANES);
    let mut out_chunks = out.chunks_exact_mut(LANES);
    for (chunk, target) in (&mut point_chunks).zip(&mut out_chunks) {
        let (fields, taken) = body.field_lanes([chunk[0], chunk[1], chunk[2], chunk[3]]);
        // Stored unconditionally first: a store per taken lane only would invite the
        // compiler to sink the lane arithmetic into four scalar branches.
        for (slot, field) in target.iter_mut().zip(fields) {
            *slot = pick(field);
        }
        for l in 0..LANES {
            if !taken[l] {
                target[l] = pick(body.field_outlined(&chunk[l]));
            }
        }
    }
    for (r, slot) in point_chunks
        .remainder()
        .iter()
        .zip(out_chunks.into_remainder())
    {
        *slot = pick(body.field_outlined(r));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each operation is the scalar one lane by lane, NaN and signed zeros included.
    #[test]
    fn operations_are_the_scalar_ones_lane_by_lane() {
        let a = F4([1.5, -0.0, f64::NAN, 3.0]);
        let b = F4([0.25, 0.0, 2.0, f64::NAN]);
        let same = |x: F4, y: [f64; LANES]| {
            assert_eq!(x.0.map(f64::to_bits), y.map(f64::to_bits), "{x:?} vs {y:?}")
        };
        same(a + b, std::array::from_fn(|l| a.0[l] + b.0[l]));
        same(a - b, std::array::from_fn(|l| a.0[l] - b.0[l]));
        same(a * b, std::array::from_fn(|l| a.0[l] * b.0[l]));
        same(a / b, std::array::from_fn(|l| a.0[l] / b.0[l]));
        same(2.0 - a, std::array::from_fn(|l| 2.0 - a.0[l]));
        same(a / 3.0, std::array::from_fn(|l| a.0[l] / 3.0));
        same(-a, std::array::from_fn(|l| -a.0[l]));
        same(a.max(b), std::array::from_fn(|l| a.0[l].max(b.0[l])));
        same(a.abs().sqrt(), std::array::from_fn(|l| a.0[l].abs().sqrt()));
        assert_eq!(a.le(b).flags(), [false, true, false, false]);
        assert_eq!(a.lt(b).flags(), [false, false, false, false]);
        assert_eq!(a.gt(b).flags(), [true, false, false, false]);
        let m = M4::from_flags([true, false, true, false]);
        same(m.select(a, b), [1.5, 0.0, f64::NAN, f64::NAN]);
        assert!(m.any() && !m.all() && m.or(m.not()).all() && !m.and(m.not()).any());
    }
}
