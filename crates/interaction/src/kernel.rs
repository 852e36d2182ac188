//! The node loops: one pass over an integrated body's node table evaluates the source body's
//! field once per node and accumulates every sum that the force, the torque (both forms) and
//! the mutual potential energy need (see the [module docs](super) for the formulas).
//!
//! The loops are generic over the source potential (`P: Potential + ?Sized`), so the field
//! formula of a concrete type is compiled into them; with `P = dyn Potential` they still work,
//! at the price of one indirect call per node. Nodes are moved into the source's frame on the
//! fly (nine fused multiply–adds), so no transformed copy of the table is stored and nothing is
//! allocated. Summation: plain within blocks of [`BLOCK`] nodes, compensated
//! ([`surfgrav_surfaces::CompensatedSum`]) across blocks, which keeps the rounding error at the level of
//! one block's (measured: below $10^{-15}$ relative for every table the engine builds) for a
//! fraction of the cost of compensating every term.

use super::error::InteractionError;
use nalgebra::{Matrix3, Rotation3};
use surfgrav_potentials::{Field, Pose, PoseExt, Potential};
use surfgrav_surfaces::sum::CompensatedSum3;
use surfgrav_surfaces::{LaminaNodes, Real, SurfaceNodes, Vec3};

/// Nodes summed plainly before a compensated addition.
pub const BLOCK: usize = 16;

/// The affine map $\mathbf r_B = M\\,\mathbf r + \mathbf t$ from the frame of an integrated body's
/// node table into the frame of the body whose field is evaluated ($M$ a rotation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameMap {
    pub(crate) rotation: Matrix3<Real>,
    pub(crate) offset: Vec3,
}

impl FrameMap {
    /// The map with rotation `rotation` and offset `offset`; fails on a non-finite entry.
    pub fn new(rotation: &Rotation3<Real>, offset: &Vec3) -> Result<Self, InteractionError> {
        let m = *rotation.matrix();
        if m.iter().chain(offset.iter()).all(|x| x.is_finite()) {
            Ok(Self {
                rotation: m,
                offset: *offset,
            })
        } else {
            Err(InteractionError::NonFinitePose {
                body: super::Side::A,
                what: "frame map (rotation or offset)",
            })
        }
    }

    /// The map from the body frame of a body at `integrated` to the body frame of a body at
    /// `source`: $M = R_s^{\mathsf T} R_i$, $\mathbf t = R_s^{\mathsf T}(\mathbf p_i - \mathbf p_s)$.
    pub fn between(integrated: &Pose, source: &Pose) -> Result<Self, InteractionError> {
        let rotation = (source.rotation.inverse() * integrated.rotation).to_rotation_matrix();
        let offset = source
            .rotation
            .inverse_transform_vector(&(integrated.position() - source.position()));
        Self::new(&rotation, &offset)
    }

    /// $M\mathbf r + \mathbf t$.
    #[inline]
    pub fn apply(&self, r: &Vec3) -> Vec3 {
        self.rotation * r + self.offset
    }

    /// [`FrameMap::apply`] at $(x, y, z)$, written out by component (the operations of the
    /// node loops over arrays, which the compiler vectorises across nodes).
    #[inline(always)]
    pub(crate) fn apply_components(&self, x: Real, y: Real, z: Real) -> Vec3 {
        let (m, t) = (&self.rotation, &self.offset);
        Vec3::new(
            m[(0, 0)] * x + m[(0, 1)] * y + m[(0, 2)] * z + t.x,
            m[(1, 0)] * x + m[(1, 1)] * y + m[(1, 2)] * z + t.y,
            m[(2, 0)] * x + m[(2, 1)] * y + m[(2, 2)] * z + t.z,
        )
    }

    /// $M^{\mathsf T}\mathbf v$: a source-frame vector in the table frame.
    #[inline]
    pub fn back(&self, v: &Vec3) -> Vec3 {
        self.rotation.tr_mul(v)
    }
}

/// The raw node sums over a closed surface (table frame; $\mathbf x = \mathbf r - \mathbf o$ from
/// the centroid, $\mathbf a$ the source's acceleration turned into the table frame).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SolidSums {
    /// $\sum_k (\Phi_k - \Phi_0) \mathbf W_k \approx \oint \Phi\\,\mathrm d\mathbf S$, with $\Phi_0$ the
    /// source's potential at the centroid (taken out because $\oint\mathrm d\mathbf S = 0$: the
    /// terms, and their rounding, shrink by the ratio of the body's size to its distance).
    pub potential_flux: Vec3,
    /// $\sum_k (\Phi_k - \Phi_0)\\, \mathbf x_k \times \mathbf W_k \approx \oint \Phi\\,\mathbf x\times\mathrm d\mathbf S$
    /// ($\oint\mathbf x\times\mathrm d\mathbf S = 0$).
    pub potential_moment: Vec3,
    /// $\sum_k \tfrac12|\mathbf x_k|^2\\, \mathbf W_k \times \mathbf a_k \approx \tfrac12\oint |\mathbf x|^2\\,\mathrm d\mathbf S\times\mathbf a$.
    pub gradient_moment: Vec3,
    /// $\sum_k (\Phi_k \mathbf x_k + \tfrac12|\mathbf x_k|^2 \mathbf a_k)\cdot\mathbf W_k$.
    pub energy_flux: Real,
    /// $\sum_k |\Phi_k - \Phi_0|\\,|\mathbf W_k|$: the size of the terms of `potential_flux`,
    /// which bounds its rounding error (the terms cancel to a small result far from the source).
    pub potential_flux_magnitude: Real,
    /// $\sum_k |\Phi_k - \Phi_0|\\,|\mathbf x_k\times\mathbf W_k|$.
    pub potential_moment_magnitude: Real,
    /// $\sum_k |\Phi_k\\,\mathbf x_k\cdot\mathbf W_k| + |\tfrac12|\mathbf x_k|^2\\,\mathbf a_k\cdot\mathbf W_k|$.
    pub energy_flux_magnitude: Real,
    /// $\sum_k \mathbf x_k\\,(\mathbf a_k\cdot\mathbf W_k) \approx \oint\mathbf x\\,(\mathbf a\cdot\mathrm d\mathbf S)
    /// = \int\mathbf a\\,\mathrm dV$ (as $\nabla\cdot(\mathbf x\otimes\mathbf a) = \mathbf a$ where
    /// $\nabla\cdot\mathbf a = 0$): the acceleration form of the force, free of the cancellation
    /// of $\Phi_k - \Phi_0$ far from the source (the engine's `force_form` choice).
    pub acceleration_flux: Vec3,
    /// $\sum_k |\mathbf x_k|\\,|\mathbf a_k\cdot\mathbf W_k|$.
    pub acceleration_flux_magnitude: Real,
    /// $\sum_k |\Phi_k|\\,|\mathbf W_k|$: the scale of the rounding of $\Phi_k$ itself, which
    /// $\Phi_k - \Phi_0$ keeps.
    pub potential_magnitude: Real,
}

