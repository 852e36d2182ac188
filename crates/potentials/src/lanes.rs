//! `f64` lanes operated on together: the batched paths of [`crate::ellipsoid`],
//! [`crate::carlson`], [`crate::spheroid`], [`crate::disk`] and [`crate::elliptic`] write each
//! scalar operation once for all lanes, so the compiler emits one vector instruction per
//! operation and lane register (four lanes: one with AVX, two with SSE2).
//!
//! Every operation rounds lane by lane exactly as the scalar operation does: IEEE addition,
//! multiplication, division and square root, `f64::max` and `f64::abs`; nothing is fused (no
//! FMA is enabled anywhere), so a lane's result is bit for bit the scalar code's when the same
//! operations are applied in the same order.
//!
//! Two widths. Four lanes ([`F4`], written out lane by lane) fill an AVX register: the disk,
//! the spheroid and the elliptic integrals. The ellipsoid's field runs eight ([`F8`], loops
//! over a width parameter, two registers per operation): its Newton iteration and Carlson
//! duplication are chains of divisions and square roots that each wait for the previous one,
//! and a second, independent register of four points fills the latency (measured on the pose
//! set's ellipsoid pairs: 20 % less time per interaction). With eight lanes a disk pair near
//! contact took 25 % longer and a spheroid pair 4 %; the four lanes written as loops cost the
//! paper's (spheroid) pair 2–5 %, and the eight written four at a time cost the ellipsoid
//! 11 %. Code for either width is generic over [`Lane`].

use crate::{Field, Real, Vec3};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Number of lanes of [`F4`] and [`M4`].
pub(crate) const LANES: usize = 4;

/// Number of lanes of [`F8`] and [`M8`].
pub(crate) const WIDE: usize = 8;

/// Four `f64` lanes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct F4(pub(crate) [f64; LANES]);

/// Four flags, each an all-ones or all-zeros bit pattern (the form a vector comparison
/// produces, so that selections compile to bitwise operations rather than branches).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct M4(pub(crate) [u64; LANES]);

/// `N` `f64` lanes, operated on by loops over the lanes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Lanes<const N: usize>(pub(crate) [f64; N]);

/// `N` flags, as for [`M4`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Mask<const N: usize>(pub(crate) [u64; N]);

/// Eight lanes.
pub(crate) type F8 = Lanes<WIDE>;
/// Eight flags.
pub(crate) type M8 = Mask<WIDE>;

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

    /// The lanes `v`.
    #[inline(always)]
    pub(crate) const fn new(v: [f64; LANES]) -> Self {
        Self(v)
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

impl<const N: usize> Lanes<N> {
    /// The same value in every lane.
    #[inline(always)]
    pub(crate) fn splat(v: f64) -> Self {
        Self([v; N])
    }

    /// The lanes `v`.
    #[inline(always)]
    pub(crate) const fn new(v: [f64; N]) -> Self {
        Self(v)
    }

    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        let mut out = self.0;
        for v in &mut out {
            *v = f(*v);
        }
        Self(out)
    }

    #[inline(always)]
    fn zip(self, other: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        let mut out = self.0;
        for (v, &w) in out.iter_mut().zip(&other.0) {
            *v = f(*v, w);
        }
        Self(out)
    }

    #[inline(always)]
    fn compare(self, other: Self, f: impl Fn(f64, f64) -> bool) -> Mask<N> {
        let mut out = [0; N];
        for (l, v) in out.iter_mut().enumerate() {
            *v = flag(f(self.0[l], other.0[l]));
        }
        Mask(out)
    }

    /// Lane-wise `f64::max` (a NaN loses to a number, as there).
    #[inline(always)]
    pub(crate) fn max(self, other: Self) -> Self {
        self.zip(other, f64::max)
    }
}

impl<const N: usize> Mask<N> {
    /// Lanes set where `flags` is true.
    #[inline(always)]
    pub(crate) fn from_flags(flags: [bool; N]) -> Self {
        Self(flags.map(flag))
    }

    /// The lanes as flags.
    #[inline(always)]
    pub(crate) fn flags(self) -> [bool; N] {
        self.0.map(|m| m != 0)
    }

    /// Whether any lane is set.
    #[inline(always)]
    pub(crate) fn any(self) -> bool {
        let mut v = self.0;
        let mut width = N;
        while width > 1 {
            width /= 2;
            for i in 0..width {
                v[i] |= v[i + width];
            }
        }
        v[0] != 0
    }

