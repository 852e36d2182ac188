//! The `surfgrav` command line.
//!
//! Every command prints its result as JSON on stdout. Bad input gives one line on stderr
//! starting with `error:`, nothing on stdout, and exit code 2 (see [`run`]).

use clap::{Parser, Subcommand};
use serde::Serialize;

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

/// Runs one parsed command, returning the JSON text to print.
pub fn run(cli: Cli) -> Result<String, UserError> {
    match cli.command {
        Command::Potential { body, at, g } => {
            let g = parse_positive("--g", &g).map_err(UserError)?;
            let spec: BodySpec = body.parse()?;
            let body = spec.build(g)?;
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
    }
}
