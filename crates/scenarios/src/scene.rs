//! Scene files: a two-body scene written in TOML, read into plain serde structs
//! ([`SceneFile`]) and validated across fields by [`SceneFile::build`] into a runnable
//! [`Scene`].
//!
//! ```toml
//! name = "paper-2s"                     # names the default output folder
//! description = "two oblate spheroids"  # optional
//! gravitational_constant = 1.0          # or units = "si" (G = 6.6743e-11); default G = 1
//! t_end = 300.0                         # end time (t starts at t_start, default 0)
//! # escape_distance = 700.0             # an unbound orbit beyond it stops the run (default
//! #                                     # 100 initial separations; inf: never)
//!
//! [body_a]
//! shape = "spheroid"        # point | sphere | spheroid | ellipsoid | disk | polyhedron
//! equatorial_radius = 1.0   # spheroid: equatorial_radius, polar_radius (symmetry axis = body z)
//! polar_radius = 0.25       # sphere, disk: radius; ellipsoid: semi_axes = [a, b, c];
//!                           # polyhedron: mesh = "a.obj" (relative to this file's folder),
//!                           # mesh_units = "km", principal_axes = true; a vertex CSV names its
//!                           # facets too: mesh_facets = "f.csv" (crate::kinds::polyhedron)
//! mass = 1.0                # or density = ... (solids only)
//! position = [-3.5, 0.0, 0.0]
//! velocity = [0.0, 0.2, 0.0]
//! orientation = [0.0, 0.0, 0.0]  # optional rotation vector (axis × angle, rad), body → world
//! angular_velocity = [0.0, 0.0, 0.0]  # optional, world frame, rad per time unit; or
//! # angular_velocity_body = [...]     # the same in the body frame (give at most one)
//!
//! [body_b]
//! # ... as body_a
//!
//! [integrator]
//! method = "rk4"     # rk4 | leapfrog | yoshida4 | yoshida6 | yoshida8 | dopri5 | dop853
//! step = 0.1         # fixed-step methods
//! # tolerance = 1e-10  # adaptive methods (relative and absolute)
//!
//! [interaction]      # optional
//! tolerance = 1e-12  # relative accuracy of the surface integrals
//! tabulate = true    # tabulated V(r) when the pair is central (module surfgrav_dynamics::engine_model)
//!
//! [output]           # optional
//! every = 1          # write every n-th step to trajectory.csv (the last one always), or
//! # interval = 0.5   # the states at t_start + k·interval from the dense output (and the last)
//! # neither: every step up to 10,000 rows, else a cadence that keeps about 10,000 (adaptive
//! # methods: the dense output at a round interval giving at most 2,000 rows)
//! figures = ["orbits", "conservation", "histograms"]   # the paper's Figs. 2, 3, 4
//! ```
//!
//! Units: lengths, masses and times are whatever the gravitational constant makes them (the
//! paper's unit-less G = 1 by default). Frames: positions and velocities are world-frame
//! centroid values; a spheroid's symmetry axis and a disk's normal are the body z axis.
//!
//! Every error says where: [`SceneError`] carries the file, the line (when the fault can be
//! placed), the field and what to change.
//!
//! From a file to a run, as `surfgrav run` does it (without the output folder):
//!
//! ```
//! use surfgrav_scenarios::{presets, scene::SceneFile, simulate::run_scene};
//!
//! // Start from a preset's text, as `surfgrav presets --show paper-2s` prints it.
//! let text = presets::find("paper-2s").unwrap().toml.replace("t_end = 300.0", "t_end = 100.0");
//! let scene = SceneFile::parse(&text, "my-scene.toml")?.build(&text, "my-scene.toml")?;
//! let run = run_scene(&scene)?;
//! assert_eq!(run.summary.steps, 1000);
//! assert!((run.orbit.minimum_separation.unwrap() - 2.5472).abs() < 1e-4);
//!
//! // A bad value is refused with the file, the line, the field and what to change.
//! let bad = text.replace("polar_radius = 0.25", "polar_radius = -0.25");
//! let error = SceneFile::parse(&bad, "my-scene.toml")?.build(&bad, "my-scene.toml").unwrap_err();
//! assert_eq!(
//!     error.to_string(),
//!     "my-scene.toml:11: body_a.polar_radius: must be a positive finite length, got -0.25"
//! );
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::fmt;
use std::path::Path;

use serde::{Deserialize, Serialize};
use surfgrav_dynamics::{
    BodyState, Integrator, IntegratorChoiceError, IntegratorKind, TwoBodyState,
};
use surfgrav_potentials::{Real, Vec3};
use toml::Spanned;

use crate::kinds::{self, Given, ValueKind, Values};
use crate::spec::{compact, Amount, BuiltBody, Spec};

/// The gravitational constant in SI units (CODATA 2018), m³ kg⁻¹ s⁻².
pub const G_SI: Real = 6.674_30e-11;

/// Why a scene could not be read or built: where, which field, what to change.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    /// The file (or `preset NAME`).
    pub file: String,
    /// 1-based line, when the fault can be placed.
    pub line: Option<usize>,
    /// The field (`body_a.mass`), when one is at fault.
    pub field: Option<String>,
    /// What is wrong and what to change.
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
        }
        write!(f, ": ")?;
        if let Some(field) = &self.field {
            write!(f, "{field}: ")?;
        }
        write!(f, "{}", self.message)
    }
}

impl std::error::Error for SceneError {}

/// One body as written in a scene file: its kind (`shape`), the kind's own keys (sizes, a
/// mesh: see [`crate::kinds`]), and the keys every body has.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyFile {
    /// The kind's name (`point`, `sphere`, ..., `polyhedron`: [`crate::kinds::REGISTRY`]).
    pub shape: Spanned<String>,
    /// The kind's own keys as written, in file order (checked against the kind by
    /// [`SceneFile::parse`] and [`SceneFile::build`]).
    pub keys: Vec<(String, Spanned<toml::Value>)>,
    /// Total mass.
    pub mass: Option<Spanned<Real>>,
    /// Density (solids only), instead of the mass.
    pub density: Option<Spanned<Real>>,
    /// Initial centroid position (world frame).
    pub position: Spanned<[Real; 3]>,
    /// Initial centroid velocity (world frame).
    pub velocity: Spanned<[Real; 3]>,
    /// Orientation as a rotation vector (axis × angle, radians), body frame → world frame.
    pub orientation: Option<Spanned<[Real; 3]>>,
    /// Angular velocity (world frame, radians per time unit). `spin` is read as this key.
    pub angular_velocity: Option<Spanned<[Real; 3]>>,
    /// Angular velocity in the body frame (radians per time unit), instead of
    /// `angular_velocity`.
    pub angular_velocity_body: Option<Spanned<[Real; 3]>>,
}

