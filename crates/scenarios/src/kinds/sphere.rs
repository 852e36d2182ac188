//! A homogeneous sphere: `sphere:radius=R,mass=M`; `shape = "sphere"`, `radius = R`.

use surfgrav_potentials::{Real, Sphere};

use super::{body_error, Key, KeyError, Kind, ValueKind, Values};
use crate::spec::{Amount, BuiltBody, Spec, SpecError};

/// The sphere.
pub(super) static KIND: Kind = Kind {
    name: "sphere",
    keys: &[Key {
        scene: "radius",
        cli: &["radius"],
        value: ValueKind::Length,
        required: true,
    }],
    solid: true,
    check: no_check,
    build,
    semi_axes: |s| s.values.lengths().first().map(|&r| [r; 3]),
};

fn no_check(_: &Values) -> Result<(), KeyError> {
    Ok(())
}

fn build(spec: &Spec, g: Real) -> Result<BuiltBody, SpecError> {
    let d = spec.values.lengths();
    match spec.amount {
        Amount::Mass(m) => Sphere::new(d[0], m),
        Amount::Density(rho) => Sphere::with_density(d[0], rho),
    }
    .and_then(|b| b.with_gravitational_constant(g))
    .map(BuiltBody::Sphere)
    .map_err(body_error(&KIND))
}
