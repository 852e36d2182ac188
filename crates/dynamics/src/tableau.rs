//! Butcher tableaux of the embedded Runge–Kutta pairs behind [`crate::Adaptive`].
//!
//! A pair advances $\mathbf y_1 = \mathbf y_0 + h\sum_i b_i \mathbf k_i$ with stages
//! $\mathbf k_i = \mathbf f(t_0 + c_i h,\ \mathbf y_0 + h\sum\_{j<i} a\_{ij}\mathbf k_j)$. Both pairs
//! here are FSAL ("first same as last"): their last stage row equals $b$, so that stage is
//! $\mathbf f(t_1, \mathbf y_1)$ and becomes the first stage of the next step.
//!
//! - Dormand–Prince 5(4) (Dormand & Prince 1980): 7 stages, 6 force evaluations per step; the
//!   error estimate is $h\sum_i (b_i - \hat b_i)\mathbf k_i$ with the 4th-order weights $\hat b$.
//! - DOP853 (Hairer, Nørsett & Wanner, *Solving ODEs I*, 2nd ed., §II.10; the 8th-order method
//!   of Dormand & Prince 1981 with Hairer's error estimators and continuous extension): 12 stages
//!   plus the FSAL stage, 12 force evaluations per step. Two embedded estimates, of 5th order
//!   $\mathbf e_5 = h\sum_i E_i\mathbf k_i$ and of 3rd order
//!   $\mathbf e_3 = h\sum_i (b_i - \breve b_i)\mathbf k_i$, are combined as
//!   $$\mathrm{err} = \frac{\\|\mathbf e_5\\|^2}{\sqrt{\\|\mathbf e_5\\|^2 + 0.01\\,\\|\mathbf e_3\\|^2}}$$
//!   (norms scaled by the tolerances, root mean square over the components), which behaves like
//!   $O(h^8)$ and is what the step control ($\mathrm{err}^{-1/8}$) is built for.
//! - DOP853's dense output of order 7 needs three more stages ($c = 0.1, 0.2, 7/9$) per step where
//!   output is wanted; with $s = (t - t_0)/h$, $s' = 1 - s$,
//!   $$\mathbf y(t_0 + sh) = \mathbf y_0 + s\big(\Delta + s'(\beta + s(\Delta - h\mathbf k\_{13} - \beta + s'(\mathbf d_4 + s(\mathbf d_5 + s'(\mathbf d_6 + s\\,\mathbf d_7))))))\big),$$
//!   $\Delta = \mathbf y_1 - \mathbf y_0$, $\beta = h\mathbf k_1 - \Delta$,
//!   $\mathbf d_r = h\sum_i D\_{ri}\mathbf k_i$ over all 16 stages.
//!
//! The coefficients are the published decimal values, rounded to the nearest `f64`, with one
//! deliberate exception per pair: $b_1$ (whose stage has $c_1 = 0$, so it enters no order
//! condition but $\sum_i b_i = 1$) is moved by a few ulp so that, in exact arithmetic on the
//! stored values, $B_2 = (B_1)^2/2$ with $B_1 = \sum_i b_i$, $B_2 = \sum_i b_i \sum_j a\_{ij}$.
//! Rounding the coefficients otherwise leaves $B_2 - B_1^2/2 \approx 4\times10^{-16}$, an error
//! $h^2 (B_2 - B_1^2/2)\\,\mathbf f'\mathbf f$ of the same sign at every step, which made the energy
//! error of long fixed-step runs grow linearly (measured: $1.5\times10^{-13}$ after 500 circular
//! orbits of 200 steps) instead of as $\sqrt t$ (Brouwer's law; after the change
//! $5\times10^{-15}$). $B_1 - 1 \approx 4\times10^{-16}$ is then only a rescaling of time, which
//! conserves energy. DOP853: $b_1$ = 0.054293734116568765 + 56 ulp; DP5(4): $b_1$ = 35/384 −
//! 25 ulp (values found with exact rational arithmetic on the stored `f64`s).
//!
//! The unit
//! tests check every order condition (all 200 rooted trees up to order 8 for DOP853's weights,
//! 17 trees up to order 5 for its 5th-order estimator, the 4 of order ≤ 3 for the 3rd-order one,
//! and the 85 trees up to order 7 for the dense output at several $s$), so a mistyped digit fails
//! a test.