impl<'de> Deserialize<'de> for BodyFile {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = BodyFile;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a body table")
            }

            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                mut map: A,
            ) -> Result<BodyFile, A::Error> {
                use serde::de::Error;
                let mut shape = None;
                let mut keys = Vec::new();
                let (mut mass, mut density) = (None, None);
                let (mut position, mut velocity, mut orientation) = (None, None, None);
                let (mut angular_velocity, mut angular_velocity_body) = (None, None);
                while let Some(key) = map.next_key::<String>()? {
                    match key.as_str() {
                        "shape" => shape = Some(map.next_value()?),
                        "mass" => mass = Some(map.next_value()?),
                        "density" => density = Some(map.next_value()?),
                        "position" => position = Some(map.next_value()?),
                        "velocity" => velocity = Some(map.next_value()?),
                        "orientation" => orientation = Some(map.next_value()?),
                        "angular_velocity" | "spin" => {
                            if angular_velocity.is_some() {
                                return Err(A::Error::duplicate_field("angular_velocity"));
                            }
                            angular_velocity = Some(map.next_value()?);
                        }
                        "angular_velocity_body" => {
                            angular_velocity_body = Some(map.next_value()?);
                        }
                        _ => keys.push((key, map.next_value()?)),
                    }
                }
                Ok(BodyFile {
                    shape: shape.ok_or_else(|| A::Error::missing_field("shape"))?,
                    keys,
                    mass,
                    density,
                    position: position.ok_or_else(|| A::Error::missing_field("position"))?,
                    velocity: velocity.ok_or_else(|| A::Error::missing_field("velocity"))?,
                    orientation,
                    angular_velocity,
                    angular_velocity_body,
                })
            }
        }
        deserializer.deserialize_map(Visitor)
    }
}

impl Serialize for BodyFile {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("shape", &self.shape)?;
        for (key, value) in &self.keys {
            map.serialize_entry(key, value)?;
        }
        let optional = [("mass", &self.mass), ("density", &self.density)];
        for (key, value) in optional {
            if let Some(v) = value {
                map.serialize_entry(key, v)?;
            }
        }
        map.serialize_entry("position", &self.position)?;
        map.serialize_entry("velocity", &self.velocity)?;
        let vectors = [
            ("orientation", &self.orientation),
            ("angular_velocity", &self.angular_velocity),
            ("angular_velocity_body", &self.angular_velocity_body),
        ];
        for (key, value) in vectors {
            if let Some(v) = value {
                map.serialize_entry(key, v)?;
            }
        }
        map.end()
    }
}

impl BodyFile {
    /// The kind named by `shape`, and no key that no kind has: a [`SceneError`] at the line.
    fn check_keys(&self, loc: &Locator<'_>, table: &str) -> Result<(), SceneError> {
        let name = self.shape.get_ref();
        if kinds::find(name).is_none() {
            let expected = kinds::REGISTRY
                .iter()
                .map(|k| format!("`{}`", k.name))
                .collect::<Vec<_>>()
                .join(", ");
            return Err(loc.at(
                &self.shape,
                &format!("{table}.shape"),
                format!("unknown variant `{name}`, expected one of {expected}"),
            ));
        }
        let kind = kinds::find(name);
        for (key, value) in &self.keys {
            if !kinds::is_scene_key(key) {
                // This shape's keys, then every body's.
                let mut takes: Vec<String> = Vec::new();
                if let Some(k) = kind.filter(|k| !k.keys.is_empty()) {
                    takes.push(k.scene_keys_text());
                }
                takes.push(if kind.is_some_and(|k| k.solid) {
                    "mass or density".into()
                } else {
                    "mass".into()
                });
                takes.push(
                    "position, velocity, orientation, angular_velocity or angular_velocity_body"
                        .into(),
                );
                return Err(loc.at(
                    value,
                    &format!("{table}.{key}"),
                    format!("unknown field `{key}`: a {name} takes {}", takes.join(", ")),
                ));
            }
        }
        Ok(())
    }
}

/// The integrator as written in a scene file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IntegratorFile {
    /// Method name (see [`IntegratorName`]).
    pub method: Spanned<String>,
    /// Step of a fixed-step method.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step: Option<Spanned<Real>>,
    /// Relative (and absolute) tolerance of an adaptive method.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<Spanned<Real>>,
}

/// Interaction settings as written in a scene file.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InteractionFile {
    /// Relative accuracy of the surface integrals (default 1e-12).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<Spanned<Real>>,
    /// Tabulate V(r) when the pair is central (default true).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tabulate: Option<bool>,
}

/// Output settings as written in a scene file.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputFile {
    /// Write every n-th step to the trajectory.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub every: Option<Spanned<i64>>,
    /// Write the states at $t_0 + k\\,\Delta$ from the dense output (instead of `every`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interval: Option<Spanned<Real>>,
    /// Figures to draw (default all three).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub figures: Option<Spanned<Vec<FigureKind>>>,
}

/// The figures a run can draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FigureKind {
    /// The paper's Fig. 2: both orbits about the centre of mass, and B relative to A.
    Orbits,
    /// The paper's Fig. 3: separation, ΔE and ΔJ against time.
    Conservation,
    /// The paper's Fig. 4: histograms of ΔE and ΔJ.
    Histograms,
    /// Spin rates, obliquities and libration angles against time, with the drifts of the
    /// energy and of the angular-momentum vector (drawn by default for runs that integrate
    /// rotation).
    Rotation,
}

impl FigureKind {
    /// Every figure, in order.
    pub const ALL: [FigureKind; 3] = [
        FigureKind::Orbits,
        FigureKind::Conservation,
        FigureKind::Histograms,
    ];
}

/// A scene file as written (plain data; [`SceneFile::build`] validates it).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Scene name (names the default output folder).
    pub name: Spanned<String>,
    /// Free text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// A named unit system: `"paper"` (G = 1) or `"si"` (G = 6.6743e-11).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub units: Option<Spanned<String>>,
    /// The gravitational constant (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gravitational_constant: Option<Spanned<Real>>,
    /// Start time (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t_start: Option<Spanned<Real>>,
    /// End time.
    pub t_end: Spanned<Real>,
    /// Separation beyond which an unbound relative orbit stops the run as an escape (default
    /// 100 times the initial separation; `inf` never stops).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub escape_distance: Option<Spanned<Real>>,
    /// Body A.
    pub body_a: Spanned<BodyFile>,
    /// Body B.
    pub body_b: Spanned<BodyFile>,
    /// The integrator.
    pub integrator: Spanned<IntegratorFile>,
    /// Interaction settings.
    #[serde(default)]
    pub interaction: InteractionFile,
    /// Output settings.
    #[serde(default)]
    pub output: OutputFile,
}

