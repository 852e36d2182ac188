//! The `surfgrav` command line.
//!
//! Every command prints its result as JSON on stdout. Bad input gives one line on stderr
//! starting with `error:`, nothing on stdout, and exit code 2 (see [`run`]).

use clap::{Parser, Subcommand};
use serde::Serialize;

use surfgrav_potentials::{Pose, Vec3};
use surfgrav_surfaces::interaction::{InteractionEngine, InteractionOptions};

use crate::spec::{parse_positive, parse_vector, BodySpec};

/// Exact gravitational interaction of extended rigid bodies.
#[derive(Debug, Parser)]
#[command(name = "surfgrav", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The commands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Potential and acceleration of one body at a point of its own frame.
    ///
    /// Prints {"potential": Φ, "acceleration": [ax, ay, az]} with Φ = −G∫ρ dV/|r − r'| (negative)
    /// and a = −∇Φ (toward the body). The body's centroid is at the origin, its symmetry axis
    /// (c axis) along z; a disk lies in the x–y plane.
    Potential {
        /// The body: point:mass=M | sphere:radius=R,mass=M | spheroid:equatorial=A,polar=C,mass=M
        /// | ellipsoid:a=A,b=B,c=C,mass=M | disk:radius=R,mass=M (density=D may replace mass=M
        /// for solids).
        #[arg(long, value_name = "SPEC")]
        body: String,
        /// The field point X,Y,Z in the body frame.
        #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
        at: String,
        /// The gravitational constant.
        #[arg(
            long,
            value_name = "G",
            default_value = "1",
            allow_hyphen_values = true
        )]
        g: String,
    },
    /// Force, torque and mutual potential energy of two bodies (Conway's surface integrals).
    ///
    /// A's centroid is at the origin and B's at --position, in the world frame. An orientation
    /// is a rotation vector (axis times angle in radians) taking the body frame to the world
    /// frame. Torques are about each body's own centroid; the energy is negative. Prints
    /// force_on_a, force_on_b, torque_on_a, torque_on_b, potential_energy, method, evaluations
    /// and error_estimate (relative) as one JSON object.
    Interact {
        /// Body A (same SPEC syntax as `potential --body`).
        #[arg(long = "a", value_name = "SPEC")]
        body_a: String,
        /// Body B.
        #[arg(long = "b", value_name = "SPEC")]
        body_b: String,
        /// B's centroid X,Y,Z in the world frame (A's centroid is at the origin).
        #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
        position: String,
        /// A's orientation as a rotation vector RX,RY,RZ (radians).
        #[arg(
            long,
            value_name = "RX,RY,RZ",
            default_value = "0,0,0",
            allow_hyphen_values = true
        )]
        orientation_a: String,
        /// B's orientation as a rotation vector RX,RY,RZ (radians).
        #[arg(
            long,
            value_name = "RX,RY,RZ",
            default_value = "0,0,0",
            allow_hyphen_values = true
        )]
        orientation_b: String,
        /// Requested relative accuracy of every output.
        #[arg(
            long,
            value_name = "T",
            default_value = "1e-12",
            allow_hyphen_values = true
        )]
        tolerance: String,
        /// The gravitational constant.
        #[arg(
            long,
            value_name = "G",
            default_value = "1",
            allow_hyphen_values = true
        )]
        g: String,
    },
}

/// A user error: printed as one line, exit code 2.
#[derive(Debug)]
pub struct UserError(pub String);

impl<E: std::error::Error> From<E> for UserError {
    fn from(e: E) -> Self {
        UserError(e.to_string())
    }
}

#[derive(Serialize)]
struct PotentialOutput {
    potential: f64,
    acceleration: [f64; 3],
}

#[derive(Serialize)]
struct InteractOutput {
    force_on_a: [f64; 3],
    force_on_b: [f64; 3],
    torque_on_a: [f64; 3],
    torque_on_b: [f64; 3],
    potential_energy: f64,
    method: &'static str,
    evaluations: usize,
    error_estimate: f64,
}

/// Runs one parsed command, returning the JSON text to print.
pub fn run(cli: Cli) -> Result<String, UserError> {
    match cli.command {
        Command::Potential { body, at, g } => {
            let g = parse_positive("--g", &g).map_err(UserError)?;
            let spec: BodySpec = body.parse()?;
            let body = spec.build(g)?.into_potential();
            let r = parse_vector("--at", &at)?;
            let field = body.field(&r);
            let out = PotentialOutput {
                potential: field.potential,
                acceleration: field.acceleration.into(),
            };
            if !out.potential.is_finite() || out.acceleration.iter().any(|a| !a.is_finite()) {
                return Err(UserError(if body.bounding_radius() == 0.0 {
                    "--at is the position of the point mass, where its potential is infinite"
                        .to_string()
                } else {
                    format!("the field at --at {at} is not finite for this body")
                }));
            }
            Ok(serde_json::to_string(&out).map_err(|e| UserError(e.to_string()))?)
        }
        Command::Interact {
            body_a,
            body_b,
            position,
            orientation_a,
            orientation_b,
            tolerance,
            g,
        } => {
            let g = parse_positive("--g", &g).map_err(UserError)?;
            let tolerance = parse_positive("--tolerance", &tolerance).map_err(UserError)?;
            let a = body_a
                .parse::<BodySpec>()
                .and_then(|s| s.build(g))
                .map_err(|e| UserError(format!("--a: {e}")))?
                .into_interaction_body()
                .map_err(|e| UserError(format!("--a: {e}")))?;
            let b = body_b
                .parse::<BodySpec>()
                .and_then(|s| s.build(g))
                .map_err(|e| UserError(format!("--b: {e}")))?
                .into_interaction_body()
                .map_err(|e| UserError(format!("--b: {e}")))?;
            let pose_a = Pose::new(
                Vec3::zeros(),
                parse_vector("--orientation-a", &orientation_a)?,
            );
            let pose_b = Pose::new(
                parse_vector("--position", &position)?,
                parse_vector("--orientation-b", &orientation_b)?,
            );
            let mut engine = InteractionEngine::new(InteractionOptions {
                relative_tolerance: tolerance,
                ..InteractionOptions::default()
            })?;
            let r = engine.interact(&a, &pose_a, &b, &pose_b)?;
            let out = InteractOutput {
                force_on_a: r.force_on_a.into(),
                force_on_b: r.force_on_b.into(),
                torque_on_a: r.torque_on_a.into(),
                torque_on_b: r.torque_on_b.into(),
                potential_energy: r.potential_energy,
                method: r.method.name(),
                evaluations: r.evaluations,
                error_estimate: r.error_estimate,
            };
            Ok(serde_json::to_string(&out).map_err(|e| UserError(e.to_string()))?)
        }
    }
}
