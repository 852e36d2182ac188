//! Body specifications as typed on the command line: `kind:key=value,key=value`.
//!
//! | kind       | keys                                         |
//! |------------|----------------------------------------------|
//! | `point`    | `mass`                                       |
//! | `sphere`   | `radius`, `mass` or `density`                |
//! | `spheroid` | `equatorial`, `polar`, `mass` or `density`   |
//! | `ellipsoid`| `a`, `b`, `c` (semi-axes along x, y, z), `mass` or `density` |
//! | `disk`     | `radius`, `mass`                             |
//!
//! Parsing never panics: every malformed spec is a [`SpecError`] whose message says what to
//! change.

use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;

use surfgrav_potentials::{
    BodyError, Ellipsoid, PointMass, Potential, Sphere, Spheroid, UniformDisk, Vec3,
};
use surfgrav_surfaces::interaction::{Body, InteractionError};
use thiserror::Error;

/// Why a body spec or a vector argument could not be used.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SpecError {
    /// No `kind:` prefix.
    #[error("body spec `{spec}` has no kind: write it as KIND:key=value,... with KIND one of point, sphere, spheroid, ellipsoid, disk")]
    MissingKind {
        /// The spec as given.
        spec: String,
    },
    /// The kind is not one we know.
    #[error("unknown body kind `{kind}`: expected point, sphere, spheroid, ellipsoid or disk")]
    UnknownKind {
        /// The rejected kind.
        kind: String,
    },
    /// An item without `=`.
    #[error("body spec item `{item}` is not key=value")]
    NotKeyValue {
        /// The rejected item.
        item: String,
    },
    /// A key that this kind does not take.
    #[error("unknown key `{key}` for a {kind}: expected {expected}")]
    UnknownKey {
        /// The body kind.
        kind: &'static str,
        /// The rejected key.
        key: String,
        /// The keys this kind takes.
        expected: &'static str,
    },
    /// A key given twice.
    #[error("key `{key}` is given twice")]
    DuplicateKey {
        /// The repeated key.
        key: String,
    },
    /// A required key is absent.
    #[error("a {kind} needs `{key}`")]
    MissingKey {
        /// The body kind.
        kind: &'static str,
        /// The missing key.
        key: &'static str,
    },
    /// Both `mass` and `density`.
    #[error("give either mass or density for a {kind}, not both")]
    MassAndDensity {
        /// The body kind.
        kind: &'static str,
    },
    /// A value that is not a number.
    #[error("`{key}={value}` is not a number")]
    NotANumber {
        /// The key.
        key: String,
        /// The rejected text.
        value: String,
    },
    /// A vector with the wrong number of components or a bad component.
    #[error("{what} must be three comma-separated finite numbers X,Y,Z, got `{value}`")]
    BadVector {
        /// Which argument.
        what: &'static str,
        /// The rejected text.
        value: String,
    },
    /// The body's constructor rejected the values.
    #[error("{kind}: {}", body_error_message(.source))]
    Body {
        /// The body kind.
        kind: &'static str,
        /// The constructor's error.
        #[source]
        source: BodyError,
    },
}

/// The kinds of body a spec can name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BodyKind {
    /// A point mass.
    Point,
    /// A homogeneous sphere.
    Sphere,
    /// A homogeneous spheroid (oblate, prolate or spherical).
    Spheroid,
    /// A homogeneous triaxial ellipsoid.
    Ellipsoid,
    /// A uniform thin disk.
    Disk,
}

impl BodyKind {
    fn name(self) -> &'static str {
        match self {
            BodyKind::Point => "point",
            BodyKind::Sphere => "sphere",
            BodyKind::Spheroid => "spheroid",
            BodyKind::Ellipsoid => "ellipsoid",
            BodyKind::Disk => "disk",
        }
    }

    /// Geometric keys, in order, then whether `density` is accepted.
    fn keys(self) -> (&'static [&'static str], bool, &'static str) {
        match self {
            BodyKind::Point => (&[], false, "mass"),
            BodyKind::Sphere => (&["radius"], true, "radius, mass or density"),
            BodyKind::Spheroid => (
                &["equatorial", "polar"],
                true,
                "equatorial, polar, mass or density",
            ),
            BodyKind::Ellipsoid => (&["a", "b", "c"], true, "a, b, c, mass or density"),
            BodyKind::Disk => (&["radius"], false, "radius, mass"),
        }
    }
}