/// How often `trajectory.csv` gets a row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum OutputCadence {
    /// Chosen from the run's length ([`crate::output::OutputPlan::of`]): every step up to
    /// [`crate::output::DEFAULT_MAX_ROWS`] rows, fewer evenly spaced ones beyond; the dense
    /// output at a round interval giving at most [`crate::output::DEFAULT_MAX_ADAPTIVE_ROWS`]
    /// rows for adaptive methods.
    Default,
    /// Every n-th step (and the last).
    Every(usize),
    /// The states at $t_0 + k\\,\Delta$ from the integrator's dense output (and the last).
    Interval(Real),
}

/// Most rows `[output] interval` may ask for (10 million rows are ~3 GB of CSV).
pub const MAX_INTERVAL_ROWS: Real = 1e7;

/// The integrators a scene can name (the dynamics crate's [`IntegratorKind`]).
pub type IntegratorName = IntegratorKind;

/// A validated integrator choice: the method with its step or tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum IntegratorChoice {
    /// A fixed-step method.
    Fixed {
        /// The method.
        method: IntegratorName,
        /// The step.
        step: Real,
    },
    /// An adaptive method.
    Adaptive {
        /// The method.
        method: IntegratorName,
        /// Relative and absolute tolerance.
        tolerance: Real,
    },
}

impl IntegratorChoice {
    /// The method.
    pub fn method(&self) -> IntegratorName {
        match *self {
            Self::Fixed { method, .. } | Self::Adaptive { method, .. } => method,
        }
    }

    /// The integrator, ready to run.
    ///
    /// # Errors
    /// The integrator's own parameter errors.
    pub fn make(&self) -> Result<Box<dyn Integrator>, IntegratorChoiceError> {
        match *self {
            Self::Fixed { method, step } => method.build(step, Real::NAN),
            Self::Adaptive { method, tolerance } => method.build(Real::NAN, tolerance),
        }
    }
}

/// A validated scene, ready to run.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Name (names the default output folder).
    pub name: String,
    /// Free text.
    pub description: Option<String>,
    /// The gravitational constant.
    pub gravitational_constant: Real,
    /// Body A as a spec (kind, its values, mass or density).
    pub spec_a: Spec,
    /// Body B.
    pub spec_b: Spec,
    /// Body A, validated.
    pub body_a: BuiltBody,
    /// Body B, validated.
    pub body_b: BuiltBody,
    /// The initial state.
    pub initial: TwoBodyState,
    /// Start time.
    pub t_start: Real,
    /// End time.
    pub t_end: Real,
    /// An unbound orbit beyond this separation stops the run (`None`: never).
    pub escape_distance: Option<Real>,
    /// The integrator.
    pub integrator: IntegratorChoice,
    /// Relative accuracy of the surface integrals.
    pub interaction_tolerance: Real,
    /// Tabulate V(r) when central.
    pub tabulate: bool,
    /// How often the trajectory is written.
    pub output: OutputCadence,
    /// Figures to draw.
    pub figures: Vec<FigureKind>,
    /// What was done to read the bodies, for the user (a mesh's file, size and frame), one
    /// line each.
    pub notes: Vec<String>,
}

/// The default escape distance, in initial separations: far enough that a bound orbit of a
/// realistic eccentricity never reaches it, near enough that a flyby stops soon after.
pub const DEFAULT_ESCAPE_FACTOR: Real = 100.0;

/// Byte offset → 1-based line.
fn line_of(source: &str, offset: usize) -> usize {
    source
        .get(..offset.min(source.len()))
        .map_or(1, |s| s.matches('\n').count() + 1)
}

/// The nearest `[table]` header above `offset`, if any.
fn table_above(source: &str, offset: usize) -> Option<String> {
    let head = source.get(..offset.min(source.len()))?;
    head.lines().rev().find_map(|line| {
        let t = line.trim();
        (t.starts_with('[') && t.ends_with(']')).then(|| t.trim_matches(['[', ']']).to_string())
    })
}

/// Builds errors for one source text.
struct Locator<'s> {
    file: &'s str,
    source: &'s str,
}

impl Locator<'_> {
    fn at<T>(&self, spanned: &Spanned<T>, field: &str, message: impl Into<String>) -> SceneError {
        SceneError {
            file: self.file.to_string(),
            line: Some(line_of(self.source, spanned.span().start)),
            field: Some(field.to_string()),
            message: message.into(),
        }
    }
}

impl SceneFile {
    /// Parses TOML text; `file` names the source in messages.
    ///
    /// # Errors
    /// Malformed TOML, unknown or missing fields, values of the wrong type, each with the line.
    pub fn parse(source: &str, file: &str) -> Result<Self, SceneError> {
        let scene: Self = toml::from_str(source).map_err(|e| {
            let start = e.span().map(|s| s.start);
            let mut message = e.message().trim().replace('\n', " ");
            // The TOML parser says "duplicate key" without the key: name it, from the text at
            // the span (`mass = 2.0` gives `mass`).
            if message.starts_with("duplicate key") && !message.contains('`') {
                let key = start
                    .and_then(|s| source.get(s..))
                    .and_then(|rest| rest.split(['=', '\n']).next())
                    .map(|k| k.trim().trim_matches(['[', ']']).trim())
                    .filter(|k| !k.is_empty());
                if let Some(key) = key {
                    message =
                        format!("duplicate key `{key}`: it is given twice in this table; keep one");
                }
            }
            SceneError {
                file: file.to_string(),
                line: start.map(|s| line_of(source, s)),
                field: start
                    .and_then(|s| table_above(source, s))
                    .map(|t| format!("[{t}]")),
                message,
            }
        })?;
        let loc = Locator { file, source };
        scene.body_a.get_ref().check_keys(&loc, "body_a")?;
        scene.body_b.get_ref().check_keys(&loc, "body_b")?;
        Ok(scene)
    }

    /// Reads and parses a scene file.
    ///
    /// # Errors
    /// An unreadable file, then as [`SceneFile::parse`].
    pub fn read(path: &Path) -> Result<(Self, String), SceneError> {
        let file = path.display().to_string();
        let source = std::fs::read_to_string(path).map_err(|e| SceneError {
            file: file.clone(),
            line: None,
            field: None,
            message: format!("cannot read the scene file: {e}"),
        })?;
        Ok((Self::parse(&source, &file)?, source))
    }

