//! The nested (doubling) rule of the engine: the founding paper's azimuth–height form of an
//! ellipsoid, the clustered trapezoid rule in azimuth under doubling and Fejér's second rule in
//! height under doubling ([`surfgrav_quadrature::nested`]), so that every finer level reuses
//! every evaluation of the coarser one and the error estimate costs nothing.
//!
//! # Why the azimuth–height form suits Fejér's rule
//!
//! On a slice $z$ of the ellipsoid $x = a s\cos\varphi$, $y = b s\sin\varphi$,
//! $s = \sqrt{1 - z^2/c^2}$, the area vector per $\mathrm d\varphi\\,\mathrm dz$ is
//! $(b s\cos\varphi,\ a s\sin\varphi,\ ab z/c^2)$. Each integrand is a smooth function of
//! $(s\cos\varphi, s\sin\varphi, z)$ times such a vector, and its azimuthal integral is then a
//! smooth function of $s^2 = 1 - z^2/c^2$: the square root at the poles cancels once the
//! azimuth is summed, so the line sums are analytic in $z$ on $[-c, c]$ and Fejér's rule in $z$
//! converges geometrically. The height range is split at the equator (the rule on $[0, c]$ and
//! its mirror image), which puts the rule's end clustering where a body in the equatorial
//! plane comes closest, as the fixed ladder does ([`super::rules`]).
//!
//! # Levels and start
//!
//! Level $(i, j)$ has $N_0 2^i$ azimuth nodes (over a full turn) and $n_0 2^j - 1$ heights per
//! half. The bases $N_0$ and $n_0$ are chosen from the ladder's prediction of the nodes the
//! tolerance needs ([`super::InteractionEngine`]'s start model), so that the coarser levels of
//! the start grid, $(0, 1)$ and $(1, 0)$, are the predicted sufficient grid: when the
//! prediction holds, the first grid is both the answer and its certificate.
//!
//! Far away (gap ratio at least 8, `NESTED_GEOMETRIC_GAP` of the engine) the integrand is
//! analytic in a wide strip, the error falls geometrically from the coarsest levels, and a
//! direction's error is estimated as $\delta_2(\delta_2/\delta_1)^{3/2}$
//! ([`surfgrav_quadrature::geometric_estimate`]) instead of $\delta_2^2/\delta_1$, from a
//! start one level coarser in height: the founding paper's pair at separation 30 certifies
//! 10⁻¹² on 63 nodes (9 azimuths × 7 heights) instead of 99.

use super::kernel::{
    add_solid_node, FrameMap, NodeConstants, SolidBlock, SolidMagnitudes, SolidSums,
};
use super::rules::CLUSTERING;
use std::collections::HashMap;
use std::f64::consts::{PI, TAU};
use std::ops::Range;
use std::sync::{Arc, Mutex, OnceLock};
use surfgrav_potentials::{Field, Potential};
use surfgrav_quadrature::{
    Interval, NestedFejer, NestedTensorRule, NestedTrapezoid, QuadratureError,
};
use surfgrav_surfaces::{Real, Vec3};

/// Largest azimuth count of the finest level over a full turn.
pub const MAX_NESTED_AZIMUTH: usize = 8192;

/// Largest subdivision count of the finest height level (heights per half: one less).
pub const MAX_NESTED_HEIGHTS: usize = 1024;

/// A nested rule with the azimuth's cosines and sines tabulated (built once, shared).
#[derive(Debug)]
pub(crate) struct NestedRuleSet {
    pub(crate) rule: NestedTensorRule,
    pub(crate) cos: Vec<Real>,
    pub(crate) sin: Vec<Real>,
}

/// What identifies a nested rule set: azimuth base, clustering index, half azimuth, height base.
type RuleKey = (usize, u8, bool, usize);

fn cache() -> &'static Mutex<HashMap<RuleKey, Arc<NestedRuleSet>>> {
    static CACHE: OnceLock<Mutex<HashMap<RuleKey, Arc<NestedRuleSet>>>> = OnceLock::new();
    CACHE.get_or_init(|| Mutex::new(HashMap::new()))
}

/// Rounds a base up to the form $m 2^e$, $m \in \\{4, 5, 6, 7\\}$ (or 1, 2, 3 below 4), so that few
/// distinct rules are ever built.
pub(crate) fn round_base(n: usize) -> usize {
    if n <= 4 {
        return n.max(1);
    }
    let mut e = 0;
    while (n >> e) >= 8 {
        e += 1;
    }
    let m = n.div_ceil(1 << e);
    m << e
}