/// How much matter a body has.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Amount {
    /// Total mass.
    Mass(f64),
    /// Volume density (solids only).
    Density(f64),
}

/// A parsed (not yet validated) body spec.
#[derive(Debug, Clone, PartialEq)]
pub struct BodySpec {
    /// The body kind.
    pub kind: BodyKind,
    /// The geometric values, in the order of the kind's keys.
    pub dimensions: Vec<f64>,
    /// Mass or density.
    pub amount: Amount,
}

impl FromStr for BodySpec {
    type Err = SpecError;

    fn from_str(spec: &str) -> Result<Self, SpecError> {
        let (kind, rest) = spec.split_once(':').ok_or_else(|| SpecError::MissingKind {
            spec: spec.to_string(),
        })?;
        let kind = match kind.trim() {
            "point" => BodyKind::Point,
            "sphere" => BodyKind::Sphere,
            "spheroid" => BodyKind::Spheroid,
            "ellipsoid" => BodyKind::Ellipsoid,
            "disk" => BodyKind::Disk,
            other => {
                return Err(SpecError::UnknownKind {
                    kind: other.to_string(),
                })
            }
        };
        let (geometric, density_allowed, expected) = kind.keys();
        let mut values = BTreeMap::new();
        for item in rest.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let (key, value) = item.split_once('=').ok_or_else(|| SpecError::NotKeyValue {
                item: item.to_string(),
            })?;
            let key = key.trim();
            let known =
                geometric.contains(&key) || key == "mass" || (density_allowed && key == "density");
            if !known {
                return Err(SpecError::UnknownKey {
                    kind: kind.name(),
                    key: key.to_string(),
                    expected,
                });
            }
            let number: f64 = value.trim().parse().map_err(|_| SpecError::NotANumber {
                key: key.to_string(),
                value: value.to_string(),
            })?;
            if values.insert(key.to_string(), number).is_some() {
                return Err(SpecError::DuplicateKey {
                    key: key.to_string(),
                });
            }
        }
        let dimensions = geometric
            .iter()
            .map(|&key| {
                values.get(key).copied().ok_or(SpecError::MissingKey {
                    kind: kind.name(),
                    key,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let amount = match (values.get("mass"), values.get("density")) {
            (Some(_), Some(_)) => return Err(SpecError::MassAndDensity { kind: kind.name() }),
            (Some(&m), None) => Amount::Mass(m),
            (None, Some(&d)) => Amount::Density(d),
            (None, None) => {
                return Err(SpecError::MissingKey {
                    kind: kind.name(),
                    key: "mass",
                })
            }
        };
        Ok(BodySpec {
            kind,
            dimensions,
            amount,
        })
    }
}

impl fmt::Display for BodySpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (keys, _, _) = self.kind.keys();
        write!(f, "{}:", self.kind.name())?;
        for (k, v) in keys.iter().zip(&self.dimensions) {
            write!(f, "{k}={v},")?;
        }
        match self.amount {
            Amount::Mass(m) => write!(f, "mass={m}"),
            Amount::Density(d) => write!(f, "density={d}"),
        }
    }
}

/// A validated body of any kind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BuiltBody {
    /// A point mass.
    Point(PointMass),
    /// A homogeneous sphere.
    Sphere(Sphere),
    /// A homogeneous spheroid.
    Spheroid(Spheroid),
    /// A homogeneous triaxial ellipsoid.
    Ellipsoid(Ellipsoid),
    /// A uniform thin disk.
    Disk(UniformDisk),
}

impl BuiltBody {
    /// The body as a potential.
    pub fn into_potential(self) -> Box<dyn Potential> {
        match self {
            BuiltBody::Point(b) => Box::new(b),
            BuiltBody::Sphere(b) => Box::new(b),
            BuiltBody::Spheroid(b) => Box::new(b),
            BuiltBody::Ellipsoid(b) => Box::new(b),
            BuiltBody::Disk(b) => Box::new(b),
        }
    }

