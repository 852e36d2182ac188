//! The 7-point Gauss rule and its 15-point Kronrod extension on $[-1, 1]$ (the G7–K15 pair).
//!
//! The Kronrod rule reuses the 7 Gauss–Legendre nodes and adds the 8 roots of the Stieltjes
//! polynomial $E_8$ (the monic even polynomial orthogonal to $x^0, \dots, x^7$ under the weight
//! $P_7(x)$ on $[-1, 1]$); its 15 weights make it exact for polynomials of degree $\le 23$,
//! while the embedded Gauss rule is exact to degree 13. Their difference estimates the error
//! of the Gauss rule at the cost of no extra evaluation; the adaptive integrator
//! ([`crate::adaptive`]) builds its product rule from this pair.
//!
//! Provenance: the values below are the 25-digit values of `tests/reference/gauss_legendre.json`
//! (written by `tests/reference/gauss_legendre.py` with mpmath at 50 digits) rounded to the
//! nearest double; `tests/gauss_kronrod.rs` checks each one against the file and the stated
//! degrees of exactness.

/// The 15 Kronrod nodes on $[-1, 1]$, increasing. The Gauss nodes are those of odd index
/// ($1, 3, \dots, 13$), the middle one being $0$.
pub const KRONROD_15_NODES: [f64; 15] = [
    -0.9914553711208126,
    -0.9491079123427585,
    -0.8648644233597691,
    -0.7415311855993945,
    -0.5860872354676911,
    -0.4058451513773972,
    -0.20778495500789848,
    0.0,
    0.20778495500789848,
    0.4058451513773972,
    0.5860872354676911,
    0.7415311855993945,
    0.8648644233597691,
    0.9491079123427585,
    0.9914553711208126,
];

/// The 15 Kronrod weights, one per entry of [`KRONROD_15_NODES`] (summing to 2).
pub const KRONROD_15_WEIGHTS: [f64; 15] = [
    0.022935322010529224,
    0.06309209262997856,
    0.10479001032225019,
    0.14065325971552592,
    0.1690047266392679,
    0.19035057806478542,
    0.20443294007529889,
    0.20948214108472782,
    0.20443294007529889,
    0.19035057806478542,
    0.1690047266392679,
    0.14065325971552592,
    0.10479001032225019,
    0.06309209262997856,
    0.022935322010529224,
];

/// The 7 Gauss–Legendre weights, for the nodes `KRONROD_15_NODES[2 j + 1]`, `j = 0..7`
/// (summing to 2).
pub const GAUSS_7_WEIGHTS: [f64; 7] = [
    0.1294849661688697,
    0.27970539148927664,
    0.3818300505051189,
    0.4179591836734694,
    0.3818300505051189,
    0.27970539148927664,
    0.1294849661688697,
];