use surfgrav_potentials::Real;

/// Most stages of any pair, including dense-output stages.
pub(crate) const MAX_STAGES: usize = 16;

/// How a pair estimates its local error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum ErrorWeights {
    /// $h\sum_i (b_i - \hat b_i)\mathbf k_i$, with $\hat b$ the embedded lower-order weights.
    Lower(&'static [Real]),
    /// Hairer's combined 5th/3rd-order estimate (DOP853): `fifth` holds $E_i$, `third` holds
    /// $\breve b_i$.
    Combined {
        fifth: &'static [Real],
        third: &'static [Real],
    },
}

/// An explicit embedded FSAL pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Tableau {
    /// Nodes $c_i$ of the step stages (the FSAL stage included).
    #[cfg_attr(not(test), allow(dead_code))]
    pub c: &'static [Real],
    /// Rows $i = 1, 2, \dots$ of $a\_{ij}$, $j < i$; the last row is $b$ (FSAL).
    pub a: &'static [&'static [Real]],
    /// The error estimator.
    pub error: ErrorWeights,
    /// The order $q$ the error estimate behaves like, $\mathrm{err} = O(h^{q+1})$: the step
    /// factor is $0.9\\,\mathrm{err}^{-1/(q+1)}$.
    pub error_order: u32,
    /// Smallest and largest step factor after an accepted step.
    pub factor_range: (Real, Real),
}

impl Tableau {
    /// Number of stages of a step, the FSAL stage included.
    pub fn stages(&self) -> usize {
        self.a.len() + 1
    }

    /// The propagated weights $b$ (the last row).
    pub fn b(&self) -> &'static [Real] {
        self.a[self.a.len() - 1]
    }

    /// The scaled error norm of a step over `components` state components, given
    /// `squares(w)` $= \sum_n (h\sum_i w_i k\_{i,n} / \mathrm{sc}\_n)^2$ for stage weights $w_i$
    /// (how the state is scaled is the caller's): the RMS of the lower-order difference, or
    /// Hairer's combined estimate $e_5/\sqrt{n(e_5 + 0.01 e_3)}$ (0 when both vanish; NaN or
    /// infinity propagate to the caller's finiteness check).
    pub fn error_norm(
        &self,
        components: usize,
        squares: impl Fn(&dyn Fn(usize) -> Real) -> Real,
    ) -> Real {
        let b = self.b();
        let weight = |w: &[Real], i: usize| w.get(i).copied().unwrap_or(0.0);
        let n = components as Real;
        match self.error {
            ErrorWeights::Lower(lower) => {
                (squares(&|i| weight(b, i) - weight(lower, i)) / n).sqrt()
            }
            ErrorWeights::Combined { fifth, third } => {
                let e5 = squares(&|i| weight(fifth, i));
                let e3 = squares(&|i| weight(b, i) - weight(third, i));
                let denominator = e5 + 0.01 * e3;
                if denominator == 0.0 {
                    0.0
                } else {
                    e5 / (n * denominator).sqrt()
                }
            }
        }
    }
}