    /// The body with its integration geometry, for the interaction engine.
    pub fn into_interaction_body(self) -> Result<Body, InteractionError> {
        match self {
            BuiltBody::Point(b) => Ok(Body::point_mass(b)),
            BuiltBody::Sphere(b) => Body::sphere(b),
            BuiltBody::Spheroid(b) => Body::spheroid(b),
            BuiltBody::Ellipsoid(b) => Body::ellipsoid(b),
            BuiltBody::Disk(b) => Body::disk(b),
        }
    }
}

impl BodySpec {
    /// Builds the validated body with gravitational constant `g`.
    pub fn build(&self, g: f64) -> Result<BuiltBody, SpecError> {
        let kind = self.kind.name();
        let wrap = |source| SpecError::Body { kind, source };
        let d = &self.dimensions;
        let body = match (self.kind, self.amount) {
            (BodyKind::Point, Amount::Mass(m)) => BuiltBody::Point(
                PointMass::new(m)
                    .and_then(|b| b.with_gravitational_constant(g))
                    .map_err(wrap)?,
            ),
            (BodyKind::Sphere, Amount::Mass(m)) => BuiltBody::Sphere(
                Sphere::new(d[0], m)
                    .and_then(|b| b.with_gravitational_constant(g))
                    .map_err(wrap)?,
            ),
            (BodyKind::Sphere, Amount::Density(rho)) => BuiltBody::Sphere(
                Sphere::with_density(d[0], rho)
                    .and_then(|b| b.with_gravitational_constant(g))
                    .map_err(wrap)?,
            ),
            (BodyKind::Spheroid, Amount::Mass(m)) => BuiltBody::Spheroid(
                Spheroid::new(d[0], d[1], m)
                    .and_then(|b| b.with_gravitational_constant(g))
                    .map_err(wrap)?,
            ),
            (BodyKind::Spheroid, Amount::Density(rho)) => BuiltBody::Spheroid(
                Spheroid::with_density(d[0], d[1], rho)
                    .and_then(|b| b.with_gravitational_constant(g))
                    .map_err(wrap)?,
            ),
            (BodyKind::Ellipsoid, Amount::Mass(m)) => BuiltBody::Ellipsoid(
                Ellipsoid::new(d[0], d[1], d[2], m)
                    .and_then(|b| b.with_gravitational_constant(g))
                    .map_err(wrap)?,
            ),
            (BodyKind::Ellipsoid, Amount::Density(rho)) => BuiltBody::Ellipsoid(
                Ellipsoid::with_density(d[0], d[1], d[2], rho)
                    .and_then(|b| b.with_gravitational_constant(g))
                    .map_err(wrap)?,
            ),
            (BodyKind::Disk, Amount::Mass(m)) => BuiltBody::Disk(
                UniformDisk::new(d[0], m)
                    .and_then(|b| b.with_gravitational_constant(g))
                    .map_err(wrap)?,
            ),
            // The parser accepts density only for solids.
            (BodyKind::Point | BodyKind::Disk, Amount::Density(_)) => {
                return Err(SpecError::UnknownKey {
                    kind,
                    key: "density".into(),
                    expected: self.kind.keys().2,
                })
            }
        };
        Ok(body)
    }
}

/// A number as a person reads it: the shortest decimal that round-trips, in positional form
/// when that is short (`0.25`, `300`, `6.6743e-11` stays scientific), in scientific form
/// otherwise (`1e-320`, not 330 digits; `1e307`, not 308).
pub fn compact(x: f64) -> String {
    let plain = x.to_string();
    if !x.is_finite() || x == 0.0 || ((1e-4..1e16).contains(&x.abs()) && plain.len() <= 24) {
        plain
    } else {
        format!("{x:e}")
    }
}

/// The constructor's message with its numbers in [`compact`] form.
fn body_error_message(e: &BodyError) -> String {
    match e {
        BodyError::NotPositive { field, value } => {
            format!(
                "{field} must be a positive finite number, got {}",
                compact(*value)
            )
        }
        BodyError::NotFinite { field, value } => {
            format!("{field} must be finite, got {}", compact(*value))
        }
        BodyError::OutOfRange { what, value } => format!(
            "{what} is not representable for these inputs ({}); rescale the units",
            compact(*value)
        ),
        other => other.to_string(),
    }
}

