//! Body specifications as typed on the command line: `kind:key=value,key=value`.
//!
//! | kind       | keys                                         |
//! |------------|----------------------------------------------|
//! | `point`    | `mass`                                       |
//! | `sphere`   | `radius`, `mass` or `density`                |
//! | `spheroid` | `equatorial`, `polar`, `mass` or `density`   |
//! | `ellipsoid`| `a`, `b`, `c` (semi-axes along x, y, z), `mass` or `density` |
//! | `disk`     | `radius`, `mass`                             |
//! | `polyhedron` | `mesh` (a path: `.obj`, or a vertex `.csv` with `facets`), `units` (`m` or `km`), `principal_axes`, `mass` or `density` |
//!
//! The kinds, their keys and how each becomes a body are the registry of [`crate::kinds`],
//! which the scene files share. [`Spec`] holds a spec of any registered kind; [`BodySpec`] is
//! the typed view of the five closed-form kinds.
//!
//! Parsing never panics: every malformed spec is a [`SpecError`] whose message says what to
//! change.

use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;
use std::sync::Arc;

use surfgrav_interaction::{Body, InteractionError};
use surfgrav_potentials::{
    BodyError, Ellipsoid, MeshError, PointMass, Potential, Real, Sphere, Spheroid, UniformDisk,
    Vec3,
};
use thiserror::Error;

use crate::kinds::{self, polyhedron::PolyhedronBody, Given, Kind, ValueKind, Values};

/// Why a body spec or a vector argument could not be used.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SpecError {
    /// No `kind:` prefix.
    #[error(
        "body spec `{spec}` has no kind: write it as KIND:key=value,... with KIND one of {}",
        kinds::names_text("or")
    )]
    MissingKind {
        /// The spec as given.
        spec: String,
    },
    /// The kind is not one we know.
    #[error("unknown body kind `{kind}`: expected {}", kinds::names_text("or"))]
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
        expected: String,
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
    /// A value that is not one of the allowed words.
    #[error("`{key}={value}`: expected {expected}")]
    BadValue {
        /// The key.
        key: String,
        /// The rejected text.
        value: String,
        /// What is allowed.
        expected: &'static str,
    },
    /// Values that do not fit together (a kind's own check).
    #[error("{kind}: {key}: {message}")]
    Invalid {
        /// The body kind.
        kind: &'static str,
        /// The key at fault (as the command line spells it).
        key: &'static str,
        /// What to change.
        message: String,
    },
    /// An option that must be a positive finite number.
    #[error("{what} must be a positive finite number, got `{value}`")]
    NotPositive {
        /// Which option.
        what: &'static str,
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
    /// A mesh could not be read, or is not a closed outward surface.
    #[error("polyhedron: {}", mesh_error_message(.path, .source))]
    Mesh {
        /// The mesh file(s).
        path: String,
        /// The reader's or the validation's error.
        #[source]
        source: MeshError,
    },
    /// Any other refusal of a polyhedron.
    #[error("polyhedron: {message}")]
    Polyhedron {
        /// What went wrong.
        message: String,
    },
    /// A [`BodySpec`] can only hold the closed-form kinds.
    #[error("a {kind} is not a closed-form body: use spec::Spec for it")]
    NotClosedForm {
        /// The body kind.
        kind: &'static str,
    },
}

/// A mesh error with the file named once.
fn mesh_error_message(path: &str, e: &MeshError) -> String {
    match e {
        MeshError::Io { .. } => format!("cannot read the mesh: {e}"),
        MeshError::Parse { .. } | MeshError::NotTriangle { .. } => e.to_string(),
        _ => format!("the mesh {path} does not bound a solid: {e}"),
    }
}

