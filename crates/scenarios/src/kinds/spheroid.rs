//! A homogeneous spheroid, symmetry axis along body z: `spheroid:equatorial=A,polar=C,mass=M`;
//! `shape = "spheroid"`, `equatorial_radius = A`, `polar_radius = C`.

use surfgrav_potentials::{Real, Spheroid};

use super::{body_error, Key, KeyError, Kind, ValueKind, Values};
use crate::spec::{Amount, BuiltBody, Spec, SpecError};

/// The spheroid.
pub(super) static KIND: Kind = Kind {
    name: "spheroid",
    keys: &[
        Key {
            scene: "equatorial_radius",
            cli: &["equatorial"],
            value: ValueKind::Length,
            required: true,
        },
        Key {
            scene: "polar_radius",
            cli: &["polar"],
            value: ValueKind::Length,
            required: true,
        },
    ],
    solid: true,
    check: no_check,
    build,
    semi_axes: |s| match s.values.lengths()[..] {
        [a, c] => Some([a, a, c]),
        _ => None,
    },
};

fn no_check(_: &Values) -> Result<(), KeyError> {
    Ok(())
}

fn build(spec: &Spec, g: Real) -> Result<BuiltBody, SpecError> {
    let d = spec.values.lengths();
    match spec.amount {
        Amount::Mass(m) => Spheroid::new(d[0], d[1], m),
        Amount::Density(rho) => Spheroid::with_density(d[0], d[1], rho),
    }
    .and_then(|b| b.with_gravitational_constant(g))
    .map(BuiltBody::Spheroid)
    .map_err(body_error(&KIND))
}