/// Parses `X,Y,Z` into a vector of three finite numbers.
pub fn parse_vector(what: &'static str, text: &str) -> Result<Vec3, SpecError> {
    let bad = || SpecError::BadVector {
        what,
        value: text.to_string(),
    };
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(bad());
    }
    let mut v = [0.0; 3];
    for (slot, part) in v.iter_mut().zip(&parts) {
        let x: f64 = part.parse().map_err(|_| bad())?;
        if !x.is_finite() {
            return Err(bad());
        }
        *slot = x;
    }
    Ok(Vec3::new(v[0], v[1], v[2]))
}

/// Parses a positive finite number (a gravitational constant, a tolerance).
pub fn parse_positive(what: &'static str, text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!(
            "{what} must be a positive finite number, got `{text}`"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_every_kind() {
        let s: BodySpec = "spheroid:equatorial=1,polar=0.25,mass=1".parse().unwrap();
        assert_eq!(s.kind, BodyKind::Spheroid);
        assert_eq!(s.dimensions, vec![1.0, 0.25]);
        assert_eq!(s.amount, Amount::Mass(1.0));
        let s: BodySpec = "ellipsoid:c=3,a=1,b=2,density=2".parse().unwrap();
        assert_eq!(s.dimensions, vec![1.0, 2.0, 3.0]);
        assert_eq!(s.amount, Amount::Density(2.0));
        for ok in [
            "point:mass=2",
            "sphere:radius=1,mass=1",
            "disk:radius=1,mass=1",
        ] {
            ok.parse::<BodySpec>().unwrap();
        }
    }

    #[test]
    fn rejects_malformed_specs_with_named_errors() {
        let cases = [
            ("spheroid", "no kind"),
            ("cube:side=1,mass=1", "unknown body kind"),
            ("sphere:radius=1,mass=1,colour=2", "unknown key `colour`"),
            ("sphere:radius=1", "needs `mass`"),
            ("sphere:mass=1", "needs `radius`"),
            ("sphere:radius=1,radius=2,mass=1", "twice"),
            ("sphere:radius=one,mass=1", "not a number"),
            ("sphere:radius=1,mass=1,density=1", "not both"),
            ("disk:radius=1,density=1", "unknown key `density`"),
            ("sphere:radius1,mass=1", "not key=value"),
        ];
        for (spec, expected) in cases {
            let err = spec.parse::<BodySpec>().unwrap_err().to_string();
            assert!(err.contains(expected), "{spec}: `{err}` lacks `{expected}`");
        }
    }

    /// Numbers in messages stay short at any magnitude (a subnormal mass once printed 330
    /// digits) and round-trip.
    #[test]
    fn compact_numbers_are_short_and_exact() {
        for (x, shown) in [
            (0.25, "0.25"),
            (300.0, "300"),
            (-3.5, "-3.5"),
            (0.0, "0"),
            (1e-320, "1e-320"),
            (1e307, "1e307"),
            (6.6743e-11, "6.6743e-11"),
            (f64::INFINITY, "inf"),
        ] {
            assert_eq!(compact(x), shown);
            if x.is_finite() {
                assert_eq!(compact(x).parse::<f64>().unwrap(), x);
            }
        }
        let err = "sphere:radius=1,mass=1e-320"
            .parse::<BodySpec>()
            .unwrap()
            .build(1.0)
            .unwrap_err()
            .to_string();
        assert!(err.contains("e-") && err.len() < 120, "{err}");
    }

    #[test]
    fn vectors_need_three_finite_components() {
        assert_eq!(
            parse_vector("--at", "1, -2,3e2").unwrap(),
            Vec3::new(1.0, -2.0, 300.0)
        );
        for bad in ["1,2", "1,2,3,4", "1,nan,3", "1,inf,3", "a,b,c", ""] {
            assert!(parse_vector("--at", bad).is_err(), "{bad}");
        }
    }
}