/// The closed-form kinds, as the Python bindings name them (a typed view of the registry's
/// first five kinds).
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
    /// The registry's name of the kind.
    pub fn name(self) -> &'static str {
        match self {
            BodyKind::Point => "point",
            BodyKind::Sphere => "sphere",
            BodyKind::Spheroid => "spheroid",
            BodyKind::Ellipsoid => "ellipsoid",
            BodyKind::Disk => "disk",
        }
    }

    /// The registry's entry.
    pub fn kind(self) -> &'static Kind {
        let name = self.name();
        kinds::REGISTRY
            .iter()
            .copied()
            .find(|k| k.name == name)
            .unwrap_or(kinds::REGISTRY[0])
    }

    fn of(kind: &Kind) -> Option<Self> {
        [
            BodyKind::Point,
            BodyKind::Sphere,
            BodyKind::Spheroid,
            BodyKind::Ellipsoid,
            BodyKind::Disk,
        ]
        .into_iter()
        .find(|k| k.name() == kind.name)
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

/// A parsed (not yet built) body spec of any registered kind.
#[derive(Debug, Clone, PartialEq)]
pub struct Spec {
    /// The kind.
    pub kind: &'static Kind,
    /// Its values, in the kind's key order.
    pub values: Values,
    /// Mass or density.
    pub amount: Amount,
}

impl Spec {
    /// Builds the validated body with gravitational constant `g`.
    ///
    /// # Errors
    /// The constructor's refusal, or an unreadable or invalid mesh.
    pub fn build(&self, g: f64) -> Result<BuiltBody, SpecError> {
        (self.kind.build)(self, g)
    }

    /// The error for a density given to a kind without a volume.
    pub fn density_refused(&self) -> SpecError {
        SpecError::UnknownKey {
            kind: self.kind.name,
            key: "density".into(),
            expected: self.kind.cli_keys_text(),
        }
    }

    /// Semi-axes along the body axes for drawing an outline (`None`: a point or a mesh).
    pub fn semi_axes(&self) -> Option<[Real; 3]> {
        (self.kind.semi_axes)(self)
    }

    /// The closed-form view, for the five kinds that have one.
    pub fn closed_form(&self) -> Option<BodySpec> {
        Some(BodySpec {
            kind: BodyKind::of(self.kind)?,
            dimensions: self.values.lengths(),
            amount: self.amount,
        })
    }
}

impl From<&BodySpec> for Spec {
    fn from(spec: &BodySpec) -> Self {
        let kind = spec.kind.kind();
        let mut values = Vec::new();
        let mut d = spec.dimensions.iter().copied();
        for key in kind.keys {
            let mut next = || d.next().unwrap_or(f64::NAN);
            let value = match key.value {
                ValueKind::Lengths => Given::Numbers(key.cli.iter().map(|_| next()).collect()),
                _ => Given::Number(next()),
            };
            values.push((key.scene, value));
        }
        Spec {
            kind,
            values: Values(values),
            amount: spec.amount,
        }
    }
}

impl FromStr for Spec {
    type Err = SpecError;

    fn from_str(spec: &str) -> Result<Self, SpecError> {
        let (name, rest) = spec.split_once(':').ok_or_else(|| SpecError::MissingKind {
            spec: spec.to_string(),
        })?;
        let kind = kinds::find(name.trim()).ok_or_else(|| SpecError::UnknownKind {
            kind: name.trim().to_string(),
        })?;
        let numeric = |key: &str| {
            key == "mass"
                || key == "density"
                || kind.keys.iter().any(|k| {
                    matches!(k.value, ValueKind::Length | ValueKind::Lengths)
                        && k.cli.contains(&key)
                })
        };
        let mut numbers: BTreeMap<String, f64> = BTreeMap::new();
        let mut texts: BTreeMap<String, String> = BTreeMap::new();
        for item in rest.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let (key, value) = item.split_once('=').ok_or_else(|| SpecError::NotKeyValue {
                item: item.to_string(),
            })?;
            let key = key.trim();
            let known = kind.keys.iter().any(|k| k.cli.contains(&key))
                || key == "mass"
                || (kind.solid && key == "density");
            if !known {
                return Err(SpecError::UnknownKey {
                    kind: kind.name,
                    key: key.to_string(),
                    expected: kind.cli_keys_text(),
                });
            }
            let duplicate = if numeric(key) {
                let number: f64 = value.trim().parse().map_err(|_| SpecError::NotANumber {
                    key: key.to_string(),
                    value: value.to_string(),
                })?;
                numbers.insert(key.to_string(), number).is_some()
            } else {
                texts
                    .insert(key.to_string(), value.trim().to_string())
                    .is_some()
            };
            if duplicate {
                return Err(SpecError::DuplicateKey {
                    key: key.to_string(),
                });
            }
        }
        let mut values = Vec::new();
        for key in kind.keys {
            let missing = |cli: &'static str| SpecError::MissingKey {
                kind: kind.name,
                key: cli,
            };
            let cli = key.cli[0];
            let value = match key.value {
                ValueKind::Length => numbers.get(cli).map(|&x| Given::Number(x)),
                ValueKind::Lengths => {
                    let mut xs = Vec::new();
                    for &c in key.cli {
                        xs.push(*numbers.get(c).ok_or_else(|| missing(c))?);
                    }
                    Some(Given::Numbers(xs))
                }
                ValueKind::Path => texts.get(cli).map(|t| Given::Text(t.clone())),
                ValueKind::Unit => match texts.get(cli).map(String::as_str) {
                    None => None,
                    Some(u @ ("m" | "km")) => Some(Given::Text(u.to_string())),
                    Some(other) => {
                        return Err(SpecError::BadValue {
                            key: cli.to_string(),
                            value: other.to_string(),
                            expected: "m or km",
                        })
                    }
                },
                ValueKind::Flag => match texts.get(cli).map(String::as_str) {
                    None => None,
                    Some("true") => Some(Given::Flag(true)),
                    Some("false") => Some(Given::Flag(false)),
                    Some(other) => {
                        return Err(SpecError::BadValue {
                            key: cli.to_string(),
                            value: other.to_string(),
                            expected: "true or false",
                        })
                    }
                },
            };
            match value {
                Some(v) => values.push((key.scene, v)),
                None if key.required => return Err(missing(cli)),
                None => {}
            }
        }
        let amount = match (numbers.get("mass"), numbers.get("density")) {
            (Some(_), Some(_)) => return Err(SpecError::MassAndDensity { kind: kind.name }),
            (Some(&m), None) => Amount::Mass(m),
            (None, Some(&d)) => Amount::Density(d),
            (None, None) => {
                return Err(SpecError::MissingKey {
                    kind: kind.name,
                    key: "mass",
                })
            }
        };
        let values = Values(values);
        (kind.check)(&values).map_err(|e| SpecError::Invalid {
            kind: kind.name,
            key: kind.key(e.key).map_or(e.key, |k| k.cli[0]),
            message: e.message,
        })?;
        Ok(Spec {
            kind,
            values,
            amount,
        })
    }
}