/// The shared rule set for these bases (built on first use).
pub(crate) fn rule_set(
    azimuth_base: usize,
    clustering: u8,
    half_azimuth: bool,
    height_base: usize,
) -> Result<Arc<NestedRuleSet>, QuadratureError> {
    let key = (azimuth_base, clustering, half_azimuth, height_base);
    if let Ok(map) = cache().lock() {
        if let Some(set) = map.get(&key) {
            return Ok(set.clone());
        }
    }
    let mut azimuth_levels = 0;
    while (azimuth_base << (azimuth_levels + 1)) <= MAX_NESTED_AZIMUTH && azimuth_levels < 10 {
        azimuth_levels += 1;
    }
    let mut height_levels = 0;
    while (height_base << (height_levels + 1)) <= MAX_NESTED_HEIGHTS && height_levels < 10 {
        height_levels += 1;
    }
    let eps = CLUSTERING[usize::from(clustering).min(CLUSTERING.len() - 1)];
    // The clustering map of `super::rules`, with ψ ∈ [0, 2π): φ(ψ) = 2 atan(ε tan(ψ/2)).
    let map = |psi: Real| {
        let (s, c) = (0.5 * psi).sin_cos();
        let mut phi = 2.0 * (eps * s).atan2(c);
        if phi < 0.0 {
            phi += TAU;
        }
        (phi.clamp(0.0, TAU), eps / (c * c + eps * eps * s * s))
    };
    let periodic =
        NestedTrapezoid::with_map(azimuth_base, azimuth_levels, 0.0, TAU, half_azimuth, map)?;
    let across = NestedFejer::new(height_base, height_levels, Interval::new(0.0, 1.0)?)?;
    let (sin, cos): (Vec<Real>, Vec<Real>) = periodic
        .nodes()
        .iter()
        .map(|&phi| {
            // Exact zeros on the mirror planes (φ = 0, π), which the half rules contain.
            if phi == 0.0 {
                (0.0, 1.0)
            } else if phi == PI {
                (0.0, -1.0)
            } else {
                phi.sin_cos()
            }
        })
        .unzip();
    let set = Arc::new(NestedRuleSet {
        rule: NestedTensorRule { periodic, across },
        cos,
        sin,
    });
    if let Ok(mut map) = cache().lock() {
        if map.len() > 256 {
            map.clear();
        }
        map.insert(key, set.clone());
    }
    Ok(set)
}

/// Components of the nested integrand: $\Phi - \Phi_0$ times $\mathrm d\mathbf S$ (3), times
/// $\mathbf x\times\mathrm d\mathbf S$ (3), $\tfrac12|\mathbf x|^2\\,\mathrm d\mathbf S\times\mathbf a$ (3),
/// the energy integrand (1), the magnitudes of the force, torque and energy terms for the
/// rounding bound (3), $\mathbf x\\,(\mathbf a\cdot\mathrm d\mathbf S)$ (3) and the magnitudes
/// $|\mathbf x||\mathbf a\cdot\mathrm d\mathbf S|$, $|\Phi||\mathrm d\mathbf S|$ (2), as in
/// [`super::kernel`]'s solid loop.
pub(crate) const COMPONENTS: usize = 18;

/// What one node of a line adds (see [`COMPONENTS`]); everything but the field is computed
/// once for a node and its mirror image, which share $\tfrac12|\mathbf x|^2$, $\mathbf x\cdot\mathbf W$,
/// $|\mathbf W|$, $|\mathbf x\times\mathbf W|$ and $|\mathbf x|$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct NodeGeometry {
    /// The weighted area vector $\mathbf W$.
    w: Vec3,
    /// The node's constants, $\mathbf x = \mathbf r$ (the centroid is the origin).
    k: NodeConstants,
}

/// The terms of a segment's nodes summed by the kernel's one integrand ([`add_solid_node`]),
/// as the nested rule's components (see [`COMPONENTS`] and [`solid_sums_from`]).
fn components(block: &SolidBlock, sizes: &SolidMagnitudes) -> [Real; COMPONENTS] {
    [
        block.flux.x,
        block.flux.y,
        block.flux.z,
        block.moment.x,
        block.moment.y,
        block.moment.z,
        block.gradient_moment.x,
        block.gradient_moment.y,
        block.gradient_moment.z,
        block.energy,
        sizes.flux,
        sizes.moment,
        sizes.energy,
        block.acceleration_flux.x,
        block.acceleration_flux.y,
        block.acceleration_flux.z,
        sizes.acceleration,
        sizes.potential,
    ]
}