impl SolidSums {
    /// The sums over these nodes and their mirror images in the plane $x\_{axis} = 0$, for a
    /// field with that mirror symmetry: a mirror image changes the sign of a polar vector's
    /// component `axis` and of an axial vector's (a moment's) other two components, so the
    /// sum keeps twice the polar vectors' other components and twice the axial vectors'
    /// component `axis`; scalars double.
    #[inline]
    pub(crate) fn symmetrised(&self, axis: usize) -> Self {
        let (polar, axial) = match axis {
            0 => (Vec3::new(0.0, 2.0, 2.0), Vec3::new(2.0, 0.0, 0.0)),
            1 => (Vec3::new(2.0, 0.0, 2.0), Vec3::new(0.0, 2.0, 0.0)),
            _ => (Vec3::new(2.0, 2.0, 0.0), Vec3::new(0.0, 0.0, 2.0)),
        };
        Self {
            potential_flux: self.potential_flux.component_mul(&polar),
            potential_moment: self.potential_moment.component_mul(&axial),
            gradient_moment: self.gradient_moment.component_mul(&axial),
            energy_flux: 2.0 * self.energy_flux,
            potential_flux_magnitude: 2.0 * self.potential_flux_magnitude,
            potential_moment_magnitude: 2.0 * self.potential_moment_magnitude,
            energy_flux_magnitude: 2.0 * self.energy_flux_magnitude,
            acceleration_flux: self.acceleration_flux.component_mul(&polar),
            acceleration_flux_magnitude: 2.0 * self.acceleration_flux_magnitude,
            potential_magnitude: 2.0 * self.potential_magnitude,
        }
    }

    /// The physical integrals for a solid of density `density` (table frame):
    /// $\mathbf F = -\rho\oint\Phi\\,\mathrm d\mathbf S$, $\mathbf M = -\rho\oint\Phi\\,\mathbf x\times\mathrm d\mathbf S$,
    /// $\mathbf M' = \tfrac\rho2\oint|\mathbf x|^2\\,\mathrm d\mathbf S\times\mathbf a$,
    /// $V = \tfrac\rho3\oint(\Phi\mathbf x + \tfrac12|\mathbf x|^2\mathbf a)\cdot\mathrm d\mathbf S$.
    pub fn integrals(&self, density: Real, evaluations: usize) -> SolidIntegrals {
        SolidIntegrals {
            force: -density * self.potential_flux,
            torque: -density * self.potential_moment,
            torque_gradient_form: density * self.gradient_moment,
            potential_energy: density * self.energy_flux / 3.0,
            evaluations,
        }
    }
}

/// Force, torque (both forms) and mutual potential energy of a homogeneous solid in another
/// body's field, in the frame of its node table, torques about its centroid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolidIntegrals {
    /// $\mathbf F = -\rho\oint\Phi\\,\mathrm d\mathbf S$ (force on the solid).
    pub force: Vec3,
    /// $\mathbf M = -\rho\oint\Phi\\,(\mathbf r-\mathbf o)\times\mathrm d\mathbf S$.
    pub torque: Vec3,
    /// $\mathbf M = \tfrac\rho2\oint|\mathbf r-\mathbf o|^2\\,\mathrm d\mathbf S\times\mathbf a$: the
    /// same torque by the second form; the two agree to quadrature accuracy.
    pub torque_gradient_form: Vec3,
    /// $V = \rho\int\Phi\\,\mathrm dV$ (negative); valid when the source's matter is outside the
    /// solid.
    pub potential_energy: Real,
    /// Field evaluations spent.
    pub evaluations: usize,
}

#[inline]
fn reflect_polar(v: &Vec3, axis: usize) -> Vec3 {
    // A product with a sign vector, not a store through a run-time index: the latter made
    // the symmetrisation of the nested rule's level values a measurable share of its cost.
    let sign = match axis {
        0 => Vec3::new(-1.0, 1.0, 1.0),
        1 => Vec3::new(1.0, -1.0, 1.0),
        _ => Vec3::new(1.0, 1.0, -1.0),
    };
    v.component_mul(&sign)
}

#[inline]
fn reflect_axial(v: &Vec3, axis: usize) -> Vec3 {
    -reflect_polar(v, axis)
}

/// The solid loop over parallel slices of points and weighted area vectors (table frame),
/// moments about `origin`: [`add_solid_node`] with each node's constants computed on the fly.
#[inline(never)]
pub(crate) fn solid_sums<P: Potential + ?Sized>(
    points: &[Vec3],
    area_vectors: &[Vec3],
    origin: &Vec3,
    source: &P,
    map: &FrameMap,
) -> SolidSums {
    let mut totals = SolidTotals::new();
    let mut sizes = SolidMagnitudes::default();
    // ∮ dS = 0 and ∮ x × dS = 0: the potential at the centroid can be taken out of the force
    // and torque sums, whose terms then shrink by the ratio of size to distance.
    let reference = source.potential(&map.apply(origin));
    for (block_points, block_weights) in points.chunks(BLOCK).zip(area_vectors.chunks(BLOCK)) {
        let mut block = SolidBlock::default();
        let fields = block_fields::<P, true>(block_points, source, map);
        for ((r, w), field) in block_points.iter().zip(block_weights).zip(&fields) {
            let k = NodeConstants::new(r - origin, w);
            add_solid_node::<false, true>(&mut block, &mut sizes, field, map, w, &k, reference);
        }
        // Without `FAR` the block's acceleration flux stays zero, and so does its total.
        totals.add::<true>(&block);
    }
    totals.finish(&sizes)
}

/// What a solid node's terms need besides the field, the point and the weighted area vector
/// $\mathbf W$: constants of the node ($\mathbf x = \mathbf r - \mathbf o$), computed once when a
/// table is built (or per node where the nodes move with the pose).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct NodeConstants {
    /// $\mathbf x\times\mathbf W$.
    pub(crate) moment: Vec3,
    /// $\tfrac12|\mathbf x|^2$.
    pub(crate) half_x2: Real,
    /// $\mathbf x\cdot\mathbf W$.
    pub(crate) x_dot_w: Real,
    /// $|\mathbf W|$.
    pub(crate) w_norm: Real,
    /// $|\mathbf x\times\mathbf W|$.
    pub(crate) moment_norm: Real,
    /// $\mathbf x$.
    pub(crate) x: Vec3,
    /// $|\mathbf x|$.
    pub(crate) x_norm: Real,
}

impl NodeConstants {
    /// The constants of a node at $\mathbf x$ (from the centroid) with area vector `w`.
    #[inline(always)]
    pub(crate) fn new(x: Vec3, w: &Vec3) -> Self {
        let moment = x.cross(w);
        Self {
            moment,
            half_x2: 0.5 * x.norm_squared(),
            x_dot_w: x.dot(w),
            w_norm: w.norm(),
            moment_norm: moment.norm(),
            x,
            x_norm: x.norm(),
        }
    }
}

/// One block's plain sums of the solid integrand (summed compensated across blocks).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct SolidBlock {
    /// $\sum(\Phi - \Phi_0)\mathbf W$.
    pub(crate) flux: Vec3,
    /// $\sum(\Phi - \Phi_0)\\,\mathbf x\times\mathbf W$.
    pub(crate) moment: Vec3,
    /// $\sum\tfrac12|\mathbf x|^2\\,\mathbf W\times\mathbf a$.
    pub(crate) gradient_moment: Vec3,
    /// $\sum(\Phi\mathbf x + \tfrac12|\mathbf x|^2\mathbf a)\cdot\mathbf W$.
    pub(crate) energy: Real,
    /// $\sum\mathbf x\\,(\mathbf a\cdot\mathbf W)$ (far away only).
    pub(crate) acceleration_flux: Vec3,
}