    /// The scene as TOML text (comments are not kept).
    ///
    /// # Errors
    /// Only if the TOML serialiser fails (it does not for these structs).
    pub fn to_toml(&self) -> Result<String, toml::ser::Error> {
        toml::to_string(self)
    }

    /// Validates every field and their combinations and builds the scene. `source` is the text
    /// the file was parsed from (for line numbers) and `file` names it.
    ///
    /// # Errors
    /// A [`SceneError`] naming the field, its line and what to change.
    pub fn build(&self, source: &str, file: &str) -> Result<Scene, SceneError> {
        let loc = Locator { file, source };
        let positive = |value: &Spanned<Real>, field: &str| -> Result<Real, SceneError> {
            let v = *value.get_ref();
            if v.is_finite() && v > 0.0 {
                Ok(v)
            } else {
                Err(loc.at(
                    value,
                    field,
                    format!("must be a positive finite number, got {}", compact(v)),
                ))
            }
        };
        // Any name is accepted; only the default output folder needs a folder-safe one (checked
        // by `output::choose_folder` when no --out is given).
        let name = self.name.get_ref().trim().to_string();
        if name.is_empty() || name.chars().any(char::is_control) {
            return Err(loc.at(&self.name, "name", "must be a non-empty name on one line"));
        }

        let g = match (&self.units, &self.gravitational_constant) {
            (Some(u), Some(_)) => {
                return Err(loc.at(
                    u,
                    "units",
                    "give either units or gravitational_constant, not both",
                ))
            }
            (Some(u), None) => match u.get_ref().as_str() {
                "paper" => 1.0,
                "si" => G_SI,
                other => {
                    return Err(loc.at(
                        u,
                        "units",
                        format!("unknown unit system `{other}`: expected \"paper\" (G = 1) or \"si\" (G = 6.6743e-11)"),
                    ))
                }
            },
            (None, Some(g)) => positive(g, "gravitational_constant")?,
            (None, None) => 1.0,
        };

        let t_start = match &self.t_start {
            Some(t) if !t.get_ref().is_finite() => {
                return Err(loc.at(t, "t_start", "must be a finite number"))
            }
            Some(t) => *t.get_ref(),
            None => 0.0,
        };
        let t_end = *self.t_end.get_ref();
        if !(t_end.is_finite() && t_end > t_start) {
            return Err(loc.at(
                &self.t_end,
                "t_end",
                format!(
                    "must be finite and greater than t_start = {}, got {}",
                    compact(t_start),
                    compact(t_end)
                ),
            ));
        }

        let folder = Path::new(file).parent();
        let (spec_a, body_a, state_a) = build_body(&loc, &self.body_a, "body_a", g, folder)?;
        let (spec_b, body_b, state_b) = build_body(&loc, &self.body_b, "body_b", g, folder)?;
        let notes = [("body_a", &body_a), ("body_b", &body_b)]
            .iter()
            .filter_map(|(table, b)| b.note().map(|n| format!("{table}: {n}")))
            .collect();
        let initial = TwoBodyState::new(state_a, state_b);
        if initial.separation() == 0.0 {
            return Err(loc.at(
                &self.body_b.get_ref().position,
                "body_b.position",
                "the centroids coincide: move body B away from body A",
            ));
        }
        let escape_distance = match &self.escape_distance {
            None => Some(DEFAULT_ESCAPE_FACTOR * initial.separation()),
            Some(d) if *d.get_ref() == Real::INFINITY => None,
            Some(d) if d.get_ref().is_finite() && *d.get_ref() > initial.separation() => {
                Some(*d.get_ref())
            }
            Some(d) => {
                return Err(loc.at(
                    d,
                    "escape_distance",
                    format!(
                    "must be larger than the initial separation {} (or inf: never stop), got {}",
                    compact(initial.separation()),
                    compact(*d.get_ref())
                ),
                ))
            }
        };
        // Positions so large that 100 separations overflow are refused as out of range below.
        let escape_distance = escape_distance.filter(|d| d.is_finite());

        check_in_range(&initial, &body_a, &body_b, g).map_err(|reason| {
            loc.at(
                &self.body_b.get_ref().position,
                "body_b.position",
                reason.to_string(),
            )
        })?;

        let integrator = build_integrator(&loc, &self.integrator)?;
        if let IntegratorChoice::Fixed { step, .. } = integrator {
            let time_scale = dynamical_time(&initial, &body_a, &body_b, g);
            if let Err(reason) = step_fits(step, t_end - t_start)
                .and_then(|()| step_resolves_orbit(step, time_scale))
            {
                let at = self.integrator.get_ref().step.as_ref().map_or_else(
                    || loc.at(&self.integrator, "integrator.step", ""),
                    |s| loc.at(s, "integrator.step", ""),
                );
                return Err(SceneError {
                    message: reason.to_string(),
                    ..at
                });
            }
        }

        let interaction_tolerance = match &self.interaction.tolerance {
            Some(t) => {
                let v = positive(t, "interaction.tolerance")?;
                if !(1e-15..=1e-2).contains(&v) {
                    return Err(loc.at(
                        t,
                        "interaction.tolerance",
                        format!("must lie in [1e-15, 1e-2], got {}", compact(v)),
                    ));
                }
                v
            }
            None => 1e-12,
        };

        let output = match (&self.output.every, &self.output.interval) {
            (Some(_), Some(i)) => {
                return Err(loc.at(
                    i,
                    "output.interval",
                    "give either output.every or output.interval, not both",
                ))
            }
            (Some(n), None) if *n.get_ref() < 1 => {
                return Err(loc.at(
                    n,
                    "output.every",
                    format!("must be a positive whole number, got {}", n.get_ref()),
                ))
            }
            (Some(n), None) => {
                OutputCadence::Every(usize::try_from(*n.get_ref()).unwrap_or(usize::MAX))
            }
            (None, Some(i)) => {
                let dt = positive(i, "output.interval")?;
                let rows = (t_end - t_start) / dt;
                if rows > MAX_INTERVAL_ROWS {
                    return Err(loc.at(
                        i,
                        "output.interval",
                        format!(
                            "would write {} rows over t = {}…{}: choose an interval of at least {}",
                            compact(rows.ceil()),
                            compact(t_start),
                            compact(t_end),
                            compact((t_end - t_start) / MAX_INTERVAL_ROWS)
                        ),
                    ));
                }
                OutputCadence::Interval(dt)
            }
            (None, None) => OutputCadence::Default,
        };
        let figures = match &self.output.figures {
            Some(f) => {
                let mut list = Vec::new();
                for kind in f.get_ref() {
                    if list.contains(kind) {
                        return Err(loc.at(f, "output.figures", "lists a figure twice"));
                    }
                    list.push(*kind);
                }
                list
            }
            None => FigureKind::ALL.to_vec(),
        };

        Ok(Scene {
            name,
            description: self.description.clone(),
            gravitational_constant: g,
            spec_a,
            spec_b,
            body_a,
            body_b,
            initial,
            t_start,
            t_end,
            escape_distance,
            integrator,
            interaction_tolerance,
            tabulate: self.interaction.tabulate.unwrap_or(true),
            output,
            figures,
            notes,
        })
    }
}

