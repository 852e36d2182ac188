//! A row of a singular circle split at both of its singularities into four pieces, each
//! clustered toward its own singular end ([`SplitRow`]), with the nodes' sines and cosines
//! from a short series instead of the library's calls.

use super::{ClusteredSide, RowSingularity};
use surfgrav_surfaces::Real;

/// A row of a singular circle split at both its singularities ([`CircleRows`](super::CircleRows)): the row's
/// angles from its narrower singularity (azimuth 0, width $\eta_n$) in the direction of the
/// other (offset $d \in (0, \pi]$, width $\eta_o$), the circle cut into the arcs $[0, d]$ and
/// $[d, 2\pi]$, each split where the two singularities' sinh maps meet (in proportion to
/// their widths) into two pieces clustered toward their singular ends. Gauss–Legendre on a
/// half-range clustered toward the narrower singularity alone meets the other one off its
/// clustering point, where it is sparse: two disks whose rims pass near each other at two
/// places (random-pose set seed 39, disk-disk gap 0.2 #3: widths 0.046 and 0.17 two radians
/// apart on the rim row) took 137 nodes per half-range unclustered, where each piece takes a
/// sinh map of its own singularity's width.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SplitRow {
    /// $(\cos d, \sin d)$.
    pub(super) at_offset: (Real, Real),
    /// +1 where the other singularity lies at $+d$, −1 at $-d$ (the pieces' sines negated).
    pub(super) sign: Real,
    /// $[0, m_a]$ from 0, $[m_a, d]$ from $d$ backward, $[d, d + m_b]$ from $d$, and
    /// $[d + m_b, 2\pi]$ from $2\pi$ backward.
    pub(super) pieces: [ClusteredSide; 4],
}

/// Nodes of a piece of a [`SplitRow`] at the plan's first level, at least: with every
/// piece at least this, a step of `start / SPLIT_MIN_PIECE` levels adds a node to each.
pub(super) const SPLIT_MIN_PIECE: Real = 8.0;

/// A row is split ([`SplitRow`]) where its pieces' plans take at most this fraction of the
/// nodes of its two half-ranges' plan: each node of a split row costs a sine, a cosine and a
/// sinh of its own (the half-ranges' lists are shared by the rows of a table entry and
/// turned), about 60 % more than a node of a shared list with the field evaluated. Measured
/// (random-pose sets of seeds 32 and 39, before the pinch plans; evaluations and worst times,
/// best of three): 0.7: 92,189 and 96,859, 268 and 672 µs; 0.5: 91,969 and 97,559, 266 and
/// 654 µs; 0.35: 92,421 and 97,763, 278 and 672 µs.
pub(super) const SPLIT_GAIN: Real = 0.5;

impl SplitRow {
    /// The split of the row with singularities `near` (the narrower) and `other`.
    pub(super) fn new(
        near: &RowSingularity,
        other: &RowSingularity,
        log_tolerance: Real,
        margin: Real,
    ) -> Self {
        // The phasors' cosine and sine of the angle between them.
        let (cos, sin) = (
            near.cos * other.cos + near.sin * other.sin,
            near.cos * other.sin - near.sin * other.cos,
        );
        let d = sin.atan2(cos).abs().max(Real::MIN_POSITIVE);
        let rest = std::f64::consts::TAU - d;
        let share = near.width / (near.width + other.width);
        let (m_a, m_b) = (d * share, rest * (1.0 - share));
        let piece = |length: Real, width: Real, far: Real| {
            let side =
                ClusteredSide::toward_end(length, width, far, log_tolerance).with_margin(margin);
            ClusteredSide {
                predicted: side.predicted.max(SPLIT_MIN_PIECE),
                ..side
            }
        };
        Self {
            at_offset: (cos, sin.abs()),
            sign: if sin < 0.0 { -1.0 } else { 1.0 },
            pieces: [
                piece(m_a, near.width, d - m_a),
                piece(d - m_a, other.width, m_a),
                piece(m_b, other.width, rest - m_b),
                piece(rest - m_b, near.width, m_b),
            ],
        }
    }

    /// Each piece's start angle, as its phasor $(\cos, \sin)$, and direction.
    pub(super) fn origins(&self) -> [((Real, Real), Real); 4] {
        let at_d = self.at_offset;
        [
            ((1.0, 0.0), 1.0),
            (at_d, -1.0),
            (at_d, 1.0),
            ((1.0, 0.0), -1.0),
        ]
    }
}

/// $(\sin t, \cos t)$ for $|t| \le 2\pi$ (the offsets along a split row's pieces,
/// [`SplitRow`]): the Taylor series of $t/8$ to degrees 17 and 18 (terms beyond below
/// $5\cdot10^{-17}$), doubled three times: branch-free and inlined, in a loop of its own over
/// a piece's nodes. The library's `sin_cos` (a call, with a general range reduction) took 17 %
/// of a split disk pair's time (random-pose set seed 22, disk-disk gap 0.05 #1: 265 µs, 239
/// µs with this). Within $2\cdot10^{-15}$ of the library's (test
/// `piece_sine_and_cosine_match_the_library`).
#[inline]
pub(super) fn sin_cos_of_piece(t: Real) -> (Real, Real) {
    pub(super) const SIN: [Real; 9] = [
        1.0,
        -0.16666666666666666,
        0.008333333333333333,
        -0.0001984126984126984,
        2.7557319223985893e-06,
        -2.505210838544172e-08,
        1.6059043836821613e-10,
        -7.647163731819816e-13,
        2.8114572543455206e-15,
    ];
    pub(super) const COS: [Real; 10] = [
        1.0,
        -0.5,
        0.041666666666666664,
        -0.001388888888888889,
        2.48015873015873e-05,
        -2.755731922398589e-07,
        2.08767569878681e-09,
        -1.1470745597729725e-11,
        4.779477332387385e-14,
        -1.5619206968586225e-16,
    ];
    let x = 0.125 * t;
    let x2 = x * x;
    let mut sin = SIN[8];
    for &c in SIN[..8].iter().rev() {
        sin = sin * x2 + c;
    }
    let mut cos = COS[9];
    for &c in COS[..9].iter().rev() {
        cos = cos * x2 + c;
    }
    let mut sin = sin * x;
    for _ in 0..3 {
        (sin, cos) = (2.0 * sin * cos, (cos - sin) * (cos + sin));
    }
    (sin, cos)
}