/// The geometry of the nodes `range` (nested order) of height node `k` of an ellipsoid of
/// semi-axes `axes`, appended to `out`.
fn line_geometry(
    set: &NestedRuleSet,
    axes: [Real; 3],
    k: usize,
    range: Range<usize>,
    out: &mut Vec<NodeGeometry>,
) {
    let [a, b, c] = axes;
    let x = set.rule.across.nodes()[k];
    let z = c * x;
    let z2 = z * z;
    let s = ((1.0 - x) * (1.0 + x)).sqrt();
    let (a_s, b_s) = (a * s, b * s);
    // dS per dφ dx (dz = c dx): c (b s cos φ, a s sin φ, ab z / c²).
    let (nx, ny, nz) = (c * b_s, c * a_s, a * b * x);
    let factors = &set.rule.periodic.factors()[range.clone()];
    let cos = &set.cos[range.clone()];
    let sin = &set.sin[range];
    out.extend(factors.iter().zip(cos).zip(sin).map(|((&f, &cp), &sp)| {
        let (rx, ry) = (a_s * cp, b_s * sp);
        let (wx, wy, wz) = (f * nx * cp, f * ny * sp, f * nz);
        let moment = Vec3::new(ry * wz - z * wy, z * wx - rx * wz, rx * wy - ry * wx);
        let x2 = rx * rx + ry * ry + z2;
        NodeGeometry {
            w: Vec3::new(wx, wy, wz),
            k: NodeConstants {
                x: Vec3::new(rx, ry, z),
                moment,
                half_x2: 0.5 * x2,
                x_dot_w: rx * wx + ry * wy + z * wz,
                w_norm: (wx * wx + wy * wy + wz * wz).sqrt(),
                moment_norm: moment.norm(),
                x_norm: x2.sqrt(),
            },
        }
    }));
}

/// Nodes cached per geometry (112 bytes each: 1.8 MB, at most 7 MB for the
/// [`CACHED_GEOMETRIES`]; the founding paper's pair needs at most 775): beyond, a line's
/// geometry is computed for the call only.
const MAX_CACHED_NODES: usize = 1 << 14;

/// Geometries kept (an engine alternates between a pair's two bodies, or a few pairs).
const CACHED_GEOMETRIES: usize = 4;

/// The node geometry of one ellipsoid under one nested rule set, line by line in nested
/// order: the nested rule's counterpart of a fixed table's per-node constants, built on first
/// use and kept by the engine.
#[derive(Debug, Clone, Default)]
pub(crate) struct LineGeometry {
    lines: Vec<Vec<NodeGeometry>>,
    cached: usize,
    scratch: Vec<NodeGeometry>,
    /// A line's fields (reused).
    fields: Vec<Field>,
}

impl LineGeometry {
    /// The geometry of nodes `range` of line `k` (computed now if not cached), and a buffer
    /// for their fields.
    pub(crate) fn line(
        &mut self,
        set: &NestedRuleSet,
        axes: [Real; 3],
        k: usize,
        range: Range<usize>,
    ) -> (&[NodeGeometry], &mut Vec<Field>) {
        if self.lines.len() <= k {
            self.lines.resize_with(k + 1, Vec::new);
        }
        let have = self.lines[k].len();
        if have < range.end {
            if self.cached + (range.end - have) > MAX_CACHED_NODES {
                self.scratch.clear();
                line_geometry(set, axes, k, range, &mut self.scratch);
                return (&self.scratch, &mut self.fields);
            }
            line_geometry(set, axes, k, have..range.end, &mut self.lines[k]);
            self.cached += range.end - have;
        }
        (&self.lines[k][range], &mut self.fields)
    }
}

/// What identifies a [`LineGeometry`]: the rule set's key and the semi-axes' bits.
type GeometryKey = (RuleKey, [u64; 3]);

/// The engine's [`LineGeometry`] store, most recently used first.
#[derive(Debug, Clone, Default)]
pub(crate) struct GeometryCache {
    entries: Vec<(GeometryKey, LineGeometry)>,
}

impl GeometryCache {
    /// The geometry of an ellipsoid of semi-axes `axes` under the rule set of these bases.
    pub(crate) fn get(
        &mut self,
        azimuth_base: usize,
        clustering: u8,
        half_azimuth: bool,
        height_base: usize,
        axes: [Real; 3],
    ) -> &mut LineGeometry {
        let key = (
            (azimuth_base, clustering, half_azimuth, height_base),
            axes.map(Real::to_bits),
        );
        match self.entries.iter().position(|(k, _)| *k == key) {
            Some(i) => self.entries[..=i].rotate_right(1),
            None => {
                if self.entries.len() >= CACHED_GEOMETRIES {
                    self.entries.pop();
                }
                self.entries.insert(0, (key, LineGeometry::default()));
            }
        }
        &mut self.entries[0].1
    }
}

