//! A point mass: `point:mass=M`; `shape = "point"`.

use surfgrav_potentials::{PointMass, Real};

use super::{body_error, KeyError, Kind, Values};
use crate::spec::{Amount, BuiltBody, Spec, SpecError};

/// The point mass.
pub(super) static KIND: Kind = Kind {
    name: "point",
    keys: &[],
    solid: false,
    check: no_check,
    build,
    semi_axes: |_| None,
};

fn no_check(_: &Values) -> Result<(), KeyError> {
    Ok(())
}

fn build(spec: &Spec, g: Real) -> Result<BuiltBody, SpecError> {
    let Amount::Mass(m) = spec.amount else {
        return Err(spec.density_refused());
    };
    PointMass::new(m)
        .and_then(|b| b.with_gravitational_constant(g))
        .map(BuiltBody::Point)
        .map_err(body_error(&KIND))
}