/// The compensated totals of [`SolidBlock`]s over a table: every solid loop adds its blocks
/// here and finishes with the sizes (`FULL`: torques and energy too, otherwise the force parts).
///
/// Neumaier's compensated sums ([`CompensatedSum`](surfgrav_surfaces::sum::CompensatedSum), the same operations, so the same bits),
/// kept side by side in arrays with the branch on the larger magnitude replaced by a selection
/// between both corrections: the sums of one block are added together, without a branch
/// that the signs of the sums make unpredictable.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SolidTotals {
    /// Flux x, y, z, acceleration flux x, y, z.
    force: Neumaier<6>,
    /// Moment x, y, z, gradient moment x, y, z, energy.
    full: Neumaier<7>,
}

/// `N` compensated sums side by side (Neumaier's, as
/// [`CompensatedSum`](surfgrav_surfaces::sum::CompensatedSum)).
#[derive(Debug, Clone, Copy)]
struct Neumaier<const N: usize> {
    sum: [Real; N],
    compensation: [Real; N],
}

impl<const N: usize> Neumaier<N> {
    fn new() -> Self {
        Self {
            sum: [0.0; N],
            compensation: [0.0; N],
        }
    }

    /// Adds `x[i]` to sum `i`: [`CompensatedSum::add`](surfgrav_surfaces::sum::CompensatedSum::add) with both corrections computed and the
    /// one for the larger magnitude kept.
    #[inline(always)]
    fn add(&mut self, x: &[Real; N]) {
        for i in 0..N {
            let (s, x) = (self.sum[i], x[i]);
            let t = s + x;
            let (big, small) = ((s - t) + x, (x - t) + s);
            self.compensation[i] += if s.abs() >= x.abs() { big } else { small };
            self.sum[i] = t;
        }
    }

    /// Sum `i`: [`CompensatedSum::value`](surfgrav_surfaces::sum::CompensatedSum::value).
    fn value(&self, i: usize) -> Real {
        self.sum[i] + self.compensation[i]
    }

    fn vector(&self, first: usize) -> Vec3 {
        Vec3::new(
            self.value(first),
            self.value(first + 1),
            self.value(first + 2),
        )
    }
}

impl SolidTotals {
    pub(crate) fn new() -> Self {
        Self {
            force: Neumaier::new(),
            full: Neumaier::new(),
        }
    }

    /// Adds one block's plain sums.
    #[inline(always)]
    pub(crate) fn add<const FULL: bool>(&mut self, block: &SolidBlock) {
        let (f, a) = (&block.flux, &block.acceleration_flux);
        self.force.add(&[f.x, f.y, f.z, a.x, a.y, a.z]);
        if FULL {
            let (m, g) = (&block.moment, &block.gradient_moment);
            self.full.add(&[m.x, m.y, m.z, g.x, g.y, g.z, block.energy]);
        }
    }

    /// The sums, with the magnitudes gathered along the loop.
    pub(crate) fn finish(&self, sizes: &SolidMagnitudes) -> SolidSums {
        sizes.sums(
            self.force.vector(0),
            self.full.vector(0),
            self.full.vector(3),
            self.full.value(6),
            self.force.vector(3),
        )
    }
}

/// The running sizes of the solid integrand's terms (the rounding bounds of [`SolidSums`]).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct SolidMagnitudes {
    /// $\sum|\Phi - \Phi_0||\mathbf W|$.
    pub(crate) flux: Real,
    /// $\sum|\Phi - \Phi_0||\mathbf x\times\mathbf W|$.
    pub(crate) moment: Real,
    /// $\sum|\Phi\\,\mathbf x\cdot\mathbf W| + |\tfrac12|\mathbf x|^2\mathbf a\cdot\mathbf W|$.
    pub(crate) energy: Real,
    /// $\sum|\mathbf x||\mathbf a\cdot\mathbf W|$ (far away only).
    pub(crate) acceleration: Real,
    /// $\sum|\Phi||\mathbf W|$.
    pub(crate) potential: Real,
}

impl SolidMagnitudes {
    /// The sums with these magnitudes.
    pub(crate) fn sums(
        &self,
        potential_flux: Vec3,
        potential_moment: Vec3,
        gradient_moment: Vec3,
        energy_flux: Real,
        acceleration_flux: Vec3,
    ) -> SolidSums {
        SolidSums {
            potential_flux,
            potential_moment,
            gradient_moment,
            energy_flux,
            potential_flux_magnitude: self.flux,
            potential_moment_magnitude: self.moment,
            energy_flux_magnitude: self.energy,
            acceleration_flux,
            acceleration_flux_magnitude: self.acceleration,
            potential_magnitude: self.potential,
        }
    }
}

/// The solid integrand at one node, added to a block's sums: the one place where the terms of
/// the force (both forms), the torques (both forms) and the energy are written. `field` is the
/// source's field at the node (source frame; `map` turns its acceleration back), `w` the
/// weighted area vector, `reference` the source's potential at the centroid. `FULL`: torques
/// and energy too (otherwise the force alone); `FAR`: the acceleration form of the force too.
#[inline(always)]
pub(crate) fn add_solid_node<const FAR: bool, const FULL: bool>(
    block: &mut SolidBlock,
    sizes: &mut SolidMagnitudes,
    field: &Field,
    map: &FrameMap,
    w: &Vec3,
    k: &NodeConstants,
    reference: Real,
) {
    let phi = field.potential;
    if FULL {
        let a = map.back(&field.acceleration);
        let a_dot_w = a.dot(w);
        let (e_potential, e_gradient) = (phi * k.x_dot_w, k.half_x2 * a_dot_w);
        if FAR {
            block.acceleration_flux += k.x * a_dot_w;
            sizes.acceleration += k.x_norm * a_dot_w.abs();
        }
        sizes.potential += phi.abs() * k.w_norm;
        let relative = phi - reference;
        block.flux += w * relative;
        block.moment += k.moment * relative;
        block.gradient_moment += w.cross(&a) * k.half_x2;
        block.energy += e_potential + e_gradient;
        sizes.flux += relative.abs() * k.w_norm;
        sizes.moment += relative.abs() * k.moment_norm;
        sizes.energy += e_potential.abs() + e_gradient.abs();
    } else {
        if FAR {
            let a_dot_w = map.back(&field.acceleration).dot(w);
            block.acceleration_flux += k.x * a_dot_w;
            sizes.acceleration += k.x_norm * a_dot_w.abs();
        }
        sizes.potential += phi.abs() * k.w_norm;
        let relative = phi - reference;
        block.flux += w * relative;
        sizes.flux += relative.abs() * k.w_norm;
    }
}

/// The solid integrand at a single node ([`add_solid_node`] with everything, near form): for
/// rules that evaluate one node at a time (the adaptive cubature). `x` is the node's position
/// from the centroid (table frame).
#[inline]
pub(crate) fn solid_node(
    field: &Field,
    map: &FrameMap,
    x: Vec3,
    w: &Vec3,
    reference: Real,
) -> SolidBlock {
    let mut node = SolidBlock::default();
    let k = NodeConstants::new(x, w);
    add_solid_node::<false, true>(
        &mut node,
        &mut SolidMagnitudes::default(),
        field,
        map,
        w,
        &k,
        reference,
    );
    node
}

/// A solid's node table with its per-node constants (the engine's cached form).
#[derive(Debug, Clone)]
pub(crate) struct SolidTable {
    nodes: SurfaceNodes,
    constants: Vec<NodeConstants>,
}

impl SolidTable {
    pub(crate) fn new(nodes: SurfaceNodes) -> Self {
        let origin = nodes.origin();
        let constants = nodes
            .points()
            .iter()
            .zip(nodes.weighted_area_vectors())
            .map(|(r, w)| NodeConstants::new(r - origin, w))
            .collect();
        Self { nodes, constants }
    }
}