fn build_body(
    loc: &Locator<'_>,
    body: &Spanned<BodyFile>,
    table: &str,
    g: Real,
    folder: Option<&Path>,
) -> Result<(Spec, BuiltBody, BodyState), SceneError> {
    let b = body.get_ref();
    b.check_keys(loc, table)?;
    let shape_name = b.shape.get_ref().as_str();
    let Some(kind) = kinds::find(shape_name) else {
        return Err(loc.at(&b.shape, &format!("{table}.shape"), "unknown shape"));
    };
    let field = |name: &str| format!("{table}.{name}");
    for (name, value) in &b.keys {
        if kind.key(name).is_none() {
            return Err(loc.at(
                value,
                &field(name),
                format!(
                    "a {shape_name} has no {name}; it takes {}: remove this line or change the shape",
                    kind.scene_keys_text()
                ),
            ));
        }
    }
    let missing = |name: &str| {
        loc.at(
            &b.shape,
            &field(name),
            format!("a {shape_name} needs {name}: add it to [{table}]"),
        )
    };
    let mut values = Vec::new();
    for key in kind.keys {
        let Some((_, v)) = b.keys.iter().find(|(k, _)| k == key.scene) else {
            if key.required {
                return Err(missing(key.scene));
            }
            continue;
        };
        let name = key.scene;
        let value = match key.value {
            ValueKind::Length => {
                let x = number(v.get_ref()).ok_or_else(|| {
                    loc.at(
                        v,
                        &field(name),
                        "must be a positive finite length (a number)",
                    )
                })?;
                Given::Number(
                    kinds::positive_length(x)
                        .map_err(|e| loc.at(v, &field(name), e.to_string()))?,
                )
            }
            ValueKind::Lengths => {
                let n = key.cli.len();
                let xs: Option<Vec<Real>> = match v.get_ref() {
                    toml::Value::Array(items) if items.len() == n => {
                        items.iter().map(number).collect()
                    }
                    _ => None,
                };
                let names = key.cli.join(", ");
                match xs {
                    Some(xs) if xs.iter().all(|x| x.is_finite() && *x > 0.0) => Given::Numbers(xs),
                    Some(xs) => {
                        return Err(loc.at(
                            v,
                            &field(name),
                            format!(
                                "must be {n} positive finite lengths [{names}], got [{}]",
                                xs.iter()
                                    .map(|&x| compact(x))
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            )
                            .replacen(
                                "must be 3 ",
                                "must be three ",
                                1,
                            ),
                        ))
                    }
                    None => {
                        return Err(loc.at(
                            v,
                            &field(name),
                            format!("must be an array of {n} lengths [{names}]"),
                        ))
                    }
                }
            }
            ValueKind::Path => match v.get_ref() {
                toml::Value::String(p) if !p.trim().is_empty() => {
                    Given::Text(kinds::polyhedron::resolve(p.trim(), folder))
                }
                _ => return Err(loc.at(v, &field(name), "must be a file path (a string)")),
            },
            ValueKind::Unit => match v.get_ref() {
                toml::Value::String(u) if u == "m" || u == "km" => Given::Text(u.clone()),
                other => {
                    return Err(loc.at(
                        v,
                        &field(name),
                        format!("must be \"m\" or \"km\", got {other}"),
                    ))
                }
            },
            ValueKind::Flag => match v.get_ref() {
                toml::Value::Boolean(f) => Given::Flag(*f),
                other => {
                    return Err(loc.at(
                        v,
                        &field(name),
                        format!("must be true or false, got {other}"),
                    ))
                }
            },
        };
        values.push((key.scene, value));
    }
    let values = Values(values);
    (kind.check)(&values).map_err(|e| match b.keys.iter().find(|(k, _)| k == e.key) {
        Some((_, v)) => loc.at(v, &field(e.key), e.message),
        None => loc.at(&b.shape, &field(e.key), e.message),
    })?;
    let amount_value = |v: &Spanned<Real>, name: &str| -> Result<Real, SceneError> {
        let x = *v.get_ref();
        if x.is_finite() && x > 0.0 {
            Ok(x)
        } else {
            Err(loc.at(
                v,
                &field(name),
                format!("must be a positive finite number, got {}", compact(x)),
            ))
        }
    };
    let amount = match (&b.mass, &b.density) {
        (Some(_), Some(d)) => {
            return Err(loc.at(
                d,
                &field("density"),
                "give either mass or density, not both",
            ))
        }
        (Some(m), None) => Amount::Mass(amount_value(m, "mass")?),
        (None, Some(d)) => {
            if !kind.solid {
                return Err(loc.at(
                    d,
                    &field("density"),
                    format!("a {shape_name} has no volume density: give its mass instead"),
                ));
            }
            Amount::Density(amount_value(d, "density")?)
        }
        (None, None) => {
            return Err(loc.at(
                &b.shape,
                &field("mass"),
                format!("a {shape_name} needs mass (or density for a solid): add it to [{table}]"),
            ))
        }
    };
    let spec = Spec {
        kind,
        values,
        amount,
    };
    // A mesh that cannot be read or used is blamed on its `mesh` line.
    let blame = b.keys.iter().find(|(k, _)| k == "mesh").map_or_else(
        || loc.at(&b.shape, table, ""),
        |(_, v)| loc.at(v, &field("mesh"), ""),
    );
    let built = spec.build(g).map_err(|e| {
        let at = match e {
            crate::spec::SpecError::Mesh { .. } | crate::spec::SpecError::Polyhedron { .. } => {
                blame.clone()
            }
            _ => loc.at(&b.shape, table, ""),
        };
        SceneError {
            message: e.to_string(),
            ..at
        }
    })?;
    let vec3 = |v: &Spanned<[Real; 3]>, name: &str| -> Result<Vec3, SceneError> {
        let a = *v.get_ref();
        if a.iter().all(|x| x.is_finite()) {
            Ok(Vec3::new(a[0], a[1], a[2]))
        } else {
            Err(loc.at(v, &field(name), "must be three finite numbers [x, y, z]"))
        }
    };
    let position = vec3(&b.position, "position")?;
    let velocity = vec3(&b.velocity, "velocity")?;
    let mut state = BodyState::new(position, velocity);
    if let Some(o) = &b.orientation {
        state.orientation = nalgebra::UnitQuaternion::from_scaled_axis(vec3(o, "orientation")?);
    }
    match (&b.angular_velocity, &b.angular_velocity_body) {
        (Some(_), Some(w)) => {
            return Err(loc.at(
                w,
                &field("angular_velocity_body"),
                "give either angular_velocity (world frame) or angular_velocity_body (body frame), not both",
            ))
        }
        (Some(w), None) => state.angular_velocity = vec3(w, "angular_velocity")?,
        (None, Some(w)) => {
            state.angular_velocity = state.orientation * vec3(w, "angular_velocity_body")?;
        }
        (None, None) => {}
    }
    if kind.name == "point" && state.angular_velocity != Vec3::zeros() {
        let message =
            "a point mass cannot rotate: remove the angular velocity or give the body a size";
        return Err(
            match b
                .angular_velocity
                .as_ref()
                .or(b.angular_velocity_body.as_ref())
            {
                Some(w) => loc.at(w, &field("angular_velocity"), message),
                None => loc.at(&b.shape, &field("angular_velocity"), message),
            },
        );
    }
    Ok((spec, built, state))
}