/// Adds to `outs[s]` the sum over the nodes `start..ends[s]` of one height line (`nodes` holds
/// `start..` the last end; with `mirror`, also over their mirror images $-z$)
/// of the integrand times the azimuth factor (the acceleration form of the force only with
/// `FAR`), in the field of `source` (`reference` its potential at the centroid). The line's
/// fields are evaluated first, into `fields`, then summed: consecutive field evaluations (long
/// chains of divisions and square roots) overlap in the processor. Returns the evaluations
/// spent.
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn ellipsoid_line<P: Potential + ?Sized, const FAR: bool>(
    nodes: &[NodeGeometry],
    start: usize,
    ends: &[usize],
    mirror: bool,
    source: &P,
    map: &FrameMap,
    reference: Real,
    outs: &mut [[Real; COMPONENTS]],
    fields: &mut Vec<Field>,
) -> usize {
    // The mirror image (rx, ry, −z) with W = (wx, wy, −wz): x × W = (−mx, −my, mz), of the
    // same length; every other constant is shared.
    let mirrored = |n: &NodeGeometry| {
        let mut m = *n;
        m.k.x.z = -n.k.x.z;
        m.w.z = -n.w.z;
        m.k.moment.x = -n.k.moment.x;
        m.k.moment.y = -n.k.moment.y;
        m
    };
    fields.clear();
    fields.extend(nodes.iter().map(|n| source.field(&map.apply(&n.k.x))));
    if mirror {
        fields.extend(
            nodes
                .iter()
                .map(|n| source.field(&map.apply(&mirrored(n).k.x))),
        );
    }
    let (upper, lower) = fields.split_at(nodes.len());
    // Each segment summed on its own, then added to the running prefix.
    let mut prefix = [0.0; COMPONENTS];
    let mut from = 0;
    for (&end, out) in ends.iter().zip(outs) {
        let to = end - start;
        let mut block = SolidBlock::default();
        let mut sizes = SolidMagnitudes::default();
        for (i, n) in nodes[from..to].iter().enumerate() {
            let field = &upper[from + i];
            add_solid_node::<FAR, true>(&mut block, &mut sizes, field, map, &n.w, &n.k, reference);
            if mirror {
                let m = mirrored(n);
                let field = &lower[from + i];
                add_solid_node::<FAR, true>(
                    &mut block, &mut sizes, field, map, &m.w, &m.k, reference,
                );
            }
        }
        let acc = components(&block, &sizes);
        for ((o, p), v) in out.iter_mut().zip(prefix.iter_mut()).zip(acc) {
            *p += v;
            *o += *p;
        }
        from = to;
    }
    if mirror {
        2 * nodes.len()
    } else {
        nodes.len()
    }
}

/// The raw sums of a nested value (see [`COMPONENTS`]); the acceleration form of the force only
/// when `far` (as the fixed rules' loops).
pub(crate) fn solid_sums_from(v: &[Real; COMPONENTS], far: bool) -> SolidSums {
    let far = if far { 1.0 } else { 0.0 };
    SolidSums {
        potential_flux: Vec3::new(v[0], v[1], v[2]),
        potential_moment: Vec3::new(v[3], v[4], v[5]),
        gradient_moment: Vec3::new(v[6], v[7], v[8]),
        energy_flux: v[9],
        potential_flux_magnitude: v[10],
        potential_moment_magnitude: v[11],
        energy_flux_magnitude: v[12],
        acceleration_flux: Vec3::new(v[13], v[14], v[15]) * far,
        acceleration_flux_magnitude: v[16] * far,
        potential_magnitude: v[17],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A line's geometry is the same from the cache and, past the cache's cap, computed for
    /// the call; its points lie on the ellipsoid and the area vectors are outward normals.
    #[test]
    fn cached_and_uncached_line_geometry_agree() {
        let set = rule_set(4, 2, false, 3).unwrap();
        let axes = [1.0, 0.8, 0.3];
        let mut cached = LineGeometry::default();
        let mut full = LineGeometry {
            cached: MAX_CACHED_NODES,
            ..LineGeometry::default()
        };
        for k in 0..set.rule.across.count(2) {
            for range in [0..4, 4..9, 0..17] {
                let (a, _) = cached.line(&set, axes, k, range.clone());
                let a = a.to_vec();
                let (b, _) = full.line(&set, axes, k, range.clone());
                assert_eq!(a, b.to_vec(), "line {k}, nodes {range:?}");
                for n in &a {
                    let on = (n.k.x.x / axes[0]).powi(2)
                        + (n.k.x.y / axes[1]).powi(2)
                        + (n.k.x.z / axes[2]).powi(2);
                    assert!((on - 1.0).abs() < 1e-14, "{on}");
                    // The surface normal at r is (x/a², y/b², z/c²).
                    let normal = Vec3::new(
                        n.k.x.x / (axes[0] * axes[0]),
                        n.k.x.y / (axes[1] * axes[1]),
                        n.k.x.z / (axes[2] * axes[2]),
                    );
                    assert!(n.w.cross(&normal).norm() <= 1e-14 * n.w.norm() * normal.norm());
                    assert!(n.w.dot(&normal) > 0.0);
                }
            }
        }
        assert!(full.lines.iter().all(Vec::is_empty));
    }
}