impl std::ops::Deref for SolidTable {
    type Target = SurfaceNodes;
    fn deref(&self) -> &SurfaceNodes {
        &self.nodes
    }
}

/// The source's fields at a block's points (`ACCELERATION`: with the acceleration, otherwise
/// the potential alone), evaluated before the block's sums through the batched
/// [`Potential::fields_into`] / [`Potential::potentials_into`]: consecutive field evaluations
/// (long chains of divisions and square roots, independent of each other) then overlap in the
/// processor, and a kind that evaluates several points together (the ellipsoid) does so.
#[inline(always)]
fn block_fields<P: Potential + ?Sized, const ACCELERATION: bool>(
    points: &[Vec3],
    source: &P,
    map: &FrameMap,
) -> [Field; BLOCK] {
    let mut fields = [Field {
        potential: 0.0,
        acceleration: Vec3::zeros(),
    }; BLOCK];
    let mut mapped = [Vec3::zeros(); BLOCK];
    let n = points.len().min(BLOCK);
    for (m, r) in mapped.iter_mut().zip(points) {
        *m = map.apply(r);
    }
    if ACCELERATION {
        source.fields_into(&mapped[..n], &mut fields[..n]);
    } else {
        let mut potentials = [0.0; BLOCK];
        source.potentials_into(&mapped[..n], &mut potentials[..n]);
        for (field, &potential) in fields.iter_mut().zip(&potentials[..n]) {
            field.potential = potential;
        }
    }
    fields
}

/// The node sums over a [`SolidTable`] ([`add_solid_node`] with the table's constants):
/// `FULL`, everything; otherwise the force parts alone, the potential form and, with `FAR`,
/// the acceleration form (the field's acceleration is then needed; otherwise only the
/// potential is evaluated).
#[inline(never)]
pub(crate) fn solid_table_sums<P: Potential + ?Sized, const FAR: bool, const FULL: bool>(
    table: &SolidTable,
    source: &P,
    map: &FrameMap,
) -> SolidSums {
    let mut totals = SolidTotals::new();
    let mut sizes = SolidMagnitudes::default();
    let reference = source.potential(&map.apply(&table.nodes.origin()));
    for ((block_points, block_weights), block_constants) in table
        .nodes
        .points()
        .chunks(BLOCK)
        .zip(table.nodes.weighted_area_vectors().chunks(BLOCK))
        .zip(table.constants.chunks(BLOCK))
    {
        let mut block = SolidBlock::default();
        let fields = if FULL || FAR {
            block_fields::<P, true>(block_points, source, map)
        } else {
            block_fields::<P, false>(block_points, source, map)
        };
        for ((w, k), field) in block_weights.iter().zip(block_constants).zip(&fields) {
            add_solid_node::<FAR, FULL>(&mut block, &mut sizes, field, map, w, k, reference);
        }
        totals.add::<FULL>(&block);
    }
    totals.finish(&sizes)
}

/// Force, torque (both forms) and energy of a homogeneous solid of density `density` whose
/// closed surface is tabulated by `nodes`, in the field of `source`; `map` takes the table's
/// frame into the source's body frame. Results are in the table's frame, torques about the
/// table's [`origin`](SurfaceNodes::origin) (the solid's centroid).
///
/// Generic over the source, so a user's own potential type gets a monomorphised loop; any
/// [`Surface`](surfgrav_surfaces::Surface) and any rule make the table. Valid when the source's matter lies
/// outside the solid (the energy needs $\nabla^2\Phi = 0$ inside it); this function does not
/// check it (the [`InteractionEngine`](super::InteractionEngine) does).
///
/// ```
/// use surfgrav_potentials::{PointMass, Potential};
/// use surfgrav_quadrature::{GaussLegendre, PeriodicTrapezoid, Rule1D};
/// use surfgrav_interaction::{integrate_over_solid, FrameMap};
/// use surfgrav_surfaces::{EllipsoidSurface, Interval, BorrowedRule, SurfaceNodes, Vec3};
///
/// // A unit sphere of mass 1 and a point mass 1 at distance 3: F = 1/9 toward it, V = −1/3.
/// let sphere = EllipsoidSurface::sphere(1.0)?;
/// let azimuth = PeriodicTrapezoid::new(32, 0.0, 1.0)?;
/// let height = GaussLegendre::new(20, -1.0, 1.0)?;
/// let table = SurfaceNodes::with_periodic_rule(
///     &sphere.azimuth_height(),
///     BorrowedRule::new(azimuth.nodes(), azimuth.weights(), Interval::UNIT)?,
///     BorrowedRule::new(height.nodes(), height.weights(), Interval::SYMMETRIC_UNIT)?,
/// )?;
/// let point = PointMass::new(1.0)?;
/// let map = FrameMap::new(&nalgebra::Rotation3::identity(), &Vec3::new(-3.0, 0.0, 0.0))?;
/// let density = 1.0 / sphere.volume();
/// let result = integrate_over_solid(&table, density, &point, &map);
/// assert!((result.force - Vec3::new(1.0 / 9.0, 0.0, 0.0)).norm() < 1e-14);
/// assert!((result.potential_energy + 1.0 / 3.0).abs() < 1e-14);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn integrate_over_solid<P: Potential + ?Sized>(
    nodes: &SurfaceNodes,
    density: Real,
    source: &P,
    map: &FrameMap,
) -> SolidIntegrals {
    solid_sums(
        nodes.points(),
        nodes.weighted_area_vectors(),
        &nodes.origin(),
        source,
        map,
    )
    .integrals(density, nodes.len())
}

/// The raw node sums over a lamina (table frame; unit normal $\hat{\mathbf n}$, centre
/// $\mathbf c$, $\mathbf x = \mathbf r - \mathbf c$, $a_n = \mathbf a\cdot\hat{\mathbf n}$).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LaminaSums {
    /// $\sum_k w_k \Phi_k \approx \iint\Phi\\,\mathrm dA$.
    pub area_potential: Real,
    /// $\sum_k w_k a\_{n,k}$.
    pub area_normal_acceleration: Real,
    /// $\sum_k w_k a\_{n,k}\\, \mathbf x_k\times\hat{\mathbf n}$.
    pub area_normal_moment: Vec3,
    /// $\sum_k w_k \mathbf a_k$ (plain area form of the force, a check).
    pub area_acceleration: Vec3,
    /// $\sum_k w_k\\, \mathbf x_k\times\mathbf a_k$ (plain area form of the torque, a check).
    pub area_moment: Vec3,
    /// $\sum_i (\Phi(\boldsymbol\rho_i) - \Phi_0)\\,\boldsymbol\nu_i \approx \oint\Phi\\,\hat{\boldsymbol\nu}\\,\mathrm dl$,
    /// $\Phi_0$ the source's potential at the centre ($\oint\hat{\boldsymbol\nu}\\,\mathrm dl = 0$).
    pub rim_potential_flux: Vec3,
    /// $\sum_k w_k |a\_{n,k}| + \sum_i |\Phi_i - \Phi_0|\\,|\boldsymbol\nu_i|$: the size of the force's terms.
    pub force_magnitude: Real,
    /// $\sum_k w_k |a\_{n,k}|\\,|\mathbf x_k|$: the size of the torque's terms.
    pub moment_magnitude: Real,
}