    /// Whether every lane is set.
    #[inline(always)]
    pub(crate) fn all(self) -> bool {
        let mut v = self.0;
        let mut width = N;
        while width > 1 {
            width /= 2;
            for i in 0..width {
                v[i] &= v[i + width];
            }
        }
        v[0] == u64::MAX
    }

    /// Lane-wise negation.
    #[inline(always)]
    pub(crate) fn not(self) -> Self {
        Self(self.0.map(|m| !m))
    }

    /// Lane-wise and.
    #[inline(always)]
    pub(crate) fn and(self, other: Self) -> Self {
        let mut out = self.0;
        for (v, &w) in out.iter_mut().zip(&other.0) {
            *v &= w;
        }
        Self(out)
    }

    /// Lane-wise or.
    #[inline(always)]
    pub(crate) fn or(self, other: Self) -> Self {
        let mut out = self.0;
        for (v, &w) in out.iter_mut().zip(&other.0) {
            *v |= w;
        }
        Self(out)
    }

    /// `if_set` where the lane is set, `otherwise` elsewhere.
    #[inline(always)]
    pub(crate) fn select(self, if_set: Lanes<N>, otherwise: Lanes<N>) -> Lanes<N> {
        let mut out = otherwise.0;
        for (l, v) in out.iter_mut().enumerate() {
            *v = if self.0[l] != 0 {
                if_set.0[l]
            } else {
                otherwise.0[l]
            };
        }
        Lanes(out)
    }
}

macro_rules! lane_operator {
    ([$($generics:tt)*] $lanes:ty, $trait:ident, $method:ident, $op:tt) => {
        impl<$($generics)*> $trait for $lanes {
            type Output = $lanes;
            #[inline(always)]
            fn $method(self, other: $lanes) -> $lanes {
                self.zip(other, |a, b| a $op b)
            }
        }

        impl<$($generics)*> $trait<f64> for $lanes {
            type Output = $lanes;
            #[inline(always)]
            fn $method(self, other: f64) -> $lanes {
                self.map(|a| a $op other)
            }
        }

        impl<$($generics)*> $trait<$lanes> for f64 {
            type Output = $lanes;
            #[inline(always)]
            fn $method(self, other: $lanes) -> $lanes {
                other.map(|b| self $op b)
            }
        }
    };
}

/// The operations of a lane type defined from its `map`, `zip` and `compare` (whose forms
/// differ between the widths): arithmetic, negation, square root, absolute value, comparisons
/// into `$mask`, and [`Lane`].
macro_rules! lane_type {
    ([$($generics:tt)*] $lanes:ty, $mask:ty) => {
        impl<$($generics)*> $lanes {
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

            /// Lane-wise `self <= other` (false where either is NaN).
            #[inline(always)]
            pub(crate) fn le(self, other: Self) -> $mask {
                self.compare(other, |a, b| a <= b)
            }

            /// Lane-wise `self < other` (false where either is NaN).
            #[inline(always)]
            pub(crate) fn lt(self, other: Self) -> $mask {
                self.compare(other, |a, b| a < b)
            }

            /// Lane-wise `self > other` (false where either is NaN).
            #[inline(always)]
            pub(crate) fn gt(self, other: Self) -> $mask {
                self.compare(other, |a, b| a > b)
            }
        }

        lane_operator!([$($generics)*] $lanes, Add, add, +);
        lane_operator!([$($generics)*] $lanes, Sub, sub, -);
        lane_operator!([$($generics)*] $lanes, Mul, mul, *);
        lane_operator!([$($generics)*] $lanes, Div, div, /);

        impl<$($generics)*> Neg for $lanes {
            type Output = $lanes;
            #[inline(always)]
            fn neg(self) -> $lanes {
                self.map(|a| -a)
            }
        }

        impl<$($generics)*> Lane for $lanes {
            #[inline(always)]
            fn splat(v: f64) -> Self {
                <$lanes>::splat(v)
            }
        }
    };
}

/// What code written for either lane width ([`F4`], [`F8`]) uses: IEEE arithmetic lane by
/// lane, with `f64` on the right (a constant on the left is written [`Lane::splat`]).
pub(crate) trait Lane:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
    + Neg<Output = Self>
{
    /// The same value in every lane.
    fn splat(v: f64) -> Self;
}

