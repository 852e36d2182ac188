//! A uniform thin disk in the body x–y plane: `disk:radius=R,mass=M`; `shape = "disk"`,
//! `radius = R`.

use surfgrav_potentials::{Real, UniformDisk};

use super::{body_error, Key, KeyError, Kind, ValueKind, Values};
use crate::spec::{Amount, BuiltBody, Spec, SpecError};

/// The disk.
pub(super) static KIND: Kind = Kind {
    name: "disk",
    keys: &[Key {
        scene: "radius",
        cli: &["radius"],
        value: ValueKind::Length,
        required: true,
    }],
    solid: false,
    check: no_check,
    build,
    semi_axes: |s| s.values.lengths().first().map(|&r| [r, r, 0.0]),
};

fn no_check(_: &Values) -> Result<(), KeyError> {
    Ok(())
}

fn build(spec: &Spec, g: Real) -> Result<BuiltBody, SpecError> {
    let Amount::Mass(m) = spec.amount else {
        return Err(spec.density_refused());
    };
    UniformDisk::new(spec.values.lengths()[0], m)
        .and_then(|b| b.with_gravitational_constant(g))
        .map(BuiltBody::Disk)
        .map_err(body_error(&KIND))
}