impl LaminaSums {
    pub(crate) fn mirrored(&self, axis: usize) -> Self {
        Self {
            area_potential: self.area_potential,
            area_normal_acceleration: self.area_normal_acceleration,
            area_normal_moment: reflect_axial(&self.area_normal_moment, axis),
            area_acceleration: reflect_polar(&self.area_acceleration, axis),
            area_moment: reflect_axial(&self.area_moment, axis),
            rim_potential_flux: reflect_polar(&self.rim_potential_flux, axis),
            ..*self
        }
    }

    pub(crate) fn plus(&self, other: &Self) -> Self {
        Self {
            area_potential: self.area_potential + other.area_potential,
            area_normal_acceleration: self.area_normal_acceleration
                + other.area_normal_acceleration,
            area_normal_moment: self.area_normal_moment + other.area_normal_moment,
            area_acceleration: self.area_acceleration + other.area_acceleration,
            area_moment: self.area_moment + other.area_moment,
            rim_potential_flux: self.rim_potential_flux + other.rim_potential_flux,
            force_magnitude: self.force_magnitude + other.force_magnitude,
            moment_magnitude: self.moment_magnitude + other.moment_magnitude,
        }
    }

    /// The physical integrals for surface density σ and unit normal $\hat{\mathbf n}$:
    /// $\mathbf F = \sigma\hat{\mathbf n}\iint a_n\\,\mathrm dA - \sigma\oint\Phi\hat{\boldsymbol\nu}\\,\mathrm dl$,
    /// $\mathbf M = \sigma\iint a_n\\,\mathbf x\times\hat{\mathbf n}\\,\mathrm dA$, $V = \sigma\iint\Phi\\,\mathrm dA$.
    pub fn integrals(
        &self,
        surface_density: Real,
        normal: &Vec3,
        evaluations: usize,
    ) -> LaminaIntegrals {
        let s = surface_density;
        LaminaIntegrals {
            force: s * (normal * self.area_normal_acceleration - self.rim_potential_flux),
            torque: s * self.area_normal_moment,
            force_area_form: s * self.area_acceleration,
            torque_area_form: s * self.area_moment,
            potential_energy: s * self.area_potential,
            evaluations,
        }
    }
}

/// Force, torque and energy of a uniform lamina in another body's field (table frame, torque
/// about the disk centre), with the plain area forms as checks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaminaIntegrals {
    /// $\sigma\hat{\mathbf n}\iint a_n\\,\mathrm dA - \sigma\oint\Phi\\,\hat{\boldsymbol\nu}\\,\mathrm dl$.
    pub force: Vec3,
    /// $\sigma\iint a_n\\,(\mathbf r-\mathbf c)\times\hat{\mathbf n}\\,\mathrm dA$.
    pub torque: Vec3,
    /// $\sigma\iint\mathbf a\\,\mathrm dA$: the same force by the area form.
    pub force_area_form: Vec3,
    /// $\sigma\iint(\mathbf r-\mathbf c)\times\mathbf a\\,\mathrm dA$: the same torque by the area form.
    pub torque_area_form: Vec3,
    /// $V = \sigma\iint\Phi\\,\mathrm dA$ (negative).
    pub potential_energy: Real,
    /// Field evaluations spent (area and rim nodes).
    pub evaluations: usize,
}

/// A block's plain sums of the lamina integrand (table frame), the components of
/// [`LaminaSums`] before compensated summation over blocks.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct LaminaBlock {
    /// $\sum_k w_k \Phi_k$.
    pub(crate) potential: Real,
    /// $\sum_k w_k a\_{n,k}$.
    pub(crate) normal_acceleration: Real,
    /// $\sum_k w_k a\_{n,k}\\, \mathbf x_k\times\hat{\mathbf n}$.
    pub(crate) normal_moment: Vec3,
    /// $\sum_k w_k \mathbf a_k$.
    pub(crate) acceleration: Vec3,
    /// $\sum_k w_k\\, \mathbf x_k\times\mathbf a_k$.
    pub(crate) moment: Vec3,
    /// $\sum_i (\Phi_i - \Phi_0)\\,\boldsymbol\nu_i$.
    pub(crate) rim_potential_flux: Vec3,
}

/// The sizes of the lamina's terms ([`LaminaSums::force_magnitude`],
/// [`LaminaSums::moment_magnitude`]), summed plainly over all nodes.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct LaminaMagnitudes {
    pub(crate) force: Real,
    pub(crate) moment: Real,
}

/// The lamina's area integrand at one node, added to a block's sums: the one place where the
/// area terms of the force (normal form and the plain area check), the torques and the energy
/// of a lamina are written (the fixed and aimed tables through [`lamina_sums`], the adaptive
/// cubature node by node). `field` is the source's field at the node (source frame; `map`
/// turns its acceleration back), `x` the node's position from the centre and `normal` the
/// unit normal $\hat{\mathbf n}$ (table frame), `w` the node's area weight.
#[inline(always)]
pub(crate) fn add_lamina_area_node(
    block: &mut LaminaBlock,
    sizes: &mut LaminaMagnitudes,
    field: &Field,
    map: &FrameMap,
    x: &Vec3,
    normal: &Vec3,
    w: Real,
) {
    let a = map.back(&field.acceleration);
    let an = a.dot(normal);
    block.potential += w * field.potential;
    block.normal_acceleration += w * an;
    block.normal_moment += x.cross(normal) * (w * an);
    block.acceleration += a * w;
    block.moment += x.cross(&a) * w;
    sizes.force += w * an.abs();
    sizes.moment += w * an.abs() * x.norm();
}

/// The lamina's rim integrand at one node, added to a block's sums: the potential `potential`
/// less the reference $\Phi_0$ (the source's potential at the centre; $\oint\hat{\boldsymbol\nu}
/// \\,\mathrm dl = 0$) times the weighted outward normal `nu` $= \boldsymbol\nu_i$.
#[inline(always)]
pub(crate) fn add_lamina_rim_node(
    block: &mut LaminaBlock,
    sizes: &mut LaminaMagnitudes,
    potential: Real,
    reference: Real,
    nu: &Vec3,
) {
    let relative = potential - reference;
    block.rim_potential_flux += nu * relative;
    // The rounding of Φ itself stays in Φ − Φ₀ (see `SolidSums::potential_magnitude`).
    sizes.force += (relative.abs() + potential.abs()) * nu.norm();
}

/// The lamina loop (table frame): the same terms as [`add_lamina_area_node`] and
/// [`add_lamina_rim_node`], each rounded the same way and added in the same order.
///
/// Each block of [`BLOCK`] nodes goes in three passes: the nodes ($\mathbf x = \mathbf r -
/// \mathbf c$ and the point in the source's frame) lane by lane over arrays, the batched field,
/// then each node's terms lane by lane over arrays (compiled with AVX where the CPU has it: no
/// FMA, so every operation rounds as in the scalar code), and only the additions into the sums
/// in node order.
#[inline(never)]
pub(crate) fn lamina_sums<P: Potential + ?Sized>(
    nodes: &LaminaNodes,
    source: &P,
    map: &FrameMap,
) -> LaminaSums {
    #[cfg(target_arch = "x86_64")]
    let avx = std::arch::is_x86_feature_detected!("avx");
    #[cfg(not(target_arch = "x86_64"))]
    let avx = false;
    lamina_sums_lanes(nodes, source, map, avx)
}

