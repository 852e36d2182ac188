//! A homogeneous triaxial ellipsoid, semi-axes along body x, y, z: `ellipsoid:a=..,b=..,c=..,
//! mass=M`; `shape = "ellipsoid"`, `semi_axes = [a, b, c]`.

use surfgrav_potentials::{Ellipsoid, Real};

use super::{body_error, Key, KeyError, Kind, ValueKind, Values};
use crate::spec::{Amount, BuiltBody, Spec, SpecError};

/// The ellipsoid.
pub(super) static KIND: Kind = Kind {
    name: "ellipsoid",
    keys: &[Key {
        scene: "semi_axes",
        cli: &["a", "b", "c"],
        value: ValueKind::Lengths,
        required: true,
    }],
    solid: true,
    check: no_check,
    build,
    semi_axes: |s| match s.values.lengths()[..] {
        [a, b, c] => Some([a, b, c]),
        _ => None,
    },
};

fn no_check(_: &Values) -> Result<(), KeyError> {
    Ok(())
}

fn build(spec: &Spec, g: Real) -> Result<BuiltBody, SpecError> {
    let d = spec.values.lengths();
    match spec.amount {
        Amount::Mass(m) => Ellipsoid::new(d[0], d[1], d[2], m),
        Amount::Density(rho) => Ellipsoid::with_density(d[0], d[1], d[2], rho),
    }
    .and_then(|b| b.with_gravitational_constant(g))
    .map(BuiltBody::Ellipsoid)
    .map_err(body_error(&KIND))
}