impl fmt::Display for Spec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:", self.kind.name)?;
        for (scene, value) in &self.values.0 {
            let Some(key) = self.kind.key(scene) else {
                continue;
            };
            match value {
                Given::Number(x) => write!(f, "{}={x},", key.cli[0])?,
                Given::Numbers(xs) => {
                    for (c, x) in key.cli.iter().zip(xs) {
                        write!(f, "{c}={x},")?;
                    }
                }
                Given::Text(t) => write!(f, "{}={t},", key.cli[0])?,
                Given::Flag(b) => write!(f, "{}={b},", key.cli[0])?,
            }
        }
        match self.amount {
            Amount::Mass(m) => write!(f, "mass={m}"),
            Amount::Density(d) => write!(f, "density={d}"),
        }
    }
}

/// A parsed (not yet validated) spec of a closed-form kind (the Python bindings' view; every
/// kind, meshes included, is a [`Spec`]).
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
        let spec: Spec = spec.parse()?;
        spec.closed_form().ok_or(SpecError::NotClosedForm {
            kind: spec.kind.name,
        })
    }
}

impl fmt::Display for BodySpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        Spec::from(self).fmt(f)
    }
}

impl BodySpec {
    /// Builds the validated body with gravitational constant `g`.
    ///
    /// # Errors
    /// The constructor's refusal of the values.
    pub fn build(&self, g: f64) -> Result<BuiltBody, SpecError> {
        Spec::from(self).build(g)
    }
}

/// A validated body of any kind.
#[derive(Debug, Clone)]
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
    /// A homogeneous polyhedron (shared: a mesh is large).
    Polyhedron(Arc<PolyhedronBody>),
}

impl PartialEq for BuiltBody {
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (BuiltBody::Point(a), BuiltBody::Point(b)) => a == b,
            (BuiltBody::Sphere(a), BuiltBody::Sphere(b)) => a == b,
            (BuiltBody::Spheroid(a), BuiltBody::Spheroid(b)) => a == b,
            (BuiltBody::Ellipsoid(a), BuiltBody::Ellipsoid(b)) => a == b,
            (BuiltBody::Disk(a), BuiltBody::Disk(b)) => a == b,
            (BuiltBody::Polyhedron(a), BuiltBody::Polyhedron(b)) => Arc::ptr_eq(a, b) || a == b,
            _ => false,
        }
    }
}

impl BuiltBody {
    /// The body's field.
    pub fn potential(&self) -> &dyn Potential {
        match self {
            BuiltBody::Point(b) => b,
            BuiltBody::Sphere(b) => b,
            BuiltBody::Spheroid(b) => b,
            BuiltBody::Ellipsoid(b) => b,
            BuiltBody::Disk(b) => b,
            BuiltBody::Polyhedron(b) => &b.polyhedron,
        }
    }

    /// The body as an owned potential.
    pub fn into_potential(&self) -> Box<dyn Potential> {
        match self {
            BuiltBody::Point(b) => Box::new(*b),
            BuiltBody::Sphere(b) => Box::new(*b),
            BuiltBody::Spheroid(b) => Box::new(*b),
            BuiltBody::Ellipsoid(b) => Box::new(*b),
            BuiltBody::Disk(b) => Box::new(*b),
            BuiltBody::Polyhedron(b) => Box::new(b.polyhedron.clone()),
        }
    }

    /// The body with its integration geometry, for the interaction engine.
    ///
    /// # Errors
    /// The engine's refusal of the body.
    pub fn into_interaction_body(&self) -> Result<Body, InteractionError> {
        match self {
            BuiltBody::Point(b) => Ok(Body::point_mass(*b)),
            BuiltBody::Sphere(b) => Body::sphere(*b),
            BuiltBody::Spheroid(b) => Body::spheroid(*b),
            BuiltBody::Ellipsoid(b) => Body::ellipsoid(*b),
            BuiltBody::Disk(b) => Body::disk(*b),
            BuiltBody::Polyhedron(b) => Body::polyhedron(b.polyhedron.clone()),
        }
    }

    /// What was done to read the body, for the user (a mesh's frame), if anything.
    pub fn note(&self) -> Option<String> {
        match self {
            BuiltBody::Polyhedron(b) => Some(b.note()),
            _ => None,
        }
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
///
/// # Errors
/// [`SpecError::NotPositive`] naming the option.
pub fn parse_positive(what: &'static str, text: &str) -> Result<f64, SpecError> {
    match text.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(SpecError::NotPositive {
            what,
            value: text.to_string(),
        }),
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