/// [`lamina_sums`] with the lane passes compiled with AVX (`avx`, which the CPU must then
/// support) or without.
#[inline(always)]
fn lamina_sums_lanes<P: Potential + ?Sized>(
    nodes: &LaminaNodes,
    source: &P,
    map: &FrameMap,
    avx: bool,
) -> LaminaSums {
    let c = nodes.centre();
    let mut lanes = LaminaLanes::new(*map, c, nodes.normal());
    // Potential, normal acceleration, normal moment x, y, z, acceleration x, y, z, moment x,
    // y, z: the compensated sums side by side (`Neumaier`, the bits of `CompensatedSum`).
    let mut area = Neumaier::<11>::new();
    let mut sizes = LaminaMagnitudes::default();
    let mut fields = [Field {
        potential: 0.0,
        acceleration: Vec3::zeros(),
    }; BLOCK];
    for (block_points, block_weights) in nodes
        .area_points()
        .chunks(BLOCK)
        .zip(nodes.area_weights().chunks(BLOCK))
    {
        let n = block_points.len().min(block_weights.len());
        if avx {
            // SAFETY: `avx` only where AVX was detected on this CPU (std caches the answer).
            #[cfg(target_arch = "x86_64")]
            unsafe {
                lanes.area_nodes_avx(block_points, block_weights)
            };
        } else {
            lanes.area_nodes(block_points, block_weights);
        }
        source.fields_into(&lanes.mapped[..n], &mut fields[..n]);
        if avx {
            // SAFETY: as above.
            #[cfg(target_arch = "x86_64")]
            unsafe {
                lanes.area_terms_avx(&fields)
            };
        } else {
            lanes.area_terms(&fields);
        }
        let block = lanes.area_sum(&mut sizes, n);
        let (n, a, m) = (&block.normal_moment, &block.acceleration, &block.moment);
        area.add(&[
            block.potential,
            block.normal_acceleration,
            n.x,
            n.y,
            n.z,
            a.x,
            a.y,
            a.z,
            m.x,
            m.y,
            m.z,
        ]);
    }
    let mut rim = CompensatedSum3::new();
    // ∮ ν̂ dl = 0 around the rim: the potential at the centre comes out of the rim sum.
    let reference = source.potential(&map.apply(&c));
    let mut potentials = [0.0; BLOCK];
    for (block_points, block_normals) in nodes
        .rim_points()
        .chunks(BLOCK)
        .zip(nodes.rim_weighted_normals().chunks(BLOCK))
    {
        let n = block_points.len().min(block_normals.len());
        lanes.rim_nodes(block_points);
        source.potentials_into(&lanes.mapped[..n], &mut potentials[..n]);
        let mut block = LaminaBlock::default();
        for (&phi, nu) in potentials[..n].iter().zip(block_normals) {
            add_lamina_rim_node(&mut block, &mut sizes, phi, reference, nu);
        }
        rim.add(&block.rim_potential_flux);
    }
    LaminaSums {
        area_potential: area.value(0),
        area_normal_acceleration: area.value(1),
        area_normal_moment: area.vector(2),
        area_acceleration: area.vector(5),
        area_moment: area.vector(8),
        rim_potential_flux: rim.value(),
        force_magnitude: sizes.force,
        moment_magnitude: sizes.moment,
    }
}

/// One block of [`lamina_sums`] by component (struct of arrays): the nodes' positions
/// $\mathbf x$ from the centre, weights, points in the source's frame and terms.
#[derive(Debug, Clone, Copy)]
struct LaminaLanes {
    map: FrameMap,
    centre: Vec3,
    normal: Vec3,
    x: [[Real; BLOCK]; 3],
    w: [Real; BLOCK],
    mapped: [Vec3; BLOCK],
    potential: [Real; BLOCK],
    normal_acceleration: [Real; BLOCK],
    normal_moment: [[Real; BLOCK]; 3],
    acceleration: [[Real; BLOCK]; 3],
    moment: [[Real; BLOCK]; 3],
    size_force: [Real; BLOCK],
    size_moment: [Real; BLOCK],
}

impl LaminaLanes {
    fn new(map: FrameMap, centre: Vec3, normal: Vec3) -> Self {
        let zero = [0.0; BLOCK];
        Self {
            map,
            centre,
            normal,
            x: [zero; 3],
            w: zero,
            mapped: [Vec3::zeros(); BLOCK],
            potential: zero,
            normal_acceleration: zero,
            normal_moment: [zero; 3],
            acceleration: [zero; 3],
            moment: [zero; 3],
            size_force: zero,
            size_moment: zero,
        }
    }

    /// The block's area nodes (at most [`BLOCK`]): $\mathbf x = \mathbf r - \mathbf c$, the
    /// weight and $M\mathbf r + \mathbf t$ ([`FrameMap::apply`], the same operations).
    #[inline(always)]
    fn area_nodes(&mut self, points: &[Vec3], weights: &[Real]) {
        let c = &self.centre;
        for (k, (r, &w)) in points.iter().zip(weights).take(BLOCK).enumerate() {
            let (px, py, pz) = (r.x, r.y, r.z);
            self.x[0][k] = px - c.x;
            self.x[1][k] = py - c.y;
            self.x[2][k] = pz - c.z;
            self.w[k] = w;
            self.mapped[k] = self.map.apply_components(px, py, pz);
        }
    }

    /// [`LaminaLanes::area_nodes`] compiled with AVX.
    ///
    /// # Safety
    ///
    /// The CPU must support AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    unsafe fn area_nodes_avx(&mut self, points: &[Vec3], weights: &[Real]) {
        self.area_nodes(points, weights);
    }

    /// The block's rim points in the source's frame ([`FrameMap::apply`]).
    #[inline(always)]
    fn rim_nodes(&mut self, points: &[Vec3]) {
        for (mapped, r) in self.mapped.iter_mut().zip(points) {
            *mapped = self.map.apply(r);
        }
    }

    /// Each area node's terms (those of [`add_lamina_area_node`], the same operations in the
    /// same order), from the block's fields; every lane, the ones past the block's end too
    /// (never summed).
    #[inline(always)]
    fn area_terms(&mut self, fields: &[Field; BLOCK]) {
        let m = &self.map.rotation;
        let (nx, ny, nz) = (self.normal.x, self.normal.y, self.normal.z);
        for (k, field) in fields.iter().enumerate() {
            let (xx, xy, xz) = (self.x[0][k], self.x[1][k], self.x[2][k]);
            let w = self.w[k];
            // a = Mᵀ g: the acceleration in the table frame (`FrameMap::back`).
            let g = &field.acceleration;
            let ax = m[(0, 0)] * g.x + m[(1, 0)] * g.y + m[(2, 0)] * g.z;
            let ay = m[(0, 1)] * g.x + m[(1, 1)] * g.y + m[(2, 1)] * g.z;
            let az = m[(0, 2)] * g.x + m[(1, 2)] * g.y + m[(2, 2)] * g.z;
            let an = ax * nx + ay * ny + az * nz;
            let w_an = w * an;
            self.potential[k] = w * field.potential;
            self.normal_acceleration[k] = w_an;
            // x × n̂, then x × a.
            self.normal_moment[0][k] = (xy * nz - xz * ny) * w_an;
            self.normal_moment[1][k] = (xz * nx - xx * nz) * w_an;
            self.normal_moment[2][k] = (xx * ny - xy * nx) * w_an;
            self.acceleration[0][k] = ax * w;
            self.acceleration[1][k] = ay * w;
            self.acceleration[2][k] = az * w;
            self.moment[0][k] = (xy * az - xz * ay) * w;
            self.moment[1][k] = (xz * ax - xx * az) * w;
            self.moment[2][k] = (xx * ay - xy * ax) * w;
            let w_abs_an = w * an.abs();
            self.size_force[k] = w_abs_an;
            self.size_moment[k] = w_abs_an * (xx * xx + xy * xy + xz * xz).sqrt();
        }
    }

    /// [`LaminaLanes::area_terms`] compiled with AVX.
    ///
    /// # Safety
    ///
    /// The CPU must support AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    unsafe fn area_terms_avx(&mut self, fields: &[Field; BLOCK]) {
        self.area_terms(fields);
    }

    /// The first `n` area nodes' terms added in node order: the block's sums, and the
    /// magnitudes into `sizes`.
    #[inline(always)]
    fn area_sum(&self, sizes: &mut LaminaMagnitudes, n: usize) -> LaminaBlock {
        let mut block = LaminaBlock::default();
        let lane = |v: &[[Real; BLOCK]; 3], k: usize| Vec3::new(v[0][k], v[1][k], v[2][k]);
        for k in 0..n.min(BLOCK) {
            block.potential += self.potential[k];
            block.normal_acceleration += self.normal_acceleration[k];
            block.normal_moment += lane(&self.normal_moment, k);
            block.acceleration += lane(&self.acceleration, k);
            block.moment += lane(&self.moment, k);
            sizes.force += self.size_force[k];
            sizes.moment += self.size_moment[k];
        }
        block
    }
}

