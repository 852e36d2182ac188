//! Times the lamina node loop (`integrate_over_lamina`) on a disk table of 32 × 40 area nodes
//! and 64 rim nodes, in the field of a point mass (the loop's own cost shows) and of a uniform
//! disk near contact (the field's cost dominates):
//! `cargo run --release -p surfgrav-interaction --example lamina_loop -- [SECONDS]`.
//! Prints the time per node (best of five runs) and a checksum of the sums.

use std::time::Instant;
use surfgrav_interaction::{integrate_over_lamina, FrameMap};
use surfgrav_potentials::{PointMass, Potential, UniformDisk};
use surfgrav_quadrature::{GaussLegendre, PeriodicTrapezoid, Rule1D};
use surfgrav_surfaces::{BorrowedRule, Interval, Lamina, LaminaNodes, Vec3};

fn time<P: Potential>(name: &str, nodes: &LaminaNodes, source: &P, map: &FrameMap, seconds: f64) {
    let count = nodes.area_points().len() + nodes.rim_points().len();
    let mut best = f64::INFINITY;
    let mut checksum = 0.0;
    for _ in 0..5 {
        let start = Instant::now();
        let mut calls = 0u64;
        while start.elapsed().as_secs_f64() < seconds / 5.0 {
            for _ in 0..8 {
                let r = integrate_over_lamina(std::hint::black_box(nodes), 1.0, source, map);
                checksum = r.force.x + r.torque.y + r.potential_energy;
            }
            calls += 8;
        }
        best = best.min(start.elapsed().as_secs_f64() / (calls * count as u64) as f64);
    }
    println!(
        "{name}: {count} nodes, {:.2} ns per node (best of 5), checksum {checksum:.17e}",
        best * 1e9
    );
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let seconds: f64 = std::env::args().nth(1).map_or(Ok(2.0), |s| s.parse())?;
    let lamina = Lamina::new(1.0)?;
    let angle = PeriodicTrapezoid::new(40, 0.0, 1.0)?;
    let radial = GaussLegendre::new(32, -1.0, 1.0)?;
    let rim = PeriodicTrapezoid::new(64, 0.0, 1.0)?;
    let nodes = lamina.nodes(
        BorrowedRule::new(angle.nodes(), angle.weights(), Interval::UNIT)?,
        BorrowedRule::new(radial.nodes(), radial.weights(), Interval::SYMMETRIC_UNIT)?,
        BorrowedRule::new(rim.nodes(), rim.weights(), Interval::UNIT)?,
    )?;
    let turn = nalgebra::Rotation3::new(nalgebra::Vector3::new(0.4, -0.3, 0.2));
    let map = FrameMap::new(&turn, &Vec3::new(0.3, -0.2, 1.05))?;
    time("point mass", &nodes, &PointMass::new(1.0)?, &map, seconds);
    time(
        "uniform disk",
        &nodes,
        &UniformDisk::new(1.0, 1.0)?,
        &map,
        seconds,
    );
    Ok(())
}