/// Dormand–Prince 5(4).
pub(crate) const DORMAND_PRINCE_54: Tableau = Tableau {
    c: &[0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0],
    a: &[
        &[1.0 / 5.0],
        &[3.0 / 40.0, 9.0 / 40.0],
        &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
        &[
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
        ],
        &[
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
        ],
        &[
            // 35/384 − 25 ulp (module documentation).
            0.09114583333333298,
            0.0,
            500.0 / 1113.0,
            125.0 / 192.0,
            -2187.0 / 6784.0,
            11.0 / 84.0,
        ],
    ],
    error: ErrorWeights::Lower(&[
        5179.0 / 57600.0,
        0.0,
        7571.0 / 16695.0,
        393.0 / 640.0,
        -92097.0 / 339200.0,
        187.0 / 2100.0,
        1.0 / 40.0,
    ]),
    error_order: 4,
    factor_range: (0.2, 5.0),
};

/// DOP853: the step stages (rows 1–11), the FSAL row $b$ (row 12) and, in [`DOP853_DENSE_A`],
/// the three dense-output stages.
pub(crate) const DOP853: Tableau = Tableau {
    c: &DOP853_C_STEP,
    a: &DOP853_A_STEP,
    error: ErrorWeights::Combined {
        fifth: &DOP853_ER,
        third: &DOP853_BHH,
    },
    error_order: 7,
    factor_range: (1.0 / 3.0, 6.0),
};
/// DOP853 nodes of the step stages (13, the FSAL stage last).
const DOP853_C_STEP: [Real; 13] = [
    0.0,
    0.05260015195876773,
    0.0789002279381516,
    0.1183503419072274,
    0.2816496580927726,
    0.3333333333333333,
    0.25,
    0.3076923076923077,
    0.6512820512820513,
    0.6,
    0.8571428571428571,
    1.0,
    1.0,
];
/// DOP853 nodes of the dense-output stages 14–16.
#[cfg(test)]
const DOP853_DENSE_C: [Real; 3] = [0.1, 0.2, 0.7777777777777778];
/// DOP853 $a\_{ij}$ of stages 2–12 and the weights $b$ (row of the FSAL stage 13).
const DOP853_A_STEP: [&[Real]; 12] = [
    &[0.05260015195876773],
    &[0.0197250569845379, 0.0591751709536137],
    &[0.02958758547680685, 0.0, 0.08876275643042054],
    &[
        0.2413651341592667,
        0.0,
        -0.8845494793282861,
        0.924834003261792,
    ],
    &[
        0.037037037037037035,
        0.0,
        0.0,
        0.17082860872947386,
        0.12546768756682242,
    ],
    &[
        0.037109375,
        0.0,
        0.0,
        0.17025221101954405,
        0.06021653898045596,
        -0.017578125,
    ],
    &[
        0.03709200011850479,
        0.0,
        0.0,
        0.17038392571223998,
        0.10726203044637328,
        -0.015319437748624402,
        0.008273789163814023,
    ],
    &[
        0.6241109587160757,
        0.0,
        0.0,
        -3.3608926294469414,
        -0.868219346841726,
        27.59209969944671,
        20.154067550477894,
        -43.48988418106996,
    ],
    &[
        0.47766253643826434,
        0.0,
        0.0,
        -2.4881146199716677,
        -0.590290826836843,
        21.230051448181193,
        15.279233632882423,
        -33.28821096898486,
        -0.020331201708508627,
    ],
    &[
        -0.9371424300859873,
        0.0,
        0.0,
        5.186372428844064,
        1.0914373489967295,
        -8.149787010746927,
        -18.52006565999696,
        22.739487099350505,
        2.4936055526796523,
        -3.0467644718982196,
    ],
    &[
        2.273310147516538,
        0.0,
        0.0,
        -10.53449546673725,
        -2.0008720582248625,
        -17.9589318631188,
        27.94888452941996,
        -2.8589982771350235,
        -8.87285693353063,
        12.360567175794303,
        0.6433927460157636,
    ],
    &[
        // b₁ + 56 ulp (module documentation).
        0.05429373411656915,
        0.0,
        0.0,
        0.0,
        0.0,
        4.450312892752409,
        1.8915178993145003,
        -5.801203960010585,
        0.3111643669578199,
        -0.1521609496625161,
        0.20136540080403034,
        0.04471061572777259,
    ],
];
/// DOP853 $a\_{ij}$ of the dense-output stages 14–16.
pub(crate) const DOP853_DENSE_A: [&[Real]; 3] = [
    &[
        0.056167502283047954,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.25350021021662483,
        -0.2462390374708025,
        -0.12419142326381637,
        0.15329179827876568,
        0.00820105229563469,
        0.007567897660545699,
        -0.008298,
    ],
    &[
        0.03183464816350214,
        0.0,
        0.0,
        0.0,
        0.0,
        0.028300909672366776,
        0.053541988307438566,
        -0.05492374857139099,
        0.0,
        0.0,
        -0.00010834732869724932,
        0.0003825710908356584,
        -0.00034046500868740456,
        0.1413124436746325,
    ],
    &[
        -0.42889630158379194,
        0.0,
        0.0,
        0.0,
        0.0,
        -4.697621415361164,
        7.683421196062599,
        4.06898981839711,
        0.3567271874552811,
        0.0,
        0.0,
        0.0,
        -0.0013990241651590145,
        2.9475147891527724,
        -9.15095847217987,
    ],
];
/// DOP853 5th-order error weights $E_i$.
const DOP853_ER: [Real; 12] = [
    0.01312004499419488,
    0.0,
    0.0,
    0.0,
    0.0,
    -1.2251564463762044,
    -0.4957589496572502,
    1.6643771824549864,
    -0.35032884874997366,
    0.3341791187130175,
    0.08192320648511571,
    -0.022355307863886294,
];
/// DOP853 3rd-order embedded weights $\breve b_i$.
const DOP853_BHH: [Real; 12] = [
    0.2440944881889764,
    0.0,
    0.0,
    0.0,
    0.0,
    0.0,
    0.0,
    0.0,
    0.7338466882816118,
    0.0,
    0.0,
    0.022058823529411766,
];
/// DOP853 dense-output coefficients $D\_{ri}$, $r = 4, \dots, 7$, over all 16 stages.
pub(crate) const DOP853_D: [[Real; 16]; 4] = [
    [
        -8.428938276109013,
        0.0,
        0.0,
        0.0,
        0.0,
        0.5667149535193777,
        -3.0689499459498917,
        2.38466765651207,
        2.117034582445028,
        -0.871391583777973,
        2.2404374302607883,
        0.6315787787694688,
        -0.08899033645133331,
        18.148505520854727,
        -9.194632392478356,
        -4.436036387594894,
    ],
    [
        10.427508642579134,
        0.0,
        0.0,
        0.0,
        0.0,
        242.28349177525817,
        165.20045171727028,
        -374.5467547226902,
        -22.113666853125306,
        7.733432668472264,
        -30.674084731089398,
        -9.332130526430229,
        15.697238121770845,
        -31.139403219565178,
        -9.35292435884448,
        35.81684148639408,
    ],
    [
        19.985053242002433,
        0.0,
        0.0,
        0.0,
        0.0,
        -387.0373087493518,
        -189.17813819516758,
        527.8081592054236,
        -11.57390253995963,
        6.8812326946963,
        -1.0006050966910838,
        0.7777137798053443,
        -2.778205752353508,
        -60.19669523126412,
        84.32040550667716,
        11.99229113618279,
    ],
    [
        -25.69393346270375,
        0.0,
        0.0,
        0.0,
        0.0,
        -154.18974869023643,
        -231.5293791760455,
        357.6391179106141,
        93.40532418362432,
        -37.45832313645163,
        104.0996495089623,
        29.8402934266605,
        -43.53345659001114,
        96.32455395918828,
        -39.17726167561544,
        -149.72683625798564,
    ],
];

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;

    /// A rooted tree, as the sorted list of the subtrees hanging from its root.
    #[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
    struct Tree(Vec<Tree>);

    impl Tree {
        fn order(&self) -> usize {
            1 + self.0.iter().map(Tree::order).sum::<usize>()
        }
        /// The density γ(t) = ρ(t) Π γ(subtrees).
        fn density(&self) -> Real {
            self.0
                .iter()
                .map(Tree::density)
                .fold(self.order() as Real, |p, g| p * g)
        }
    }

    /// All rooted trees of orders 1..=`max`, by order.
    fn trees(max: usize) -> Vec<Vec<Tree>> {
        let mut by_order: Vec<Vec<Tree>> = vec![Vec::new(), vec![Tree(Vec::new())]];
        for n in 2..=max {
            let mut set = BTreeSet::new();
            // Subtree lists whose orders sum to n − 1, in every order; sorting dedups them.
            fn extend(
                remaining: usize,
                chosen: &mut Vec<Tree>,
                by_order: &[Vec<Tree>],
                set: &mut BTreeSet<Tree>,
            ) {
                if remaining == 0 {
                    let mut children = chosen.clone();
                    children.sort();
                    set.insert(Tree(children));
                    return;
                }
                for m in 1..=remaining {
                    for t in &by_order[m] {
                        // Canonical order (non-increasing) keeps the enumeration small.
                        if chosen.last().is_some_and(|last| t > last) {
                            continue;
                        }
                        chosen.push(t.clone());
                        extend(remaining - m, chosen, by_order, set);
                        chosen.pop();
                    }
                }
            }
            extend(n - 1, &mut Vec::new(), &by_order, &mut set);
            by_order.push(set.into_iter().collect());
        }
        by_order
    }

    /// Φ_i(t) over the stages of the lower-triangular `a` (row i holds a_ij, j < i; row 0 empty).
    fn elementary_weights(tree: &Tree, a: &[Vec<Real>]) -> Vec<Real> {
        let children: Vec<Vec<Real>> = tree.0.iter().map(|t| elementary_weights(t, a)).collect();
        a.iter()
            .map(|row| {
                children
                    .iter()
                    .map(|phi| row.iter().zip(phi).map(|(a, p)| a * p).sum::<Real>())
                    .product()
            })
            .collect()
    }

    /// Largest violation of Σ w_i Φ_i(t) = s^ρ / γ(t) over the trees of order ≤ `max`, relative
    /// to Σ |w_i Φ_i(t)| (the size of the terms cancelling in the sum).
    fn worst_violation(weights: &[Real], a: &[Vec<Real>], max: usize, s: Real) -> Real {
        let mut worst: Real = 0.0;
        for (order, list) in trees(max).iter().enumerate().skip(1) {
            for tree in list {
                let phi = elementary_weights(tree, a);
                let terms = weights.iter().zip(&phi).map(|(w, p)| w * p);
                let sum: Real = terms.clone().sum();
                let scale: Real = terms.map(Real::abs).sum::<Real>().max(1.0);
                let exact = s.powi(order as i32) / tree.density();
                worst = worst.max((sum - exact).abs() / scale);
            }
        }
        worst
    }

    /// The full lower-triangular matrix of a tableau (row 0 empty), with `extra` rows appended.
    fn matrix(tableau: &Tableau, extra: &[&[Real]]) -> Vec<Vec<Real>> {
        std::iter::once(Vec::new())
            .chain(tableau.a.iter().chain(extra).map(|row| row.to_vec()))
            .collect()
    }

    fn padded(weights: &[Real], n: usize) -> Vec<Real> {
        let mut w = weights.to_vec();
        w.resize(n, 0.0);
        w
    }

    /// f64 rounding of coefficients up to ~500 in size: a few units of 1e-16 relative to the
    /// cancelling terms; a mistyped digit (beyond the 13th) shows far above this.
    const ORDER_CONDITION: Real = 1e-13;

    #[test]
    fn tree_counts_are_right() {
        // OEIS A000081: 1, 1, 2, 4, 9, 20, 48, 115 rooted trees of orders 1..8.
        let counts: Vec<usize> = trees(8).iter().skip(1).map(Vec::len).collect();
        assert_eq!(counts, [1, 1, 2, 4, 9, 20, 48, 115]);
    }

    #[test]
    fn stage_rows_sum_to_their_nodes() {
        for tableau in [DORMAND_PRINCE_54, DOP853] {
            assert_eq!(tableau.c.len(), tableau.stages());
            for (row, c) in tableau.a.iter().zip(&tableau.c[1..]) {
                assert!((row.iter().sum::<Real>() - c).abs() < 1e-14);
            }
        }
        for (row, c) in DOP853_DENSE_A.iter().zip(DOP853_DENSE_C) {
            assert!((row.iter().sum::<Real>() - c).abs() < 1e-14);
        }
    }

    #[test]
    fn dormand_prince_54_order_conditions() {
        let t = DORMAND_PRINCE_54;
        let a = matrix(&t, &[]);
        let b = padded(t.b(), t.stages());
        assert!(worst_violation(&b, &a, 5, 1.0) < ORDER_CONDITION);
        let ErrorWeights::Lower(lower) = t.error else {
            panic!("DP5(4) has one embedded solution");
        };
        assert!(worst_violation(lower, &a, 4, 1.0) < ORDER_CONDITION);
        // Order exactly 4: some 5th-order condition fails.
        assert!(worst_violation(lower, &a, 5, 1.0) > 1e-4);
    }

    #[test]
    fn dop853_order_conditions() {
        let t = DOP853;
        let a = matrix(&t, &[]);
        let n = t.stages();
        let b = padded(t.b(), n);
        let worst = worst_violation(&b, &a, 8, 1.0);
        println!("DOP853 weights, 200 trees of order <= 8: worst {worst:.2e}");
        assert!(worst < ORDER_CONDITION);
        let ErrorWeights::Combined { fifth, third } = t.error else {
            panic!("DOP853 has two estimators");
        };
        // b − E is a 5th-order solution, b̆ a 3rd-order one.
        let fifth_order: Vec<Real> = b.iter().zip(padded(fifth, n)).map(|(b, e)| b - e).collect();
        assert!(worst_violation(&fifth_order, &a, 5, 1.0) < ORDER_CONDITION);
        assert!(worst_violation(&fifth_order, &a, 6, 1.0) > 1e-6);
        assert!(worst_violation(&padded(third, n), &a, 3, 1.0) < ORDER_CONDITION);
    }

    /// The dense output's weights, polynomials in s, satisfy the order conditions of order ≤ 7
    /// with right-hand sides s^ρ/γ at several s (the trees use all 16 stages).
    #[test]
    fn dop853_dense_output_order_conditions() {
        let a = matrix(&DOP853, &DOP853_DENSE_A);
        for s in [0.1, 0.3, 0.5, 0.77, 0.95] {
            let w = dense_weights(s);
            let worst = worst_violation(&w, &a, 7, s);
            println!("DOP853 dense output at s = {s}: worst {worst:.2e} over 85 trees");
            assert!(worst < ORDER_CONDITION);
        }
    }

    /// The weight of each of the 16 stages in the dense output at fraction s (see the module doc).
    fn dense_weights(s: Real) -> Vec<Real> {
        let s1 = 1.0 - s;
        let b = padded(DOP853.b(), MAX_STAGES);
        (0..MAX_STAGES)
            .map(|i| {
                let delta = b[i];
                let beta = Real::from(u8::from(i == 0)) - delta;
                let last = Real::from(u8::from(i == 12));
                let [d4, d5, d6, d7] = DOP853_D.map(|row| row[i]);
                let inner = d4 + s * (d5 + s1 * (d6 + s * d7));
                s * (delta + s1 * (beta + s * (delta - last - beta + s1 * inner)))
            })
            .collect()
    }
}
