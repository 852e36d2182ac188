//! The registry of body kinds, shared by the command-line spec (`sphere:radius=1,mass=1`,
//! [`crate::spec`]) and the scene files (`shape = "sphere"`, [`crate::scene`]).
//!
//! A kind declares its name, its keys (how each is spelled in a scene file and on the command
//! line, what value it takes, whether it is required), whether it takes a volume density, and
//! how its validated values become a body ([`BuiltBody`]: the potential and the engine's body).
//! Adding a kind is one file in this folder holding one [`Kind`] plus one entry in
//! [`REGISTRY`]; both parsers then know its name, its keys and their messages.
//!
//! | kind | scene keys | command-line keys |
//! |---|---|---|
//! | `point` | – | – |
//! | `sphere` | `radius` | `radius` |
//! | `spheroid` | `equatorial_radius`, `polar_radius` | `equatorial`, `polar` |
//! | `ellipsoid` | `semi_axes = [a, b, c]` | `a`, `b`, `c` |
//! | `disk` | `radius` | `radius` |
//! | `polyhedron` | `mesh`, `mesh_facets`, `mesh_units`, `principal_axes` | `mesh`, `facets`, `units`, `principal_axes` |
//!
//! Every kind also takes `mass`, and the solids `density` instead.

mod disk;
mod ellipsoid;
mod point;
pub mod polyhedron;
mod sphere;
mod spheroid;

use std::fmt;

use surfgrav_potentials::{BodyError, Real};

use crate::spec::{compact, BuiltBody, Spec, SpecError};

/// What a key's value is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ValueKind {
    /// A positive finite length.
    Length,
    /// Several positive finite lengths: an array in a scene file, one key per component on the
    /// command line (the key's `cli` names).
    Lengths,
    /// A file path (in a scene file, relative to the scene's folder).
    Path,
    /// A length unit, `m` or `km`.
    Unit,
    /// `true` or `false`.
    Flag,
}

/// One key of a kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Key {
    /// Its name in a scene file.
    pub scene: &'static str,
    /// Its name on the command line (one per component for [`ValueKind::Lengths`]).
    pub cli: &'static [&'static str],
    /// Its value.
    pub value: ValueKind,
    /// Whether the kind needs it.
    pub required: bool,
}

/// A value as given, before the kind builds the body.
#[derive(Debug, Clone, PartialEq)]
pub enum Given {
    /// A number (a length).
    Number(Real),
    /// Several numbers (lengths).
    Numbers(Vec<Real>),
    /// Text (a path, a unit).
    Text(String),
    /// A flag.
    Flag(bool),
}

/// The values of a spec, by scene key name, in the kind's key order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Values(pub Vec<(&'static str, Given)>);

impl Values {
    /// The value of the key named `scene` in scene files.
    pub fn get(&self, scene: &str) -> Option<&Given> {
        self.0.iter().find(|(k, _)| *k == scene).map(|(_, v)| v)
    }

    /// Every length, in key order (a sphere's radius; an ellipsoid's a, b, c).
    pub fn lengths(&self) -> Vec<Real> {
        let mut out = Vec::new();
        for (_, v) in &self.0 {
            match v {
                Given::Number(x) => out.push(*x),
                Given::Numbers(xs) => out.extend_from_slice(xs),
                Given::Text(_) | Given::Flag(_) => {}
            }
        }
        out
    }

    /// The text of a key, if given.
    pub fn text(&self, scene: &str) -> Option<&str> {
        match self.get(scene) {
            Some(Given::Text(t)) => Some(t),
            _ => None,
        }
    }

    /// The flag of a key, if given.
    pub fn flag(&self, scene: &str) -> Option<bool> {
        match self.get(scene) {
            Some(Given::Flag(b)) => Some(*b),
            _ => None,
        }
    }
}

/// Why a kind refused its values (the key at fault, by its scene name, and what to change).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct KeyError {
    /// The key (scene name).
    pub key: &'static str,
    /// What is wrong and what to change.
    pub message: String,
}

/// A kind of body.
pub struct Kind {
    /// Its name (`shape = "NAME"` in scene files, `NAME:` on the command line).
    pub name: &'static str,
    /// Its keys besides `mass` and `density`, in order.
    pub keys: &'static [Key],
    /// Whether it takes a volume density instead of the mass.
    pub solid: bool,
    /// Checks the values together (beyond each key's own type), e.g. which mesh format a file
    /// name implies.
    pub check: fn(&Values) -> Result<(), KeyError>,
    /// Builds the validated body with gravitational constant `g`.
    pub build: fn(&Spec, Real) -> Result<BuiltBody, SpecError>,
    /// Semi-axes along the body axes for drawing an outline (`None`: draw none).
    pub semi_axes: fn(&Spec) -> Option<[Real; 3]>,
}