/// A TOML number (integer or float) as a real.
fn number(v: &toml::Value) -> Option<Real> {
    match v {
        toml::Value::Float(x) => Some(*x),
        toml::Value::Integer(i) => Some(*i as Real),
        _ => None,
    }
}

fn build_integrator(
    loc: &Locator<'_>,
    integrator: &Spanned<IntegratorFile>,
) -> Result<IntegratorChoice, SceneError> {
    let i = integrator.get_ref();
    let method: IntegratorName = i
        .method
        .get_ref()
        .trim()
        .to_ascii_lowercase()
        .parse()
        .map_err(|e: surfgrav_dynamics::IntegratorChoiceError| {
            loc.at(&i.method, "integrator.method", e.to_string())
        })?;
    let positive = |v: &Spanned<Real>, name: &str| -> Result<Real, SceneError> {
        let x = *v.get_ref();
        if x.is_finite() && x > 0.0 {
            Ok(x)
        } else {
            Err(loc.at(
                v,
                name,
                format!("must be a positive finite number, got {}", compact(x)),
            ))
        }
    };
    if method.is_adaptive() {
        if let Some(s) = &i.step {
            return Err(loc.at(
                s,
                "integrator.step",
                format!(
                    "{} chooses its own steps: give integrator.tolerance instead of step",
                    method.name()
                ),
            ));
        }
        let t = i.tolerance.as_ref().ok_or_else(|| {
            loc.at(
                &i.method,
                "integrator.tolerance",
                format!(
                    "{} needs a tolerance, e.g. tolerance = 1e-10",
                    method.name()
                ),
            )
        })?;
        let tolerance = positive(t, "integrator.tolerance")?;
        if let Err(reason) = adaptive_tolerance_in_range(tolerance) {
            return Err(loc.at(t, "integrator.tolerance", reason.to_string()));
        }
        Ok(IntegratorChoice::Adaptive { method, tolerance })
    } else {
        if let Some(t) = &i.tolerance {
            return Err(loc.at(
                t,
                "integrator.tolerance",
                format!(
                    "{} is a fixed-step method: give integrator.step instead of tolerance",
                    method.name()
                ),
            ));
        }
        let s = i.step.as_ref().ok_or_else(|| {
            loc.at(
                &i.method,
                "integrator.step",
                format!("{} needs a step, e.g. step = 0.1", method.name()),
            )
        })?;
        let step = positive(s, "integrator.step")?;
        Ok(IntegratorChoice::Fixed { method, step })
    }
}

impl Scene {
    /// Replaces the end time, step, integrator or tolerance (command-line overrides). The
    /// integrator's step or tolerance is kept when the kind (fixed or adaptive) stays; a switch
    /// of kind needs the new step or tolerance.
    ///
    /// # Errors
    /// A message naming the option and what to change.
    pub fn override_with(
        &mut self,
        t_end: Option<Real>,
        step: Option<Real>,
        method: Option<IntegratorName>,
        tolerance: Option<Real>,
    ) -> Result<(), OverrideError> {
        let positive = |name: &'static str, v: Real| {
            if v.is_finite() && v > 0.0 {
                Ok(v)
            } else {
                Err(OverrideError::NotPositive { name, value: v })
            }
        };
        if let Some(t) = t_end {
            if !(t.is_finite() && t > self.t_start) {
                return Err(OverrideError::EndNotAfterStart {
                    start: self.t_start,
                    value: t,
                });
            }
            self.t_end = t;
        }
        let step_given = step.is_some();
        let method = method.unwrap_or(self.integrator.method());
        let name = method.name();
        if method.is_adaptive() {
            if step.is_some() {
                return Err(OverrideError::StepForAdaptive { method: name });
            }
            let tolerance = match (tolerance, self.integrator) {
                (Some(t), _) => {
                    let t = positive("--tolerance", t)?;
                    adaptive_tolerance_in_range(t).map_err(|reason| OverrideError::OutOfRange {
                        flag: "--tolerance",
                        reason,
                    })?;
                    t
                }
                (None, IntegratorChoice::Adaptive { tolerance, .. }) => tolerance,
                (None, IntegratorChoice::Fixed { .. }) => {
                    return Err(OverrideError::NeedsTolerance { method: name })
                }
            };
            self.integrator = IntegratorChoice::Adaptive { method, tolerance };
        } else {
            if tolerance.is_some() {
                return Err(OverrideError::ToleranceForFixed { method: name });
            }
            let step = match (step, self.integrator) {
                (Some(s), _) => positive("--dt", s)?,
                (None, IntegratorChoice::Fixed { step, .. }) => step,
                (None, IntegratorChoice::Adaptive { .. }) => {
                    return Err(OverrideError::NeedsStep { method: name })
                }
            };
            self.integrator = IntegratorChoice::Fixed { method, step };
            step_fits(step, self.t_end - self.t_start).map_err(|reason| {
                OverrideError::OutOfRange {
                    flag: if step_given { "--dt" } else { "--t-end" },
                    reason,
                }
            })?;
            let time_scale = dynamical_time(
                &self.initial,
                &self.body_a,
                &self.body_b,
                self.gravitational_constant,
            );
            step_resolves_orbit(step, time_scale).map_err(|reason| OverrideError::OutOfRange {
                flag: "--dt",
                reason,
            })?;
        }
        Ok(())
    }
}