lane_type!([] F4, M4);
lane_type!([const N: usize] Lanes<N>, Mask<N>);

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

/// A field that computes `N` points side by side, where any lane may decline (a point the
/// lane code does not serve: inside the body, beyond its far-field limit, not a number):
/// [`batch_lanes`] then evaluates that point alone.
pub(crate) trait LaneField<const N: usize> {
    /// The fields at the `N` points and which lanes took the lane path (the others' entries
    /// are meaningless).
    fn field_lanes(&self, points: [Vec3; N]) -> ([Field; N], [bool; N]);
    /// One point's field, kept out of line so that the lane code beside it stays small
    /// enough for the compiler to vectorise whole.
    fn field_outlined(&self, r: &Vec3) -> Field;
}

/// [`Batched::batch`] for a [`LaneField`]: `N` points at a time, the declined lanes and the
/// remainder point by point; `pick` keeps what the caller stores.
#[inline(always)]
pub(crate) fn batch_lanes<const N: usize, L: LaneField<N>, T>(
    body: &L,
    points: &[Vec3],
    out: &mut [T],
    pick: impl Fn(Field) -> T,
) {
    let n = points.len().min(out.len());
    let (points, out) = (&points[..n], &mut out[..n]);
    let mut point_chunks = points.chunks_exact(N);
    let mut out_chunks = out.chunks_exact_mut(N);
    for (chunk, target) in (&mut point_chunks).zip(&mut out_chunks) {
        let (fields, taken) = body.field_lanes(std::array::from_fn(|l| chunk[l]));
        // Stored unconditionally first: a store per taken lane only would invite the
        // compiler to sink the lane arithmetic into scalar branches.
        for (slot, field) in target.iter_mut().zip(fields) {
            *slot = pick(field);
        }
        for l in 0..N {
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
        let a = F4::new([1.5, -0.0, f64::NAN, 3.0]);
        let b = F4::new([0.25, 0.0, 2.0, f64::NAN]);
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
        same(a.abs().sqrt(), std::array::from_fn(|l| a.0[l].abs().sqrt()));
        assert_eq!(a.le(b).flags(), [false, true, false, false]);
        assert_eq!(a.lt(b).flags(), [false, false, false, false]);
        assert_eq!(a.gt(b).flags(), [true, false, false, false]);
        let m = M4::from_flags([true, false, true, false]);
        same(m.select(a, b), [1.5, 0.0, f64::NAN, f64::NAN]);
        assert!(m.any() && !m.all() && !m.and(m.not()).any() && !m.not().all());
    }

    /// At eight lanes too (the ellipsoid's width): every lane's operation is its own, and
    /// `any` and `all` see each lane (a single set or cleared lane, in every position).
    #[test]
    fn eight_lanes_are_lane_by_lane() {
        let a = F8::new([1.5, -0.0, f64::NAN, 3.0, 7.0, -2.0, 1e300, 0.5]);
        let b = F8::new([0.25, 0.0, 2.0, f64::NAN, -7.0, 4.0, 1e300, 0.5]);
        let bits = |x: F8| x.0.map(f64::to_bits);
        let each = |f: fn(f64, f64) -> f64| std::array::from_fn(|l| f(a.0[l], b.0[l]).to_bits());
        assert_eq!(bits(a + b), each(|x, y| x + y));
        assert_eq!(bits(a * b), each(|x, y| x * y));
        assert_eq!(bits(a / b), each(|x, y| x / y));
        assert_eq!(bits(a.max(b).sqrt()), each(|x, y| x.max(y).sqrt()));
        let le = a.le(b);
        assert_eq!(le.flags(), std::array::from_fn(|l| a.0[l] <= b.0[l]));
        assert_eq!(
            bits(le.select(a, b)),
            each(|x, y| if x <= y { x } else { y })
        );
        for l in 0..WIDE {
            let one = M8::from_flags(std::array::from_fn(|k| k == l));
            assert!(one.any() && !one.all(), "lane {l} alone");
            let all_but_one = one.not();
            assert!(all_but_one.any() && !all_but_one.all(), "all but lane {l}");
        }
        assert!(M8::from_flags([true; WIDE]).all() && !M8::from_flags([false; WIDE]).any());
    }
}