/// Force, torque and energy of a uniform lamina of surface density `surface_density`
/// tabulated by `nodes`, in the field of `source` (see [`integrate_over_solid`] for `map` and
/// the frames). Valid when the source does not touch the lamina.
pub fn integrate_over_lamina<P: Potential + ?Sized>(
    nodes: &LaminaNodes,
    surface_density: Real,
    source: &P,
    map: &FrameMap,
) -> LaminaIntegrals {
    lamina_sums(nodes, source, map).integrals(
        surface_density,
        &nodes.normal(),
        nodes.area_points().len() + nodes.rim_points().len(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use surfgrav_potentials::{Pose, Spheroid};
    use surfgrav_quadrature::{GaussLegendre, PeriodicTrapezoid, Rule1D};
    use surfgrav_surfaces::sum::CompensatedSum;
    use surfgrav_surfaces::{BorrowedRule, EllipsoidSurface, Interval};

    /// A deterministic pseudo-random number in [-1, 1).
    fn next(state: &mut u64) -> Real {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*state >> 11) as Real / (1u64 << 53) as Real) * 2.0 - 1.0
    }

    fn vector(state: &mut u64) -> Vec3 {
        Vec3::new(next(state), next(state), next(state))
    }

    /// The one integrand ([`solid_node`], i.e. [`add_solid_node`]) against the formulas of
    /// the module docs written out directly: force $\mathbf W(\Phi - \Phi_0)$, torque
    /// $(\Phi - \Phi_0)\\,\mathbf x\times\mathbf W$, second torque $\tfrac12|\mathbf x|^2\\,\mathbf W\times\mathbf a$,
    /// energy $(\Phi\mathbf x + \tfrac12|\mathbf x|^2\mathbf a)\cdot\mathbf W$, with $\mathbf a$ turned
    /// back into the table frame. Tolerance: each term is a product of at most four factors
    /// or a sum of three, so the two orders of evaluation differ by at most
    /// [`ROUNDING_PER_TERM`](super::super::ROUNDING_PER_TERM), $4\epsilon$, of the sum of the
    /// terms' magnitudes.
    #[test]
    fn the_node_integrand_is_the_documented_formula() {
        let mut state = 12u64;
        for _ in 0..1000 {
            let pose = Pose::new(vector(&mut state) * 3.0, vector(&mut state));
            let map = FrameMap::between(&pose, &Pose::identity()).unwrap();
            let x = vector(&mut state);
            let w = vector(&mut state) * 0.1;
            let field = Field {
                potential: -1.0 + 0.5 * next(&mut state),
                acceleration: vector(&mut state),
            };
            let reference = -1.0 + 0.5 * next(&mut state);
            let node = solid_node(&field, &map, x, &w, reference);
            let phi = field.potential;
            let a = map.rotation.transpose() * field.acceleration;
            let half_x2 = 0.5 * x.norm_squared();
            let bound = 4.0 * Real::EPSILON;
            let close = |got: &Vec3, want: &Vec3, size: Real| {
                (got - want).norm() <= bound * size.max(Real::MIN_POSITIVE)
            };
            let relative = phi - reference;
            assert!(close(
                &node.flux,
                &(w * relative),
                w.norm() * relative.abs()
            ));
            let moment = x.cross(&w) * relative;
            assert!(close(
                &node.moment,
                &moment,
                x.norm() * w.norm() * relative.abs()
            ));
            let gradient = w.cross(&a) * half_x2;
            let size = w.norm() * a.norm() * half_x2;
            assert!(close(&node.gradient_moment, &gradient, size));
            let energy = (x * phi + a * half_x2).dot(&w);
            let size = (x.norm() * phi.abs() + a.norm() * half_x2) * w.norm();
            assert!((node.energy - energy).abs() <= bound * size);
            assert_eq!(node.acceleration_flux, Vec3::zeros());
        }
    }

    /// [`integrate_over_solid`]'s loop (constants computed per node) and the engine's cached
    /// table loop ([`solid_table_sums`]) run the same integrand over the same nodes: every sum
    /// and every magnitude agrees bit for bit.
    #[test]
    fn the_generic_loop_equals_the_table_loop_bit_for_bit() {
        let surface = EllipsoidSurface::spheroid(1.0, 0.25).unwrap();
        let azimuth = PeriodicTrapezoid::new(37, 0.0, 1.0).unwrap();
        let height = GaussLegendre::new(21, -1.0, 1.0).unwrap();
        let nodes = SurfaceNodes::with_periodic_rule(
            &surface.azimuth_height(),
            BorrowedRule::new(azimuth.nodes(), azimuth.weights(), Interval::UNIT).unwrap(),
            BorrowedRule::new(height.nodes(), height.weights(), Interval::SYMMETRIC_UNIT).unwrap(),
        )
        .unwrap();
        let source = Spheroid::new(0.8, 0.5, 1.3).unwrap();
        let pose = Pose::new(Vec3::new(2.2, 0.4, -0.3), Vec3::new(0.2, -0.5, 0.3));
        let map = FrameMap::between(&Pose::identity(), &pose).unwrap();
        let generic = solid_sums(
            nodes.points(),
            nodes.weighted_area_vectors(),
            &nodes.origin(),
            &source,
            &map,
        );
        let table = solid_table_sums::<_, false, true>(&SolidTable::new(nodes), &source, &map);
        assert_eq!(generic, table);
        assert!(generic.energy_flux < 0.0 && generic.potential_moment_magnitude > 0.0);
    }

    /// The lamina loop node by node through [`add_lamina_area_node`] and
    /// [`add_lamina_rim_node`] (the form before the loop went by arrays): the reference for
    /// the bit-for-bit test.
    fn lamina_node_by_node<P: Potential + ?Sized>(
        nodes: &LaminaNodes,
        source: &P,
        map: &FrameMap,
    ) -> LaminaSums {
        let (n, c) = (nodes.normal(), nodes.centre());
        let mut potential = CompensatedSum::new();
        let mut normal_acc = CompensatedSum::new();
        let mut normal_moment = CompensatedSum3::new();
        let mut acc = CompensatedSum3::new();
        let mut moment = CompensatedSum3::new();
        let mut sizes = LaminaMagnitudes::default();
        for (points, weights) in nodes
            .area_points()
            .chunks(BLOCK)
            .zip(nodes.area_weights().chunks(BLOCK))
        {
            let mut block = LaminaBlock::default();
            for (r, &w) in points.iter().zip(weights) {
                let field = source.field(&map.apply(r));
                add_lamina_area_node(&mut block, &mut sizes, &field, map, &(r - c), &n, w);
            }
            potential.add(block.potential);
            normal_acc.add(block.normal_acceleration);
            normal_moment.add(&block.normal_moment);
            acc.add(&block.acceleration);
            moment.add(&block.moment);
        }
        let mut rim = CompensatedSum3::new();
        let reference = source.potential(&map.apply(&c));
        for (points, normals) in nodes
            .rim_points()
            .chunks(BLOCK)
            .zip(nodes.rim_weighted_normals().chunks(BLOCK))
        {
            let mut block = LaminaBlock::default();
            for (r, nu) in points.iter().zip(normals) {
                let phi = source.potential(&map.apply(r));
                add_lamina_rim_node(&mut block, &mut sizes, phi, reference, nu);
            }
            rim.add(&block.rim_potential_flux);
        }
        LaminaSums {
            area_potential: potential.value(),
            area_normal_acceleration: normal_acc.value(),
            area_normal_moment: normal_moment.value(),
            area_acceleration: acc.value(),
            area_moment: moment.value(),
            rim_potential_flux: rim.value(),
            force_magnitude: sizes.force,
            moment_magnitude: sizes.moment,
        }
    }

    fn lamina_bits(s: &LaminaSums) -> Vec<u64> {
        let vectors = [
            s.area_normal_moment,
            s.area_acceleration,
            s.area_moment,
            s.rim_potential_flux,
        ];
        let scalars = [
            s.area_potential,
            s.area_normal_acceleration,
            s.force_magnitude,
            s.moment_magnitude,
        ];
        vectors
            .iter()
            .flat_map(|v| v.iter().copied().collect::<Vec<_>>())
            .chain(scalars)
            .map(Real::to_bits)
            .collect()
    }

    /// The array form of [`lamina_sums`] (with and without AVX) equals the node-by-node form
    /// bit for bit (every sum and magnitude), on random tables (random radii, angles and
    /// weights, rows of different lengths so that blocks are full and partial, turned and
    /// moved so that the centre and normal are general) in random poses of an ellipsoid
    /// (batched field), a uniform disk (batched field) and a point mass.
    #[test]
    fn the_lamina_array_loop_equals_the_node_loop_bit_for_bit() {
        use surfgrav_potentials::{Ellipsoid, PointMass, UniformDisk};
        use surfgrav_surfaces::lamina::Lamina;
        let mut state = 29u64;
        let ellipsoid = Ellipsoid::new(1.1, 0.7, 0.4, 2.0).unwrap();
        let disk = UniformDisk::new(0.9, 1.3).unwrap();
        let point = PointMass::new(1.5).unwrap();
        let sources: [&dyn Potential; 3] = [&ellipsoid, &disk, &point];
        #[cfg(target_arch = "x86_64")]
        let avx = std::arch::is_x86_feature_detected!("avx");
        #[cfg(not(target_arch = "x86_64"))]
        let avx = false;
        let mut compared = 0;
        for case in 0..40 {
            let lamina = Lamina::new(0.5 + next(&mut state).abs()).unwrap();
            let radius = lamina.radius();
            let angles: Vec<(Real, Real, Real)> = (0..23)
                .map(|_| {
                    let phi = 4.0 * next(&mut state);
                    (phi.cos(), phi.sin(), 0.3 + next(&mut state).abs())
                })
                .collect();
            // Rows of 0 to 22 angles: 16 n + 7 nodes in all for case 0, otherwise random.
            let rows: Vec<(Real, Real, std::ops::Range<usize>)> = (0..1 + case % 7)
                .map(|j| {
                    let a = (16.0 * next(&mut state).abs()) as usize;
                    let len = if case == 0 {
                        16 + 7 * (j == 0) as usize
                    } else {
                        (7.0 * next(&mut state).abs()) as usize
                    };
                    (
                        radius * next(&mut state).abs(),
                        0.1 + next(&mut state).abs(),
                        a..a + len,
                    )
                })
                .collect();
            let rim: Vec<(Real, Real, Real)> = (0..(case % 37))
                .map(|_| {
                    let phi = 4.0 * next(&mut state);
                    (phi.cos(), phi.sin(), 0.2 + next(&mut state).abs())
                })
                .collect();
            let mut body = LaminaNodes::default();
            lamina.fill_rows(&angles, &rows, &rim, &mut body);
            let turn = Rotation3::new(vector(&mut state) * 2.0);
            let nodes = body.transformed(&turn, &vector(&mut state)).unwrap();
            let pose = Pose::new(
                vector(&mut state) * 2.0 + Vec3::new(3.0, 0.0, 0.0),
                vector(&mut state),
            );
            let map = FrameMap::between(&Pose::identity(), &pose).unwrap();
            for source in sources {
                let reference = lamina_node_by_node(&nodes, source, &map);
                let plain = lamina_sums_lanes(&nodes, source, &map, false);
                let chosen = lamina_sums(&nodes, source, &map);
                assert_eq!(lamina_bits(&plain), lamina_bits(&reference), "case {case}");
                assert_eq!(
                    lamina_bits(&chosen),
                    lamina_bits(&reference),
                    "case {case}, avx {avx}"
                );
                assert!(reference.force_magnitude.is_finite());
                compared += usize::from(!nodes.area_points().is_empty());
            }
        }
        assert!(compared > 100);
    }

    /// [`SolidTotals`] (side by side, a selection for Neumaier's branch) equals
    /// [`CompensatedSum`] bit for bit: blocks of magnitudes from 1e-20 to 1e20 and both signs,
    /// so that both corrections are taken and large terms cancel; it fails when the selection
    /// keeps the wrong correction.
    #[test]
    fn the_totals_are_the_compensated_sums_bit_for_bit() {
        let mut state = 17;
        let mut totals = SolidTotals::new();
        let mut reference = [CompensatedSum::new(); 13];
        let term = |state: &mut u64| next(state) * Real::powi(10.0, (next(state) * 20.0) as i32);
        for _ in 0..2_000 {
            let block = SolidBlock {
                flux: Vec3::new(term(&mut state), term(&mut state), term(&mut state)),
                moment: Vec3::new(term(&mut state), term(&mut state), term(&mut state)),
                gradient_moment: Vec3::new(term(&mut state), term(&mut state), term(&mut state)),
                energy: term(&mut state),
                acceleration_flux: Vec3::new(term(&mut state), term(&mut state), term(&mut state)),
            };
            totals.add::<true>(&block);
            let parts = [
                block.flux.as_slice(),
                block.moment.as_slice(),
                block.gradient_moment.as_slice(),
                &[block.energy],
                block.acceleration_flux.as_slice(),
            ];
            for (sum, &x) in reference
                .iter_mut()
                .zip(parts.iter().flat_map(|p| p.iter()))
            {
                sum.add(x);
            }
        }
        let s = totals.finish(&SolidMagnitudes::default());
        let values = [
            s.potential_flux.as_slice(),
            s.potential_moment.as_slice(),
            s.gradient_moment.as_slice(),
            &[s.energy_flux],
            s.acceleration_flux.as_slice(),
        ];
        for (sum, &value) in reference.iter().zip(values.iter().flat_map(|p| p.iter())) {
            assert_eq!(sum.value().to_bits(), value.to_bits());
        }
    }
}