/// Why a command-line override of a scene ([`Scene::override_with`]) is refused; the message
/// names the option and what to change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum OverrideError {
    /// A step or tolerance that is not a positive finite number.
    #[error("{name} must be a positive finite number, got {}", compact(*.value))]
    NotPositive {
        /// The option.
        name: &'static str,
        /// The value given.
        value: Real,
    },
    /// An end time not after the start.
    #[error("--t-end must be finite and greater than the start time {}, got {}", compact(*.start), compact(*.value))]
    EndNotAfterStart {
        /// The scene's start time.
        start: Real,
        /// The end time given.
        value: Real,
    },
    /// A step for an adaptive method.
    #[error("--dt does not apply to the adaptive integrator {method}: give --tolerance")]
    StepForAdaptive {
        /// The method.
        method: &'static str,
    },
    /// An adaptive method without a tolerance.
    #[error("the adaptive integrator {method} needs --tolerance")]
    NeedsTolerance {
        /// The method.
        method: &'static str,
    },
    /// A tolerance for a fixed-step method.
    #[error("--tolerance does not apply to the fixed-step integrator {method}: give --dt")]
    ToleranceForFixed {
        /// The method.
        method: &'static str,
    },
    /// A fixed-step method without a step.
    #[error("the fixed-step integrator {method} needs --dt")]
    NeedsStep {
        /// The method.
        method: &'static str,
    },
    /// A step or tolerance out of the range that can work (the message says why and what to
    /// choose).
    #[error("{flag}: {reason}")]
    OutOfRange {
        /// The option at fault.
        flag: &'static str,
        /// Why, and what to choose.
        reason: RangeError,
    },
}

/// Numbers a run cannot work with (the message says why and what to choose): reported at the
/// scene file's line or with the command-line flag.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RangeError {
    /// A fixed step longer than the run.
    #[error(
        "the step {} is longer than the run (t_end − t_start = {}): choose a step well below \
         the run's length and the orbit's period (the paper's presets use 0.1 for t = 300)",
        compact(*.step),
        compact(*.span)
    )]
    StepLongerThanRun {
        /// The step.
        step: Real,
        /// t_end − t_start.
        span: Real,
    },
    /// A fixed step longer than the orbit's dynamical time at the start.
    #[error(
        "the step {} is longer than the orbit's dynamical time √(r³/G(m_A + m_B)) = {} at \
         the start: no fixed-step method can follow the orbit; choose a step of about a \
         hundredth of it or less (e.g. {})",
        compact(*.step),
        crate::cli::significant(*.time_scale, 3),
        crate::cli::significant(*.time_scale / 100.0, 1)
    )]
    StepBeyondOrbit {
        /// The step.
        step: Real,
        /// √(r³/G(m_A + m_B)) at the start.
        time_scale: Real,
    },
    /// A derived quantity of the initial state overflows.
    #[error(
        "values out of range: {what} overflows double precision (separation {}): rescale the \
         units so that positions, velocities and masses stay well inside 1e-150…1e150",
        compact(*.separation)
    )]
    Overflow {
        /// Which quantity.
        what: &'static str,
        /// The initial separation.
        separation: Real,
    },
    /// The squared separation underflows to zero.
    #[error(
        "values out of range: the squared separation {}² underflows to zero: rescale the units",
        compact(*.separation)
    )]
    Underflow {
        /// The initial separation.
        separation: Real,
    },
    /// An adaptive tolerance outside what double precision can meet.
    #[error(
        "must lie in [{:e}, {}) for an adaptive integrator (double precision cannot meet less \
         than ~1e-15), got {tolerance:e}; 1e-15 to 1e-6 are sensible",
        IntegratorKind::MIN_TOLERANCE,
        IntegratorKind::MAX_TOLERANCE
    )]
    Tolerance {
        /// The tolerance given.
        tolerance: Real,
    },
}

/// A fixed step must not be longer than the run: a step of 500 over t = 300 would jump the
/// bodies across their whole orbit (and out of any tabulated range) in one go.
fn step_fits(step: Real, span: Real) -> Result<(), RangeError> {
    if step <= span {
        Ok(())
    } else {
        Err(RangeError::StepLongerThanRun { step, span })
    }
}

/// The orbit's dynamical time at the start, $\tau = \sqrt{r^3 / (G(m_A + m_B))}$ (a circular
/// orbit of radius r has period $2\pi\tau$; paper-2s: τ = 13.1, T_r = 47.4).
fn dynamical_time(initial: &TwoBodyState, body_a: &BuiltBody, body_b: &BuiltBody, g: Real) -> Real {
    let mass = body_a.potential().mass() + body_b.potential().mass();
    let r = initial.separation();
    (r * r * r / (g * mass)).sqrt()
}

/// A fixed step longer than the orbit's dynamical time τ cannot follow the orbit (RK4 is
/// unstable beyond hω ≈ 2.8 with ω = 1/τ on a circular orbit, and any method's error is of
/// order one there): it would give a few steps of meaningless numbers. Refused; a step of
/// τ/100 or less is sensible. (Not a guarantee: close approaches need a smaller step still.)
fn step_resolves_orbit(step: Real, time_scale: Real) -> Result<(), RangeError> {
    if !(time_scale.is_finite() && step > time_scale) {
        Ok(())
    } else {
        Err(RangeError::StepBeyondOrbit { step, time_scale })
    }
}

/// The initial state's derived quantities (squared distances, energies, angular momentum) must
/// be finite and the separation's square nonzero: positions of ±1e307 overflow r² and every
/// later error estimate, which is bad input, not a tolerance to relax.
fn check_in_range(
    initial: &TwoBodyState,
    body_a: &BuiltBody,
    body_b: &BuiltBody,
    g: Real,
) -> Result<(), RangeError> {
    let (ma, mb) = (body_a.potential().mass(), body_b.potential().mass());
    let (a, b) = (&initial.body_a, &initial.body_b);
    let separation = initial.separation();
    let quantities = [
        ("the squared separation", separation * separation),
        (
            "body A's squared distance from the origin",
            a.position.norm_squared(),
        ),
        (
            "body B's squared distance from the origin",
            b.position.norm_squared(),
        ),
        (
            "the kinetic energy",
            0.5 * ma * a.velocity.norm_squared() + 0.5 * mb * b.velocity.norm_squared(),
        ),
        (
            "the potential energy G m_A m_B / r",
            g * ma * mb / separation,
        ),
        (
            "the angular momentum",
            (a.position.cross(&a.velocity) * ma + b.position.cross(&b.velocity) * mb).norm(),
        ),
    ];
    for (what, value) in quantities {
        if !value.is_finite() {
            return Err(RangeError::Overflow { what, separation });
        }
    }
    if separation * separation == 0.0 {
        return Err(RangeError::Underflow { separation });
    }
    Ok(())
}