impl fmt::Debug for Kind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Kind({})", self.name)
    }
}

impl PartialEq for Kind {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl Kind {
    /// The command-line keys, as a message lists them: `radius, mass or density`.
    pub fn cli_keys_text(&self) -> String {
        let mut names: Vec<&str> = self
            .keys
            .iter()
            .flat_map(|k| k.cli.iter().copied())
            .collect();
        names.push(if self.solid {
            "mass or density"
        } else {
            "mass"
        });
        names.join(", ")
    }

    /// The scene-file keys, as a message lists them: `equatorial_radius and polar_radius`.
    pub fn scene_keys_text(&self) -> String {
        let names: Vec<&str> = self.keys.iter().map(|k| k.scene).collect();
        match names.as_slice() {
            [] => "no size".to_string(),
            [one] => (*one).to_string(),
            [init @ .., last] => format!("{} and {last}", init.join(", ")),
        }
    }

    /// The key named `scene` in scene files.
    pub fn key(&self, scene: &str) -> Option<&'static Key> {
        self.keys.iter().find(|k| k.scene == scene)
    }
}

/// Every kind, in the order messages list them.
pub static REGISTRY: &[&Kind] = &[
    &point::KIND,
    &sphere::KIND,
    &spheroid::KIND,
    &ellipsoid::KIND,
    &disk::KIND,
    &polyhedron::KIND,
];

/// The kind of that name.
pub fn find(name: &str) -> Option<&'static Kind> {
    REGISTRY.iter().copied().find(|k| k.name == name)
}

/// The kinds' names as a message lists them: `point, sphere, ... or polyhedron`.
pub fn names_text(last: &str) -> String {
    let names: Vec<&str> = REGISTRY.iter().map(|k| k.name).collect();
    match names.split_last() {
        Some((tail, init)) if !init.is_empty() => format!("{} {last} {tail}", init.join(", ")),
        _ => names.join(", "),
    }
}

/// Whether any kind has a scene key of that name.
pub fn is_scene_key(name: &str) -> bool {
    REGISTRY.iter().any(|k| k.key(name).is_some())
}

/// Every kind's scene keys, each once, in registry order.
pub fn all_scene_keys() -> Vec<&'static str> {
    let mut out: Vec<&'static str> = Vec::new();
    for kind in REGISTRY {
        for key in kind.keys {
            if !out.contains(&key.scene) {
                out.push(key.scene);
            }
        }
    }
    out
}

/// A length that is not positive and finite (the scene files' message).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("must be a positive finite length, got {}", compact(*.0))]
pub struct NotPositiveLength(pub Real);

/// A length must be positive and finite.
pub fn positive_length(x: Real) -> Result<Real, NotPositiveLength> {
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(NotPositiveLength(x))
    }
}

/// The constructor's error of a kind, with its name.
pub(crate) fn body_error(kind: &'static Kind) -> impl Fn(BodyError) -> SpecError {
    move |source| SpecError::Body {
        kind: kind.name,
        source,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_keys_are_listed_for_messages() {
        assert_eq!(
            names_text("or"),
            "point, sphere, spheroid, ellipsoid, disk or polyhedron"
        );
        assert_eq!(
            find("sphere").unwrap().cli_keys_text(),
            "radius, mass or density"
        );
        assert_eq!(find("disk").unwrap().cli_keys_text(), "radius, mass");
        assert_eq!(find("point").unwrap().cli_keys_text(), "mass");
        assert_eq!(
            find("spheroid").unwrap().scene_keys_text(),
            "equatorial_radius and polar_radius"
        );
        assert_eq!(find("point").unwrap().scene_keys_text(), "no size");
        assert!(is_scene_key("mesh_units") && !is_scene_key("colour"));
        // Every kind's name is unique, and so is each of its keys.
        for (i, k) in REGISTRY.iter().enumerate() {
            assert!(REGISTRY[..i].iter().all(|o| o.name != k.name));
            for (j, key) in k.keys.iter().enumerate() {
                assert!(k.keys[..j].iter().all(|o| o.scene != key.scene));
            }
        }
    }
}