/// An adaptive integrator's tolerance must lie in [`IntegratorKind::MIN_TOLERANCE`],
/// [`IntegratorKind::MAX_TOLERANCE`]): below a few machine epsilons the error estimate is
/// rounding noise and the step size collapses. Checked here so the message can point at the
/// scene file's line or the command-line flag.
fn adaptive_tolerance_in_range(tolerance: Real) -> Result<(), RangeError> {
    if (IntegratorKind::MIN_TOLERANCE..IntegratorKind::MAX_TOLERANCE).contains(&tolerance) {
        Ok(())
    } else {
        Err(RangeError::Tolerance { tolerance })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::presets;

    fn paper_2s() -> &'static str {
        presets::find("paper-2s").unwrap().toml
    }

    /// Replaces `from` by `to` in the paper-2s text and returns the build error.
    fn error_after(from: &str, to: &str) -> SceneError {
        let text = paper_2s().replacen(from, to, 1);
        assert_ne!(text, paper_2s(), "`{from}` not in the preset");
        match SceneFile::parse(&text, "s.toml").and_then(|f| f.build(&text, "s.toml")) {
            Ok(_) => panic!("`{to}` was accepted"),
            Err(e) => e,
        }
    }

    fn line_containing(text: &str, needle: &str) -> usize {
        text.lines().position(|l| l.contains(needle)).unwrap() + 1
    }

    #[test]
    fn errors_name_file_line_field_and_fix() {
        let cases: &[(&str, &str, &str, &str)] = &[
            // (replace, with, line that must be blamed, words the message must contain)
            (
                "polar_radius = 0.25",
                "polar_radius = -0.25",
                "polar_radius = -0.25",
                "body_a.polar_radius: must be a positive",
            ),
            (
                "mass = 1.0\nposition = [3.5",
                "mass = 0.0\nposition = [3.5",
                "mass = 0.0",
                "body_b.mass: must be a positive",
            ),
            (
                "step = 0.1",
                "step = 0",
                "step = 0",
                "integrator.step: must be a positive",
            ),
            (
                "t_end = 300.0",
                "t_end = -1.0",
                "t_end = -1.0",
                "t_end: must be finite and greater",
            ),
            (
                "method = \"rk4\"",
                "method = \"rk5\"",
                "method = \"rk5\"",
                "unknown integrator 'rk5'; valid names: rk4",
            ),
            (
                "polar_radius = 0.25",
                "polar_radius = 0.25\nradius = 2.0",
                "radius = 2.0",
                "body_a.radius: a spheroid has no radius",
            ),
            (
                "polar_radius = 0.25",
                "polar_radius = 0.25\ncolour = 2.0",
                "colour = 2.0",
                "unknown field `colour`",
            ),
            (
                "shape = \"spheroid\"",
                "shape = \"cube\"",
                "shape = \"cube\"",
                "unknown variant `cube`",
            ),
            (
                "step = 0.1",
                "step = 0.1\ntolerance = 1e-9",
                "tolerance = 1e-9",
                "give integrator.step instead",
            ),
            (
                "method = \"rk4\"\nstep = 0.1",
                "method = \"dop853\"\ntolerance = 1e-18",
                "tolerance = 1e-18",
                "integrator.tolerance: must lie in [1e-15, 1)",
            ),
            (
                "gravitational_constant = 1.0",
                "gravitational_constant = 1.0\nunits = \"si\"",
                "units = \"si\"",
                "not both",
            ),
            (
                "t_end = 300.0",
                "t_end = 300.0 300",
                "t_end = 300.0 300",
                "",
            ),
        ];
        for (from, to, blamed, words) in cases {
            let from = from.replace("\\n", "\n");
            let to = to.replace("\\n", "\n");
            let text = paper_2s().replacen(&from, &to, 1);
            let e = error_after(&from, &to);
            let shown = e.to_string();
            assert_eq!(e.file, "s.toml");
            assert_eq!(e.line, Some(line_containing(&text, blamed)), "{shown}");
            assert!(
                shown.starts_with(&format!("s.toml:{}: ", e.line.unwrap())),
                "{shown}"
            );
            assert!(shown.contains(words), "`{shown}` lacks `{words}`");
            assert!(!shown.contains('\n'), "one line: {shown}");
        }
    }

    #[test]
    fn missing_fields_are_named() {
        let e = error_after("polar_radius = 0.25\n", "");
        assert!(
            e.to_string()
                .contains("body_a.polar_radius: a spheroid needs polar_radius"),
            "{e}"
        );
        let e = error_after("mass = 1.0\n", "");
        assert!(
            e.to_string().contains("body_a.mass: a spheroid needs mass"),
            "{e}"
        );
        let e = error_after("step = 0.1\n", "");
        assert!(e.to_string().contains("rk4 needs a step"), "{e}");
        let e = error_after("t_end = 300.0\n", "");
        assert!(e.to_string().contains("t_end"), "{e}");
    }

    #[test]
    fn overrides_switch_integrators_and_check_values() {
        let mut s = presets::find("paper-2s").unwrap().scene().unwrap();
        s.override_with(Some(10.0), Some(0.05), Some(IntegratorName::Yoshida4), None)
            .unwrap();
        assert_eq!(s.t_end, 10.0);
        assert_eq!(
            s.integrator,
            IntegratorChoice::Fixed {
                method: IntegratorName::Yoshida4,
                step: 0.05
            }
        );
        assert!(s
            .override_with(None, None, Some(IntegratorName::Dopri5), None)
            .is_err());
        s.override_with(None, None, Some(IntegratorName::Dopri5), Some(1e-9))
            .unwrap();
        assert!(s
            .override_with(None, None, Some(IntegratorName::Rk4), None)
            .unwrap_err()
            .to_string()
            .contains("--dt"));
        assert!(s.override_with(Some(-1.0), None, None, None).is_err());
        assert!(s.override_with(None, Some(0.1), None, None).is_err());
        assert!("euler".parse::<IntegratorName>().is_err());
    }
}
