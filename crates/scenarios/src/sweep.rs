//! Parameter sweeps: one base scene, many variants of it, each run as its own task
//! (`surfgrav sweep SWEEP.toml`).
//!
//! ```toml
//! base = "paper-2s"            # a preset, or a scene file (relative to this file)
//! name = "mass-study"          # optional: names the default output folder (default: file stem)
//! save_trajectory = false      # trajectory.csv in every task folder (default false)
//! save_figures = false         # the run's figures in every task folder (default false)
//! remove = ["body_b.mass"]     # fields of the base that no task should have (optional)
//! draws = 100                  # Monte Carlo: tasks per grid point (needs a distribution)
//! seed = 7                     # of the draws (default 0)
//!
//! [set]                        # the same change for every task (optional)
//! t_end = 30.0
//! integrator.step = 0.05
//!
//! [[vary]]                     # a grid: values, linspace or logspace
//! field = "body_b.density"
//! values = [0.5, 1.0, 2.0]     # or linspace = [a, b, n], logspace = [a, b, n] (geometric, a, b > 0)
//!
//! [[vary]]                     # a distribution (with draws): uniform, normal or loguniform
//! field = "body_a.semi_axes[2]"
//! uniform = [0.2, 0.3]         # or normal = [mean, sd], loguniform = [lo, hi],
//!                              # or distribution = "uniform(0.2, 0.3)"
//! ```
//!
//! **Fields.** A field is addressed by its dotted path as written in scene files (`t_end`,
//! `body_b.mass`, `integrator.step`, `body_a.semi_axes`), and one number of a vector by its index
//! (`body_b.angular_velocity[2]`; absent vectors start as `[0, 0, 0]`). Each task's scene is the
//! base scene's TOML document with the edits applied, read and validated by the scene reader
//! ([`SceneFile::parse`] and [`SceneFile::build`]), so every scene check holds and an unknown
//! field is refused by name. A field given in two equivalent ways replaces its alternative in
//! the same table: setting `density` drops the base's `mass` and the mass follows from density
//! × volume (and the reverse); `angular_velocity`, `angular_velocity_body` and `spin` replace
//! each other, as do `units` and `gravitational_constant`, and `output.every` and
//! `output.interval`. Any other field the base has and a task must not is listed in `remove`.
//!
//! **Tasks.** Grids combine as a Cartesian product, the last `[[vary]]` changing fastest; with
//! `draws = N` every grid point gets N draws (task = grid point × N + draw). Draw k of a
//! parameter depends only on the seed, k and the parameter's place among the distributions
//! (SplitMix64 streams; normal by Box–Muller): the first 100 draws of `draws = 1000` are the
//! tasks of `draws = 100`, and every grid point sees the same draws. Every task's scene is
//! built before anything runs: a parameter set the scene checks refuse is bad input for the
//! whole sweep (exit code 2, nothing written), named with its task and values.
//!
//! **Output.** `tasks/NNNNN/` per task (`scene.toml`, the exact scene: `surfgrav run
//! tasks/NNNNN/scene.toml` repeats it; `summary.json` as `surfgrav run` writes it; `task.toml`,
//! the task's parameters and key results; `trajectory.csv` and figures if asked), written under
//! a hidden name and renamed when complete ([`crate::output::Staging`]): a task is finished iff
//! its `summary.json` exists, and a re-run skips finished tasks. `manifest.json` lists every
//! task's parameters and status (`pending`, `done`, `failed` with the message) and the
//! definition hash (FNV-1a of every task's scene text); `results.csv` has one row per task.
//! `--shard K/N` runs the tasks whose index is K mod N and writes `manifest-shard-K-of-N.json`
//! and `results-shard-K-of-N.csv` instead, so shards can share one folder; `surfgrav sweep merge
//! DIR...` gathers them into one `results.csv` (and `manifest.json`), refusing shards of another
//! sweep.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

use clap::{Args, Subcommand};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use surfgrav_potentials::Real;
use toml::{Spanned, Table, Value};

use crate::cli::CliError;
use crate::output::{self, Staging, TrajectoryWriter};
use crate::presets;
use crate::scene::{Scene, SceneError, SceneFile};
use crate::simulate;

/// `surfgrav sweep`: the arguments.
#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct SweepArgs {
    /// `merge DIR...`: gather shard outputs.
    #[command(subcommand)]
    pub action: Option<SweepAction>,
    /// The sweep file (TOML).
    #[arg(value_name = "SWEEP.toml", required = true)]
    pub file: Option<PathBuf>,
    /// Output folder (default: the sweep's name); an existing folder of the same sweep is
    /// resumed.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Run only the tasks whose index is K mod N (0 ≤ K < N).
    #[arg(long, value_name = "K/N")]
    pub shard: Option<String>,
    /// Tasks run at once (default: every core).
    #[arg(long, value_name = "J")]
    pub jobs: Option<String>,
    /// No progress bar and no summary on stdout.
    #[arg(long)]
    pub quiet: bool,
}

/// Sub-commands of `surfgrav sweep`.
#[derive(Debug, Subcommand)]
pub enum SweepAction {
    /// Gather the outputs of shards (`--shard K/N`) of one sweep into results.csv and
    /// manifest.json, sorted by task index.
    Merge {
        /// Sweep folders holding shard outputs (one folder shared by every shard, or one each).
        #[arg(value_name = "DIR", required = true)]
        dirs: Vec<PathBuf>,
        /// Where to write results.csv and manifest.json (default: the first DIR).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// No summary on stdout.
        #[arg(long)]
        quiet: bool,
    },
}

// ---------------------------------------------------------------------------------------------
// Errors.

/// Why a sweep cannot run, or a part of it failed. The messages are the command line's.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SweepError {
    /// The sweep file (or a task's scene made from it) is wrong: one line naming the file, the
    /// line, the field and what to change. Exit code 2; nothing is written.
    #[error("{0}")]
    Definition(String),
    /// An option or the output folder is wrong (`--shard`, `--jobs`, `--out`, merge folders).
    /// Exit code 2.
    #[error("{0}")]
    Usage(String),
    /// A bad `--shard K/N`.
    #[error(transparent)]
    Shard(#[from] ShardError),
    /// A task's run failed (its message as in `manifest.json`).
    #[error(transparent)]
    Run(#[from] simulate::RunError),
    /// A file could not be read or written.
    #[error("{0}")]
    Io(String),
}

impl From<SweepError> for CliError {
    fn from(e: SweepError) -> Self {
        match e {
            SweepError::Definition(_) | SweepError::Usage(_) | SweepError::Shard(_) => {
                CliError::Input(e.to_string())
            }
            SweepError::Run(_) | SweepError::Io(_) => CliError::Failed(e.to_string()),
        }
    }
}

/// A malformed field path.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum FieldPathError {
    /// Not dotted keys with an optional `[index]`.
    #[error("`{text}` is not a field path like body_b.mass or body_a.semi_axes[2]")]
    NotAPath {
        /// The text given.
        text: String,
    },
    /// The index in `[...]` is not a whole number.
    #[error("`{text}`: the index in [...] must be 0, 1 or 2")]
    BadIndex {
        /// The text given.
        text: String,
    },
}

/// Why an edit of the base scene cannot be applied.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum EditError {
    /// A path without keys.
    #[error("an empty field path")]
    EmptyPath,
    /// A key on the way is a value, not a table.
    #[error("{table} is a value, not a table: {path} cannot be set")]
    NotATable {
        /// The keys walked so far.
        table: String,
        /// The path as written.
        path: String,
    },
    /// An index into something that is not a vector.
    #[error("{path} is not a vector: write it without [{index}]")]
    NotAVector {
        /// The dotted path.
        path: String,
        /// The index given.
        index: usize,
    },
    /// An index past the vector's end.
    #[error("{path}: index {index} is past the vector's {len} numbers")]
    IndexPastEnd {
        /// The path as written.
        path: String,
        /// The index given.
        index: usize,
        /// The vector's length.
        len: usize,
    },
    /// `remove` with an index.
    #[error("{path}: remove takes a whole field, without [...]")]
    IndexedRemove {
        /// The path as written.
        path: String,
    },
    /// `remove` of a field the base does not have.
    #[error("{path} is not in the base scene: nothing to remove")]
    NotInBase {
        /// The path as written.
        path: String,
    },
}

/// Bad parameters of a distribution.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DistributionError {
    /// A parameter is NaN or infinite.
    #[error("{kind}: the parameters must be finite numbers")]
    NotFinite {
        /// The distribution.
        kind: String,
    },
    /// uniform with lo ≥ hi.
    #[error("uniform(lo, hi) needs lo < hi, got lo = {lo}, hi = {hi}")]
    Uniform {
        /// Lower end.
        lo: Real,
        /// Upper end.
        hi: Real,
    },
    /// normal with sd ≤ 0.
    #[error("normal(mean, sd) needs sd > 0, got sd = {sd}")]
    Normal {
        /// Standard deviation.
        sd: Real,
    },
    /// loguniform without 0 < lo < hi.
    #[error("loguniform(lo, hi) needs 0 < lo < hi, got lo = {lo}, hi = {hi}")]
    LogUniform {
        /// Lower end.
        lo: Real,
        /// Upper end.
        hi: Real,
    },
    /// Not uniform, normal or loguniform.
    #[error("unknown distribution `{kind}`: expected uniform, normal or loguniform")]
    Unknown {
        /// The name given.
        kind: String,
    },
}

/// A bad `--shard K/N`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ShardError {
    /// K ≥ N.
    #[error(
        "--shard {text}: K must be below N (shards are numbered 0 to {last}), got K = {index}"
    )]
    OutOfRange {
        /// The text given.
        text: String,
        /// N − 1.
        last: usize,
        /// K.
        index: usize,
    },
    /// Not `K/N` with whole numbers, or N = 0.
    #[error("--shard {text}: expected K/N with whole numbers 0 ≤ K < N, e.g. --shard 0/4")]
    Malformed {
        /// The text given.
        text: String,
    },
}

// ---------------------------------------------------------------------------------------------
// The sweep file as written.

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SweepFile {
    base: Spanned<String>,
    #[serde(default)]
    name: Option<Spanned<String>>,
    #[serde(default)]
    save_trajectory: Option<bool>,
    #[serde(default)]
    save_figures: Option<bool>,
    #[serde(default)]
    remove: Option<Vec<Spanned<String>>>,
    #[serde(default)]
    draws: Option<Spanned<i64>>,
    #[serde(default)]
    seed: Option<Spanned<i64>>,
    #[serde(default)]
    set: Option<Spanned<Table>>,
    #[serde(default)]
    vary: Vec<Spanned<VaryFile>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct VaryFile {
    field: Spanned<String>,
    #[serde(default)]
    values: Option<Spanned<Vec<Value>>>,
    #[serde(default)]
    linspace: Option<Spanned<Vec<Value>>>,
    #[serde(default)]
    logspace: Option<Spanned<Vec<Value>>>,
    #[serde(default)]
    uniform: Option<Spanned<Vec<Value>>>,
    #[serde(default)]
    normal: Option<Spanned<Vec<Value>>>,
    #[serde(default)]
    loguniform: Option<Spanned<Vec<Value>>>,
    #[serde(default)]
    distribution: Option<Spanned<String>>,
}

// ---------------------------------------------------------------------------------------------
// Field paths and edits of a TOML document.

/// A field of a scene file: dotted keys and, for one number of a vector, an index.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FieldPath {
    keys: Vec<String>,
    index: Option<usize>,
    text: String,
}

impl FieldPath {
    /// Parses `body_b.mass` or `body_a.semi_axes[2]`.
    ///
    /// # Errors
    /// What is malformed.
    pub fn parse(text: &str) -> Result<Self, FieldPathError> {
        let trimmed = text.trim();
        let (head, index) = match trimmed.strip_suffix(']') {
            Some(rest) => {
                let (head, i) = rest
                    .rsplit_once('[')
                    .ok_or_else(|| FieldPathError::NotAPath { text: text.into() })?;
                let i: usize = i
                    .trim()
                    .parse()
                    .map_err(|_| FieldPathError::BadIndex { text: text.into() })?;
                (head, Some(i))
            }
            None => (trimmed, None),
        };
        let keys: Vec<String> = head.split('.').map(|k| k.trim().to_string()).collect();
        let valid =
            |k: &String| !k.is_empty() && k.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !keys.iter().all(valid) {
            return Err(FieldPathError::NotAPath { text: text.into() });
        }
        Ok(Self {
            keys,
            index,
            text: trimmed.to_string(),
        })
    }

    /// The path as written.
    pub fn as_str(&self) -> &str {
        &self.text
    }

    /// The dotted keys without the index.
    fn dotted(&self) -> String {
        self.keys.join(".")
    }
}

/// Keys that give the same quantity another way: setting one removes the others from its table.
const ALTERNATIVES: &[&[&str]] = &[
    &["mass", "density"],
    &["angular_velocity", "angular_velocity_body", "spin"],
    &["units", "gravitational_constant"],
    &["every", "interval"],
];

/// The table holding the path's last key, created where missing.
fn parent_table<'t>(doc: &'t mut Table, path: &FieldPath) -> Result<&'t mut Table, EditError> {
    let mut table = doc;
    let (_, parents) = path.keys.split_last().ok_or(EditError::EmptyPath)?;
    let mut walked = Vec::new();
    for key in parents {
        walked.push(key.as_str());
        let entry = table
            .entry(key.clone())
            .or_insert_with(|| Value::Table(Table::new()));
        table = match entry {
            Value::Table(t) => t,
            _ => {
                return Err(EditError::NotATable {
                    table: walked.join("."),
                    path: path.as_str().into(),
                })
            }
        };
    }
    Ok(table)
}

/// The value at `path` in the document (the whole vector for an indexed path), if present.
fn lookup<'t>(doc: &'t Table, path: &FieldPath) -> Option<&'t Value> {
    let (last, parents) = path.keys.split_last()?;
    let mut table = doc;
    for key in parents {
        table = table.get(key)?.as_table()?;
    }
    table.get(last)
}

/// A number for a field that was an integer stays one when it is whole (`output.every`), and
/// an integer for a float field becomes a float.
fn coerce(new: Value, old: Option<&Value>) -> Value {
    match (new, old) {
        (Value::Float(x), Some(Value::Integer(_))) if x.fract() == 0.0 && x.abs() < 9.0e15 => {
            Value::Integer(x as i64)
        }
        (Value::Integer(i), Some(Value::Float(_))) => Value::Float(i as f64),
        (new, _) => new,
    }
}

/// Sets `path` to `value` in the document, dropping the key's alternatives in its table.
fn set_field(doc: &mut Table, path: &FieldPath, value: Value) -> Result<(), EditError> {
    let table = parent_table(doc, path)?;
    let last = path.keys.last().cloned().unwrap_or_default();
    // `spin` is read as angular_velocity: write the canonical key.
    let key = if last == "spin" {
        "angular_velocity".to_string()
    } else {
        last
    };
    if key == "angular_velocity" {
        if let Some(spin) = table.remove("spin") {
            table.insert(key.clone(), spin);
        }
    }
    if let Some(group) = ALTERNATIVES.iter().find(|g| g.contains(&key.as_str())) {
        for other in group.iter().filter(|o| **o != key) {
            table.remove(*other);
        }
    }
    match path.index {
        None => {
            let value = coerce(value, table.get(&key));
            table.insert(key, value);
        }
        Some(i) => {
            let entry = table
                .entry(key.clone())
                .or_insert_with(|| Value::Array(vec![Value::Float(0.0); 3]));
            let Value::Array(items) = entry else {
                return Err(EditError::NotAVector {
                    path: path.dotted(),
                    index: i,
                });
            };
            let old = items
                .get(i)
                .cloned()
                .ok_or_else(|| EditError::IndexPastEnd {
                    path: path.as_str().into(),
                    index: i,
                    len: items.len(),
                })?;
            items[i] = coerce(value, Some(&old));
        }
    }
    Ok(())
}

/// Removes `path` from the document; it must be there.
fn remove_field(doc: &mut Table, path: &FieldPath) -> Result<(), EditError> {
    if path.index.is_some() {
        return Err(EditError::IndexedRemove {
            path: path.as_str().into(),
        });
    }
    if lookup(doc, path).is_none() {
        return Err(EditError::NotInBase {
            path: path.as_str().into(),
        });
    }
    let table = parent_table(doc, path)?;
    table.remove(path.keys.last().map(String::as_str).unwrap_or_default());
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Generators: grids and distributions.

/// A probability distribution of one scalar parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Distribution {
    /// Uniform on [lo, hi).
    Uniform(Real, Real),
    /// Normal with mean and standard deviation.
    Normal(Real, Real),
    /// Uniform in log between lo > 0 and hi.
    LogUniform(Real, Real),
}

impl Distribution {
    /// Checks the parameters.
    ///
    /// # Errors
    /// Non-finite values, lo ≥ hi, sd ≤ 0, a loguniform lo ≤ 0; with what to change.
    pub fn new(kind: &str, a: Real, b: Real) -> Result<Self, DistributionError> {
        if !(a.is_finite() && b.is_finite()) {
            return Err(DistributionError::NotFinite { kind: kind.into() });
        }
        match kind {
            "uniform" if a < b => Ok(Self::Uniform(a, b)),
            "uniform" => Err(DistributionError::Uniform { lo: a, hi: b }),
            "normal" if b > 0.0 => Ok(Self::Normal(a, b)),
            "normal" => Err(DistributionError::Normal { sd: b }),
            "loguniform" if a > 0.0 && a < b => Ok(Self::LogUniform(a, b)),
            "loguniform" => Err(DistributionError::LogUniform { lo: a, hi: b }),
            other => Err(DistributionError::Unknown { kind: other.into() }),
        }
    }

    /// One draw from the stream.
    pub fn sample(&self, rng: &mut SplitMix64) -> Real {
        match *self {
            Self::Uniform(lo, hi) => lo + rng.uniform() * (hi - lo),
            Self::Normal(mean, sd) => {
                // Box–Muller; 1 − u lies in (0, 1], so the logarithm is finite.
                let u1 = 1.0 - rng.uniform();
                let u2 = rng.uniform();
                mean + sd * (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
            }
            Self::LogUniform(lo, hi) => (lo.ln() + rng.uniform() * (hi.ln() - lo.ln())).exp(),
        }
    }
}

/// SplitMix64 (Steele, Lea & Flood 2014): a 64-bit state advanced by the golden-ratio
/// increment and finalised by a bijective mix; small, fast and good enough for draws.
#[derive(Debug, Clone)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// The stream of draw `draw` of the `parameter`-th distribution for `seed`.
    pub fn stream(seed: u64, draw: u64, parameter: u64) -> Self {
        let mut s = Self(seed);
        let a = s.next_u64();
        let mut s = Self(a ^ draw.wrapping_mul(0xD1B5_4A32_D192_ED03));
        let b = s.next_u64();
        Self(b ^ parameter.wrapping_mul(0x8CB9_2BA7_2F3D_8DD7))
    }

    /// The next 64 bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform on [0, 1) with 53 random bits.
    pub fn uniform(&mut self) -> Real {
        (self.next_u64() >> 11) as Real * (1.0 / (1u64 << 53) as Real)
    }
}

/// How one parameter varies.
#[derive(Debug, Clone)]
enum Generator {
    Grid(Vec<Value>),
    Draw(Distribution),
}

/// One `[[vary]]`, validated.
#[derive(Debug, Clone)]
struct Parameter {
    path: FieldPath,
    line: usize,
    generator: Generator,
}

/// 64-bit FNV-1a.
fn fnv1a(bytes: &[u8], mut hash: u64) -> u64 {
    for b in bytes {
        hash ^= u64::from(*b);
        hash = hash.wrapping_mul(0x0000_0100_0000_01B3);
    }
    hash
}

const FNV_OFFSET: u64 = 0xCBF2_9CE4_8422_2325;

// ---------------------------------------------------------------------------------------------
// A sweep, validated: every task's scene built.

/// One task: its parameters and scene.
#[derive(Debug, Clone)]
pub struct Task {
    /// Index (0-based; names the folder).
    pub index: usize,
    /// The varied fields' values, in `[[vary]]` order.
    pub parameters: Vec<(String, Value)>,
    /// The scene's TOML text.
    pub scene_text: String,
    /// The scene, validated.
    pub scene: Scene,
}

/// A validated sweep.
#[derive(Debug, Clone)]
pub struct Sweep {
    /// Name (default output folder).
    pub name: String,
    /// The base, as written (preset name or file).
    pub base: String,
    /// The varied fields, in order.
    pub fields: Vec<String>,
    /// Every task.
    pub tasks: Vec<Task>,
    /// FNV-1a of every task's scene text, as 16 hex digits.
    pub hash: String,
    /// Write trajectory.csv per task.
    pub save_trajectory: bool,
    /// Draw figures per task.
    pub save_figures: bool,
    /// Monte Carlo draws per grid point (1 without distributions).
    pub draws: usize,
    /// Seed of the draws.
    pub seed: u64,
}

/// Most tasks a sweep may have.
pub const MAX_TASKS: usize = 1_000_000;

fn line_of(source: &str, offset: usize) -> usize {
    source
        .get(..offset.min(source.len()))
        .map_or(1, |s| s.matches('\n').count() + 1)
}

struct SweepLocator<'s> {
    file: &'s str,
    source: &'s str,
}

impl SweepLocator<'_> {
    fn at<T>(
        &self,
        spanned: &Spanned<T>,
        field: &str,
        message: impl std::fmt::Display,
    ) -> SweepError {
        SweepError::Definition(format!(
            "{}:{}: {field}: {message}",
            self.file,
            line_of(self.source, spanned.span().start)
        ))
    }
}

fn number(v: &Value) -> Option<Real> {
    match v {
        Value::Float(x) => Some(*x),
        Value::Integer(i) => Some(*i as Real),
        _ => None,
    }
}

/// `[a, b, n]` of linspace or logspace.
fn range_triple(values: &[Value]) -> Option<(Real, Real, i64)> {
    match values {
        [a, b, Value::Integer(n)] => Some((number(a)?, number(b)?, *n)),
        [a, b, Value::Float(n)] if n.fract() == 0.0 => Some((number(a)?, number(b)?, *n as i64)),
        _ => None,
    }
}

fn grid_of(
    loc: &SweepLocator<'_>,
    vary: &VaryFile,
    field: &str,
) -> Result<Option<Generator>, SweepError> {
    if let Some(v) = &vary.values {
        if v.get_ref().is_empty() {
            return Err(loc.at(v, field, "values is empty: give at least one value"));
        }
        return Ok(Some(Generator::Grid(v.get_ref().clone())));
    }
    for (key, spanned, geometric) in [
        ("linspace", &vary.linspace, false),
        ("logspace", &vary.logspace, true),
    ] {
        let Some(s) = spanned else { continue };
        let (a, b, n) = range_triple(s.get_ref()).ok_or_else(|| {
            loc.at(
                s,
                field,
                format!("{key} = [a, b, n] takes two numbers and a whole count"),
            )
        })?;
        if n < 1 {
            return Err(loc.at(
                s,
                field,
                format!("{key} = [{a}, {b}, {n}] is an empty range: n must be at least 1"),
            ));
        }
        if !(a.is_finite() && b.is_finite()) {
            return Err(loc.at(s, field, format!("{key}: a and b must be finite")));
        }
        if geometric && !(a > 0.0 && b > 0.0) {
            return Err(loc.at(
                s,
                field,
                format!(
                    "logspace = [a, b, n] spaces n values geometrically from a to b (the values, not \
                     exponents): a and b must be positive, got {a} and {b}"
                ),
            ));
        }
        if n as usize > MAX_TASKS {
            return Err(loc.at(s, field, format!("{key}: n = {n} exceeds {MAX_TASKS}")));
        }
        let n = n as usize;
        let at = |k: usize| {
            if n == 1 {
                return a;
            }
            let f = k as Real / (n - 1) as Real;
            if k == n - 1 {
                b
            } else if geometric {
                (a.ln() + f * (b.ln() - a.ln())).exp()
            } else {
                a + f * (b - a)
            }
        };
        return Ok(Some(Generator::Grid(
            (0..n).map(|k| Value::Float(at(k))).collect(),
        )));
    }
    Ok(None)
}

fn distribution_of(
    loc: &SweepLocator<'_>,
    vary: &VaryFile,
    field: &str,
) -> Result<Option<Distribution>, SweepError> {
    for (kind, spanned) in [
        ("uniform", &vary.uniform),
        ("normal", &vary.normal),
        ("loguniform", &vary.loguniform),
    ] {
        let Some(s) = spanned else { continue };
        let pair = match s.get_ref().as_slice() {
            [a, b] => number(a).zip(number(b)),
            _ => None,
        };
        let (a, b) =
            pair.ok_or_else(|| loc.at(s, field, format!("{kind} = [a, b] takes two numbers")))?;
        return Distribution::new(kind, a, b)
            .map(Some)
            .map_err(|m| loc.at(s, field, m));
    }
    if let Some(s) = &vary.distribution {
        let text = s.get_ref().trim();
        let parsed = text
            .strip_suffix(')')
            .and_then(|t| t.split_once('('))
            .and_then(|(kind, args)| {
                let args: Vec<&str> = args.split(',').map(str::trim).collect();
                match args.as_slice() {
                    [a, b] => Some((
                        kind.trim(),
                        a.parse::<Real>().ok()?,
                        b.parse::<Real>().ok()?,
                    )),
                    _ => None,
                }
            });
        let (kind, a, b) = parsed.ok_or_else(|| {
            loc.at(
                s,
                field,
                format!(
                    "distribution = \"{text}\" is not uniform(lo, hi), normal(mean, sd) or \
                     loguniform(lo, hi)"
                ),
            )
        })?;
        return Distribution::new(kind, a, b)
            .map(Some)
            .map_err(|m| loc.at(s, field, m));
    }
    Ok(None)
}

/// Where an edit came from, for messages.
struct Origin {
    path: FieldPath,
    line: usize,
    what: &'static str,
}

/// The value in a one-line form (`1.5`, `[1, 0.8, 0.6]`, `"rk4"`).
fn show_value(v: &Value) -> String {
    match v {
        Value::Float(x) => format!("{x}"),
        Value::Array(items) => format!(
            "[{}]",
            items.iter().map(show_value).collect::<Vec<_>>().join(", ")
        ),
        other => other.to_string(),
    }
}

fn show_parameters(parameters: &[(String, Value)]) -> String {
    parameters
        .iter()
        .map(|(k, v)| format!("{k} = {}", show_value(v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The `[table]` header above line `line` of `text`, and the key on that line.
fn key_at_line(text: &str, line: usize) -> Option<String> {
    let lines: Vec<&str> = text.lines().collect();
    let here = lines.get(line.checked_sub(1)?)?;
    let key = here.split('=').next()?.trim();
    if key.is_empty() || key.starts_with('[') {
        return None;
    }
    let table = lines[..line - 1].iter().rev().find_map(|l| {
        let t = l.trim();
        (t.starts_with('[') && t.ends_with(']')).then(|| t.trim_matches(['[', ']']).to_string())
    });
    Some(match table {
        Some(t) => format!("{t}.{key}"),
        None => key.to_string(),
    })
}

/// Says which edit a scene error of a task belongs to.
fn attribute(
    sweep_file: &str,
    origins: &[Origin],
    task: usize,
    parameters: &[(String, Value)],
    text: &str,
    e: &SceneError,
) -> String {
    let field = e.field.clone().unwrap_or_default();
    let table = field.trim_matches(['[', ']']).to_string();
    let mut candidates: Vec<String> = vec![field.clone()];
    if let Some(k) = e.line.and_then(|l| key_at_line(text, l)) {
        candidates.push(k);
    }
    // `unknown field `colour`` in [body_b]: body_b.colour.
    if let Some(name) = e.message.split('`').nth(1) {
        candidates.push(if table.is_empty() || field == table {
            name.to_string()
        } else {
            format!("{table}.{name}")
        });
    }
    let origin = origins.iter().rev().find(|o| {
        let dotted = o.path.dotted();
        candidates.iter().any(|c| {
            *c == dotted
                || (o.path.keys.last().is_some_and(|l| l == "spin")
                    && c.ends_with("angular_velocity"))
        })
    });
    let context = if parameters.is_empty() {
        format!("task {task:05}")
    } else {
        format!("task {task:05}: {}", show_parameters(parameters))
    };
    match origin {
        Some(o) => format!(
            "{sweep_file}:{}: {} {}: {} ({context})",
            o.line,
            o.what,
            o.path.as_str(),
            e.message
        ),
        None => {
            let field = if field.is_empty() {
                String::new()
            } else {
                format!("{field}: ")
            };
            format!("{sweep_file}: {context}: {field}{}", e.message)
        }
    }
}

impl Sweep {
    /// Reads and validates a sweep file, building every task's scene.
    ///
    /// # Errors
    /// One line naming the file, the line, the field and what to change.
    pub fn load(path: &Path) -> Result<Self, SweepError> {
        let file = path.display().to_string();
        let source = fs::read_to_string(path).map_err(|e| {
            SweepError::Definition(format!("{file}: cannot read the sweep file: {e}"))
        })?;
        let dir = path.parent().unwrap_or(Path::new(""));
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "sweep".into());
        Self::parse(&source, &file, dir, &stem)
    }

    /// Validates a sweep's text; `dir` is where a base scene file is looked for, `stem` the
    /// default name.
    ///
    /// # Errors
    /// As [`Sweep::load`].
    pub fn parse(source: &str, file: &str, dir: &Path, stem: &str) -> Result<Self, SweepError> {
        let loc = SweepLocator { file, source };
        let sweep: SweepFile = toml::from_str(source).map_err(|e| {
            let line = e.span().map(|s| line_of(source, s.start));
            let message = e.message().trim().replace('\n', " ");
            SweepError::Definition(match line {
                Some(l) => format!("{file}:{l}: {message}"),
                None => format!("{file}: {message}"),
            })
        })?;

        // The base scene, checked as it is (its own errors name its own lines).
        let base_name = sweep.base.get_ref().trim().to_string();
        let base_path = dir.join(&base_name);
        let preset = presets::find(&base_name);
        let is_file = base_path.is_file()
            || (preset.is_none() && (base_name.ends_with(".toml") || base_name.contains('/')));
        let (base_text, base_label) = if is_file {
            let text = fs::read_to_string(&base_path).map_err(|e| {
                loc.at(
                    &sweep.base,
                    "base",
                    format!("cannot read the scene file {}: {e}", base_path.display()),
                )
            })?;
            (text, base_path.display().to_string())
        } else {
            let p = preset.ok_or_else(|| {
                loc.at(
                    &sweep.base,
                    "base",
                    format!(
                        "`{base_name}` is neither a preset ({}) nor a scene file next to the sweep file",
                        presets::names()
                    ),
                )
            })?;
            (p.toml.to_string(), format!("preset {}", p.name))
        };
        SceneFile::parse(&base_text, &base_label)
            .and_then(|f| f.build(&base_text, &base_label))
            .map_err(|e| SweepError::Definition(e.to_string()))?;
        let mut document: Table = toml::from_str(&base_text).map_err(|e| {
            SweepError::Definition(format!(
                "{base_label}: {}",
                e.message().trim().replace('\n', " ")
            ))
        })?;

        // Fixed edits: remove, then set.
        let mut origins = Vec::new();
        for r in sweep.remove.iter().flatten() {
            let path = FieldPath::parse(r.get_ref()).map_err(|m| loc.at(r, "remove", m))?;
            remove_field(&mut document, &path).map_err(|m| loc.at(r, "remove", m))?;
            origins.push(Origin {
                path,
                line: line_of(source, r.span().start),
                what: "remove",
            });
        }
        if let Some(set) = &sweep.set {
            let mut leaves = Vec::new();
            flatten(set.get_ref(), &mut Vec::new(), &mut leaves);
            let line = line_of(source, set.span().start);
            for (key, value) in leaves {
                let path = FieldPath::parse(&key).map_err(|m| loc.at(set, "set", m))?;
                set_field(&mut document, &path, value)
                    .map_err(|m| loc.at(set, &format!("set {key}"), m))?;
                origins.push(Origin {
                    path,
                    line,
                    what: "set",
                });
            }
        }

        // Parameters.
        let mut parameters: Vec<Parameter> = Vec::new();
        for (k, v) in sweep.vary.iter().enumerate() {
            let vary = v.get_ref();
            let label = format!("vary[{k}]");
            let path = FieldPath::parse(vary.field.get_ref())
                .map_err(|m| loc.at(&vary.field, &label, m))?;
            let label = format!("vary {}", path.as_str());
            if parameters
                .iter()
                .any(|p| p.path.dotted() == path.dotted() && p.path.index == path.index)
            {
                return Err(loc.at(&vary.field, &label, "is varied twice: keep one [[vary]]"));
            }
            let given = [
                vary.values.is_some(),
                vary.linspace.is_some(),
                vary.logspace.is_some(),
                vary.uniform.is_some(),
                vary.normal.is_some(),
                vary.loguniform.is_some(),
                vary.distribution.is_some(),
            ]
            .iter()
            .filter(|g| **g)
            .count();
            if given != 1 {
                return Err(loc.at(
                    v,
                    &label,
                    "give exactly one of values, linspace, logspace (a grid) or uniform, normal, \
                     loguniform, distribution (draws)",
                ));
            }
            let generator = match grid_of(&loc, vary, &label)? {
                Some(g) => g,
                None => Generator::Draw(
                    distribution_of(&loc, vary, &label)?
                        .ok_or_else(|| loc.at(v, &label, "nothing to vary"))?,
                ),
            };
            let scalar_only = !matches!(&generator, Generator::Grid(_) if vary.values.is_some());
            if scalar_only && path.index.is_none() {
                if let Some(Value::Array(items)) = lookup(&document, &path) {
                    return Err(loc.at(
                        &vary.field,
                        &label,
                        format!(
                            "is a vector of {} numbers: vary one of them ({}[0] …) or give whole \
                             vectors with values = [[...], ...]",
                            items.len(),
                            path.dotted()
                        ),
                    ));
                }
            }
            parameters.push(Parameter {
                path,
                line: line_of(source, vary.field.span().start),
                generator,
            });
        }
        for p in &parameters {
            origins.push(Origin {
                path: p.path.clone(),
                line: p.line,
                what: "vary",
            });
        }

        let has_draws = parameters
            .iter()
            .any(|p| matches!(p.generator, Generator::Draw(_)));
        let draws = match (&sweep.draws, has_draws) {
            (Some(d), _) if *d.get_ref() < 1 => {
                return Err(loc.at(
                    d,
                    "draws",
                    format!("must be at least 1, got {}", d.get_ref()),
                ))
            }
            (Some(d), true) => *d.get_ref() as usize,
            (Some(d), false) => {
                return Err(loc.at(
                    d,
                    "draws",
                    "no [[vary]] has a distribution (uniform, normal, loguniform) to draw from",
                ))
            }
            (None, true) => {
                let first = sweep
                    .vary
                    .iter()
                    .zip(&parameters)
                    .find(|(_, p)| matches!(p.generator, Generator::Draw(_)))
                    .map(|(v, _)| v);
                return Err(match first {
                    Some(v) => loc.at(v, "draws", "a distribution needs draws = N (and seed = S)"),
                    None => SweepError::Definition(format!(
                        "{file}: draws: a distribution needs draws = N"
                    )),
                });
            }
            (None, false) => 1,
        };
        let seed = match &sweep.seed {
            Some(s) if *s.get_ref() < 0 => {
                return Err(loc.at(s, "seed", "must be a whole number ≥ 0"))
            }
            Some(s) => *s.get_ref() as u64,
            None => 0,
        };

        // The tasks: grid points (last parameter fastest) × draws.
        let grids: Vec<(usize, &Vec<Value>)> = parameters
            .iter()
            .enumerate()
            .filter_map(|(i, p)| match &p.generator {
                Generator::Grid(v) => Some((i, v)),
                Generator::Draw(_) => None,
            })
            .collect();
        let grid_points = grids
            .iter()
            .try_fold(1usize, |n, (_, v)| n.checked_mul(v.len()))
            .unwrap_or(usize::MAX);
        let total = grid_points.saturating_mul(draws);
        if total > MAX_TASKS {
            return Err(SweepError::Definition(format!(
                "{file}: the sweep has {total} tasks, more than {MAX_TASKS}: make the grids or draws smaller"
            )));
        }
        let distributions: Vec<(usize, Distribution)> = parameters
            .iter()
            .enumerate()
            .filter_map(|(i, p)| match p.generator {
                Generator::Draw(d) => Some((i, d)),
                Generator::Grid(_) => None,
            })
            .collect();
        let mut tasks = Vec::with_capacity(total);
        let mut hash = FNV_OFFSET;
        for index in 0..total {
            let (mut point, draw) = (index / draws, index % draws);
            let mut values: Vec<Option<Value>> = vec![None; parameters.len()];
            for (i, grid) in grids.iter().rev() {
                values[*i] = Some(grid[point % grid.len()].clone());
                point /= grid.len();
            }
            for (slot, (i, d)) in distributions.iter().enumerate() {
                let mut rng = SplitMix64::stream(seed, draw as u64, slot as u64);
                values[*i] = Some(Value::Float(d.sample(&mut rng)));
            }
            let mut doc = document.clone();
            let mut task_parameters = Vec::with_capacity(parameters.len());
            for (p, v) in parameters.iter().zip(values) {
                let v = v.unwrap_or(Value::Float(Real::NAN));
                set_field(&mut doc, &p.path, v.clone()).map_err(|m| {
                    SweepError::Definition(format!(
                        "{file}:{}: vary {}: {m}",
                        p.line,
                        p.path.as_str()
                    ))
                })?;
                task_parameters.push((p.path.as_str().to_string(), v));
            }
            let text = toml::to_string(&doc)
                .map_err(|e| SweepError::Definition(format!("{file}: {e}")))?;
            let label = format!("{file} task {index:05}");
            let scene = SceneFile::parse(&text, &label)
                .and_then(|f| f.build(&text, &label))
                .map_err(|e| {
                    SweepError::Definition(attribute(
                        file,
                        &origins,
                        index,
                        &task_parameters,
                        &text,
                        &e,
                    ))
                })?;
            scene.integrator.make().map_err(|m| {
                SweepError::Definition(format!(
                    "{file}: task {index:05}: {}: {m}",
                    show_parameters(&task_parameters)
                ))
            })?;
            hash = fnv1a(text.as_bytes(), hash);
            hash = fnv1a(&[0], hash);
            tasks.push(Task {
                index,
                parameters: task_parameters,
                scene_text: text,
                scene,
            });
        }
        let name = match &sweep.name {
            Some(n) => n.get_ref().trim().to_string(),
            None => stem.to_string(),
        };
        Ok(Self {
            name,
            base: base_name,
            fields: parameters
                .iter()
                .map(|p| p.path.as_str().to_string())
                .collect(),
            tasks,
            hash: format!("{hash:016x}"),
            save_trajectory: sweep.save_trajectory.unwrap_or(false),
            save_figures: sweep.save_figures.unwrap_or(false),
            draws,
            seed,
        })
    }
}

/// The leaves of a table as dotted paths (arrays are leaves).
fn flatten(table: &Table, prefix: &mut Vec<String>, out: &mut Vec<(String, Value)>) {
    for (k, v) in table {
        prefix.push(k.clone());
        match v {
            Value::Table(t) => flatten(t, prefix, out),
            other => out.push((prefix.join("."), other.clone())),
        }
        prefix.pop();
    }
}

// ---------------------------------------------------------------------------------------------
// Results of a task.

/// What a finished task reports (its `task.toml`, one row of `results.csv`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TaskResult {
    /// Mass of body A (given, or from density × volume).
    pub mass_a: Real,
    /// Mass of body B.
    pub mass_b: Real,
    /// Time reached.
    pub t_reached: Real,
    /// Accepted steps.
    pub steps: usize,
    /// Smallest centroid separation.
    pub min_separation: Option<Real>,
    /// Largest |E − E0|/|E0|.
    pub energy_drift: Real,
    /// Largest relative change of |J|.
    pub angular_momentum_drift: Real,
    /// Largest |J − J0|/|J0|.
    pub angular_momentum_vector_drift: Real,
    /// ψ_p in degrees.
    pub precession_angle_deg: Option<Real>,
    /// |ω_A| at the end.
    pub final_spin_a: Real,
    /// |ω_B| at the end.
    pub final_spin_b: Real,
    /// `completed`, `contact` or `escape`.
    pub termination: String,
    /// Time of contact.
    pub contact_time: Option<Real>,
    /// Time of escape.
    pub escape_time: Option<Real>,
    /// Seconds of model building and integration (as summary.json's wall_seconds).
    pub wall_seconds: Real,
}

/// `task.toml`: TOML rather than JSON because its numbers read back exactly (serde_json's
/// default float parser may miss the last bit), so a resumed or merged results.csv equals the
/// one written in one go.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct TaskFile {
    task: usize,
    parameters: Table,
    result: TaskResult,
}

fn parameters_json(parameters: &[(String, Value)]) -> serde_json::Map<String, serde_json::Value> {
    parameters
        .iter()
        .map(|(k, v)| {
            (
                k.clone(),
                serde_json::to_value(v).unwrap_or(serde_json::Value::Null),
            )
        })
        .collect()
}

fn task_folder(index: usize) -> String {
    format!("tasks/{index:05}")
}

/// A task's row of `results.csv` from its scene and finished run.
fn task_result(scene: &Scene, record: &simulate::RunRecord) -> TaskResult {
    let last = &record.summary.last.state;
    TaskResult {
        mass_a: scene.body_a.into_potential().mass(),
        mass_b: scene.body_b.into_potential().mass(),
        t_reached: record.t_reached(),
        steps: record.summary.steps,
        min_separation: record.orbit.minimum_separation,
        energy_drift: record.energy.max_relative_drift,
        angular_momentum_drift: record.angular_momentum.max_relative_drift,
        angular_momentum_vector_drift: record.angular_momentum_vector_drift,
        precession_angle_deg: record.orbit.precession_angle_deg,
        final_spin_a: last.body_a.angular_velocity.norm(),
        final_spin_b: last.body_b.angular_velocity.norm(),
        termination: if record.contact().is_some() {
            "contact"
        } else if record.escape().is_some() {
            "escape"
        } else {
            "completed"
        }
        .to_string(),
        contact_time: record.contact(),
        escape_time: record.escape(),
        wall_seconds: record.wall_seconds,
    }
}

/// Runs one task's scene as `surfgrav sweep` runs it, writing nothing (no folder, trajectory
/// or figures): the task's key results, or the message its `failed` status would carry. For
/// callers that distribute the tasks themselves (the Python package's `surfgrav.sweep`).
///
/// # Errors
/// The run's error ([`SweepError::Run`]), its message as in `manifest.json`.
pub fn run_scene(scene: &Scene) -> Result<TaskResult, SweepError> {
    let prepared = simulate::prepare(scene)?;
    let record = simulate::simulate(scene, &prepared, &mut |_| {}, &mut |_| Ok(()))?;
    Ok(task_result(scene, &record))
}

/// A task's row for [`results_csv_text`]: its index, parameters (as [`Task::parameters`]) and
/// outcome ([`run_scene`]'s: the result, or the failure).
pub type TaskOutcome = (usize, Vec<(String, Value)>, Result<TaskResult, SweepError>);

/// The text of `results.csv`, as `surfgrav sweep` writes it, for these tasks. Rows are sorted
/// by index.
pub fn results_csv_text(fields: &[String], rows: &[TaskOutcome]) -> String {
    let mut tasks = Vec::with_capacity(rows.len());
    let mut results = BTreeMap::new();
    for (index, parameters, outcome) in rows {
        let (status, message) = match outcome {
            Ok(r) => {
                results.insert(*index, r.clone());
                (Status::Done, None)
            }
            Err(e) => (Status::Failed, Some(e.to_string())),
        };
        tasks.push(ManifestTask {
            task: *index,
            folder: task_folder(*index),
            parameters: parameters_json(parameters),
            status,
            message,
        });
    }
    results_csv(fields, &tasks, &results)
}

/// What a task writes beyond `summary.json` and `task.toml`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TaskFiles {
    /// `trajectory.csv`.
    pub trajectory: bool,
    /// The run's figures.
    pub figures: bool,
}

impl Sweep {
    /// What each task of this sweep writes.
    pub fn task_files(&self) -> TaskFiles {
        TaskFiles {
            trajectory: self.save_trajectory,
            figures: self.save_figures,
        }
    }
}

/// A file-writing failure as [`SweepError::Io`] (its message unchanged).
fn io_error(e: impl std::fmt::Display) -> SweepError {
    SweepError::Io(e.to_string())
}

/// Runs one task into `root/tasks/NNNNN` (staged: the folder appears whole, with
/// `summary.json` last, or not at all), as `surfgrav sweep` does.
///
/// # Errors
/// The run's error ([`SweepError::Run`]) or a file that could not be written
/// ([`SweepError::Io`]); nothing is left that looks finished.
pub fn run_task(root: &Path, task: &Task, files: TaskFiles) -> Result<TaskResult, SweepError> {
    let scene = &task.scene;
    let target = root.join(task_folder(task.index));
    let staging = Staging::new(&target).map_err(io_error)?;
    fs::write(staging.path().join("scene.toml"), &task.scene_text)
        .map_err(|e| SweepError::Io(format!("cannot write scene.toml: {e}")))?;
    let prepared = simulate::prepare(scene)?;
    let mut csv = if files.trajectory {
        Some(TrajectoryWriter::create(&staging.path().join("trajectory.csv")).map_err(io_error)?)
    } else {
        None
    };
    let record = simulate::simulate(scene, &prepared, &mut |_| {}, &mut |row| match &mut csv {
        Some(w) => w.write(row),
        None => Ok(()),
    })?;
    if let Some(w) = csv {
        w.finish().map_err(io_error)?;
    }
    if files.figures {
        crate::figures::write_all(&record, staging.path())
            .map_err(|e| SweepError::Io(format!("figures: {e}")))?;
    }
    let result = task_result(scene, &record);
    let file = TaskFile {
        task: task.index,
        parameters: task.parameters.iter().cloned().collect(),
        result: result.clone(),
    };
    let text = toml::to_string(&file).map_err(|e| SweepError::Io(e.to_string()))?;
    fs::write(staging.path().join("task.toml"), text)
        .map_err(|e| SweepError::Io(format!("cannot write task.toml: {e}")))?;
    // summary.json last: its presence marks the task finished (after the rename).
    output::write_summary(&record, &staging.path().join("summary.json")).map_err(io_error)?;
    staging.commit().map_err(io_error)?;
    Ok(result)
}

/// A finished task's result, read back from its folder under `root` (`None` if it is not
/// finished: no `summary.json`, or a `task.toml` of another task).
pub fn finished(root: &Path, index: usize) -> Option<TaskResult> {
    let folder = root.join(task_folder(index));
    if !folder.join("summary.json").is_file() {
        return None;
    }
    let text = fs::read_to_string(folder.join("task.toml")).ok()?;
    let file: TaskFile = toml::from_str(&text).ok()?;
    (file.task == index).then_some(file.result)
}

// ---------------------------------------------------------------------------------------------
// Manifest and results.

/// A task's status.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Not run (yet).
    Pending,
    /// Finished: its folder has summary.json.
    Done,
    /// Ran and failed.
    Failed,
}

/// One task in `manifest.json`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ManifestTask {
    /// Index.
    pub task: usize,
    /// Folder, relative to the manifest's folder.
    pub folder: String,
    /// The varied fields' values.
    pub parameters: serde_json::Map<String, serde_json::Value>,
    /// Status.
    pub status: Status,
    /// Why it failed.
    pub message: Option<String>,
}

/// `--shard K/N`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// K.
    pub index: usize,
    /// N.
    pub count: usize,
}

impl Shard {
    /// Parses `K/N` (0 ≤ K < N).
    ///
    /// # Errors
    /// A malformed value or K ≥ N.
    pub fn parse(text: &str) -> Result<Self, ShardError> {
        let parsed = text.split_once('/').and_then(|(k, n)| {
            Some((
                k.trim().parse::<usize>().ok()?,
                n.trim().parse::<usize>().ok()?,
            ))
        });
        match parsed {
            Some((index, count)) if count >= 1 && index < count => Ok(Self { index, count }),
            Some((index, count)) if count >= 1 => Err(ShardError::OutOfRange {
                text: text.into(),
                last: count - 1,
                index,
            }),
            _ => Err(ShardError::Malformed { text: text.into() }),
        }
    }
}

/// `manifest.json` (or `manifest-shard-K-of-N.json`).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Manifest {
    /// Sweep name.
    pub sweep: String,
    /// The base scene (preset or file).
    pub base: String,
    /// FNV-1a of every task's scene text.
    pub definition_hash: String,
    /// Tasks in the whole sweep.
    pub tasks_total: usize,
    /// The varied fields, in order (results.csv's parameter columns).
    pub fields: Vec<String>,
    /// Monte Carlo draws per grid point.
    pub draws: usize,
    /// Seed of the draws.
    pub seed: u64,
    /// This file's share, if sharded.
    pub shard: Option<Shard>,
    /// The tasks of this file (all, or the shard's), by index.
    pub tasks: Vec<ManifestTask>,
}

/// The result columns of `results.csv`, after `task`, `status` and the parameters.
pub const RESULT_COLUMNS: &[&str] = &[
    "mass_a",
    "mass_b",
    "t_reached",
    "steps",
    "min_separation",
    "energy_drift",
    "angular_momentum_drift",
    "angular_momentum_vector_drift",
    "precession_angle_deg",
    "final_spin_a",
    "final_spin_b",
    "termination",
    "contact_time",
    "escape_time",
    "wall_seconds",
    "message",
];

fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

fn json_cell(v: &serde_json::Value) -> String {
    match v {
        serde_json::Value::Null => String::new(),
        serde_json::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// Shortest round-trip decimal, in exponent form outside [1e-4, 1e15) (`3.3e-11`, not
/// `0.000000000033`).
fn num(x: Real) -> String {
    if x == 0.0 || (1e-4..1e15).contains(&x.abs()) {
        x.to_string()
    } else {
        format!("{x:e}")
    }
}

fn opt(x: Option<Real>) -> String {
    x.filter(|v| v.is_finite()).map(num).unwrap_or_default()
}

/// The text of `results.csv` for these tasks (sorted by index).
fn results_csv(
    fields: &[String],
    tasks: &[ManifestTask],
    results: &BTreeMap<usize, TaskResult>,
) -> String {
    let mut text = String::new();
    let header: Vec<String> = ["task", "status"]
        .iter()
        .map(|s| s.to_string())
        .chain(fields.iter().map(|f| csv_field(f)))
        .chain(RESULT_COLUMNS.iter().map(|s| s.to_string()))
        .collect();
    let _ = writeln!(text, "{}", header.join(","));
    let mut sorted: Vec<&ManifestTask> = tasks.iter().collect();
    sorted.sort_by_key(|t| t.task);
    for t in sorted {
        let mut cells = vec![
            t.task.to_string(),
            serde_json::to_value(&t.status)
                .ok()
                .map(|v| json_cell(&v))
                .unwrap_or_default(),
        ];
        for f in fields {
            cells.push(csv_field(
                &t.parameters.get(f).map(json_cell).unwrap_or_default(),
            ));
        }
        match results.get(&t.task).filter(|_| t.status == Status::Done) {
            Some(r) => cells.extend([
                num(r.mass_a),
                num(r.mass_b),
                num(r.t_reached),
                r.steps.to_string(),
                opt(r.min_separation),
                opt(Some(r.energy_drift)),
                opt(Some(r.angular_momentum_drift)),
                opt(Some(r.angular_momentum_vector_drift)),
                opt(r.precession_angle_deg),
                opt(Some(r.final_spin_a)),
                opt(Some(r.final_spin_b)),
                r.termination.clone(),
                opt(r.contact_time),
                opt(r.escape_time),
                num(r.wall_seconds),
                String::new(),
            ]),
            None => {
                cells.extend((0..RESULT_COLUMNS.len() - 1).map(|_| String::new()));
                cells.push(csv_field(t.message.as_deref().unwrap_or("")));
            }
        }
        let _ = writeln!(text, "{}", cells.join(","));
    }
    text
}

/// Writes a file whole: a hidden temporary sibling, then a rename.
fn write_atomic(path: &Path, text: &str) -> Result<(), SweepError> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let temporary = path.with_file_name(format!(".{name}.tmp-{}", std::process::id()));
    fs::write(&temporary, text)
        .map_err(|e| SweepError::Io(format!("cannot write {}: {e}", temporary.display())))?;
    fs::rename(&temporary, path).map_err(|e| {
        let _ = fs::remove_file(&temporary);
        SweepError::Io(format!("cannot write {}: {e}", path.display()))
    })
}

fn file_names(shard: Option<Shard>) -> (String, String) {
    match shard {
        Some(s) => (
            format!("manifest-shard-{}-of-{}.json", s.index, s.count),
            format!("results-shard-{}-of-{}.csv", s.index, s.count),
        ),
        None => ("manifest.json".into(), "results.csv".into()),
    }
}

/// Every manifest in a folder (`manifest.json` and the shards').
fn manifests_in(dir: &Path) -> Result<Vec<(PathBuf, Manifest)>, SweepError> {
    let mut found = Vec::new();
    let Ok(entries) = fs::read_dir(dir) else {
        return Ok(found);
    };
    let mut paths: Vec<PathBuf> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.file_name().and_then(|n| n.to_str()).is_some_and(|n| {
                n == "manifest.json" || (n.starts_with("manifest-shard-") && n.ends_with(".json"))
            })
        })
        .collect();
    paths.sort();
    for p in paths {
        let text = fs::read_to_string(&p)
            .map_err(|e| SweepError::Usage(format!("cannot read {}: {e}", p.display())))?;
        let m: Manifest = serde_json::from_str(&text).map_err(|e| {
            SweepError::Usage(format!("{} is not a sweep manifest: {e}", p.display()))
        })?;
        found.push((p, m));
    }
    Ok(found)
}

/// Whether `out` can hold this sweep: absent (its parent a folder), or a folder with nothing but
/// this sweep's files (manifests of the same definition, results, tasks/, hidden files).
fn check_out(out: &Path, hash: &str) -> Result<(), SweepError> {
    if out.as_os_str().is_empty() {
        return Err(SweepError::Usage("--out must not be empty".into()));
    }
    if !out.exists() {
        let parent = match out.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        if !parent.is_dir() {
            return Err(SweepError::Usage(format!(
                "--out {}: the folder {} does not exist: create it first or choose another path",
                out.display(),
                parent.display()
            )));
        }
        return Ok(());
    }
    if !out.is_dir() {
        return Err(SweepError::Usage(format!(
            "{} is a file, not a sweep folder: choose another --out",
            out.display()
        )));
    }
    for (path, m) in manifests_in(out)? {
        if m.definition_hash != hash {
            return Err(SweepError::Usage(format!(
                "{} belongs to another sweep (definition {} here, {hash} in the sweep file): \
                 choose another --out, or remove that folder",
                path.display(),
                m.definition_hash
            )));
        }
    }
    let foreign = fs::read_dir(out)
        .map_err(|e| SweepError::Usage(format!("cannot read {}: {e}", out.display())))?
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .find(|n| {
            !(n.starts_with('.')
                || n == "tasks"
                || n == "manifest.json"
                || n == "results.csv"
                || (n.starts_with("manifest-shard-") && n.ends_with(".json"))
                || (n.starts_with("results-shard-") && n.ends_with(".csv")))
        });
    if let Some(n) = foreign {
        return Err(SweepError::Usage(format!(
            "{} exists and holds `{n}`, which is not part of a sweep: choose a new --out",
            out.display()
        )));
    }
    Ok(())
}

/// What a sweep run did.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepReport {
    /// The folder.
    pub folder: PathBuf,
    /// Tasks of this run's share.
    pub selected: usize,
    /// Run now and finished.
    pub ran: usize,
    /// Finished before (skipped).
    pub skipped: usize,
    /// Failed, with the first message.
    pub failed: Vec<(usize, String)>,
    /// Seconds.
    pub wall_seconds: Real,
    /// The manifest and results files written.
    pub files: (String, String),
}

/// A sweep's share of tasks in its output folder: which are finished (read back from their
/// folders, as a re-run finds them) and which are still to run. [`run_sweep`] runs the pending
/// tasks with rayon; the Python package hands them to any executor and records the outcomes
/// here, so both write the same `manifest.json` and `results.csv` and resume alike.
#[derive(Debug, Clone)]
pub struct SweepFolder {
    /// The folder.
    pub folder: PathBuf,
    /// This run's share, if sharded.
    pub shard: Option<Shard>,
    /// Every selected task's manifest entry, in index order.
    pub entries: Vec<ManifestTask>,
    /// Finished tasks' results, by index.
    pub results: BTreeMap<usize, TaskResult>,
    /// Tasks finished before this run (skipped).
    pub skipped: usize,
}

impl SweepFolder {
    /// Checks `out` (absent, or a folder of this same sweep), creates `out/tasks`, reads back
    /// the finished tasks of the share and writes the manifest (finished tasks `done`, the
    /// others `pending`).
    ///
    /// # Errors
    /// [`SweepError::Usage`] for a folder that is not this sweep's (nothing written);
    /// [`SweepError::Io`] when the folder or manifest cannot be written.
    pub fn open(sweep: &Sweep, out: &Path, shard: Option<Shard>) -> Result<Self, SweepError> {
        check_out(out, &sweep.hash)?;
        fs::create_dir_all(out.join("tasks"))
            .map_err(|e| SweepError::Io(format!("cannot create {}: {e}", out.display())))?;
        let mut results = BTreeMap::new();
        let mut entries = Vec::new();
        for t in sweep
            .tasks
            .iter()
            .filter(|t| shard.is_none_or(|s| t.index % s.count == s.index))
        {
            let done = finished(out, t.index);
            entries.push(ManifestTask {
                task: t.index,
                folder: task_folder(t.index),
                parameters: parameters_json(&t.parameters),
                status: if done.is_some() {
                    Status::Done
                } else {
                    Status::Pending
                },
                message: None,
            });
            if let Some(r) = done {
                results.insert(t.index, r);
            }
        }
        let folder = Self {
            folder: out.to_path_buf(),
            shard,
            skipped: results.len(),
            entries,
            results,
        };
        folder.write_manifest(sweep)?;
        Ok(folder)
    }

    /// The indices of the tasks still to run.
    pub fn pending(&self) -> Vec<usize> {
        self.entries
            .iter()
            .filter(|e| e.status == Status::Pending)
            .map(|e| e.task)
            .collect()
    }

    /// Records a task's outcome (a task outside the share is ignored).
    pub fn record(&mut self, index: usize, outcome: Result<TaskResult, SweepError>) {
        let Ok(k) = self.entries.binary_search_by_key(&index, |e| e.task) else {
            return;
        };
        let entry = &mut self.entries[k];
        match outcome {
            Ok(r) => {
                entry.status = Status::Done;
                entry.message = None;
                self.results.insert(index, r);
            }
            Err(e) => {
                entry.status = Status::Failed;
                entry.message = Some(e.to_string());
            }
        }
    }

    /// The manifest and results files' names (`manifest.json`, `results.csv`, or the shard's).
    pub fn file_names(&self) -> (String, String) {
        file_names(self.shard)
    }

    /// Writes the manifest as it stands.
    ///
    /// # Errors
    /// [`SweepError::Io`].
    pub fn write_manifest(&self, sweep: &Sweep) -> Result<(), SweepError> {
        let manifest = Manifest {
            sweep: sweep.name.clone(),
            base: sweep.base.clone(),
            definition_hash: sweep.hash.clone(),
            tasks_total: sweep.tasks.len(),
            fields: sweep.fields.clone(),
            draws: sweep.draws,
            seed: sweep.seed,
            shard: self.shard,
            tasks: self.entries.clone(),
        };
        let text =
            serde_json::to_string_pretty(&manifest).map_err(|e| SweepError::Io(e.to_string()))?;
        write_atomic(&self.folder.join(self.file_names().0), &(text + "\n"))
    }

    /// Writes the manifest and the results file.
    ///
    /// # Errors
    /// [`SweepError::Io`].
    pub fn finish(&self, sweep: &Sweep) -> Result<(), SweepError> {
        self.write_manifest(sweep)?;
        write_atomic(
            &self.folder.join(self.file_names().1),
            &results_csv(&sweep.fields, &self.entries, &self.results),
        )
    }

    /// The failed tasks with their messages.
    pub fn failed(&self) -> Vec<(usize, String)> {
        self.entries
            .iter()
            .filter(|e| e.status == Status::Failed)
            .map(|e| (e.task, e.message.clone().unwrap_or_default()))
            .collect()
    }
}

/// Runs a sweep's share of tasks into `out`.
///
/// # Errors
/// Bad input (before anything is written) or I/O failures.
pub fn run_sweep(
    sweep: &Sweep,
    out: &Path,
    shard: Option<Shard>,
    jobs: usize,
    progress: &(dyn Fn() + Sync),
) -> Result<SweepReport, SweepError> {
    let start = Instant::now();
    let folder = SweepFolder::open(sweep, out, shard)?;
    let pending: Vec<&Task> = folder
        .pending()
        .into_iter()
        .filter_map(|i| sweep.tasks.get(i))
        .collect();
    let selected = folder.entries.len();
    let skipped = folder.skipped;
    let files = sweep.task_files();
    let state = Mutex::new((folder, Instant::now()));
    let ran = AtomicUsize::new(0);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| SweepError::Io(format!("cannot start {jobs} threads: {e}")))?;
    pool.install(|| {
        pending.par_iter().for_each(|task| {
            let outcome = run_task(out, task, files);
            if outcome.is_ok() {
                ran.fetch_add(1, Ordering::Relaxed);
            }
            let mut guard = state.lock().unwrap_or_else(|p| p.into_inner());
            let (folder, last_write) = &mut *guard;
            folder.record(task.index, outcome);
            // The manifest follows the sweep every few seconds (it is also rebuilt from the
            // task folders on a re-run).
            if last_write.elapsed().as_secs_f64() > 5.0 {
                let _ = folder.write_manifest(sweep);
                *last_write = Instant::now();
            }
            drop(guard);
            progress();
        });
    });
    let (folder, _) = state.into_inner().unwrap_or_else(|p| p.into_inner());
    folder.finish(sweep)?;
    Ok(SweepReport {
        folder: out.to_path_buf(),
        selected,
        ran: ran.into_inner(),
        skipped,
        failed: folder.failed(),
        wall_seconds: start.elapsed().as_secs_f64(),
        files: folder.file_names(),
    })
}

/// Merges shard outputs: returns the folder written and the counts.
///
/// # Errors
/// No manifest found, manifests of different sweeps ([`SweepError::Usage`]); I/O failures
/// ([`SweepError::Io`]).
pub fn merge(dirs: &[PathBuf], out: Option<&Path>) -> Result<(PathBuf, usize, usize), SweepError> {
    let mut all = Vec::new();
    for d in dirs {
        if !d.is_dir() {
            return Err(SweepError::Usage(format!(
                "{} is not a folder: give the sweep folders of the shards",
                d.display()
            )));
        }
        let found = manifests_in(d)?;
        if found.is_empty() {
            return Err(SweepError::Usage(format!(
                "{} holds no manifest.json or manifest-shard-K-of-N.json: not a sweep folder",
                d.display()
            )));
        }
        all.extend(found.into_iter().map(|(p, m)| (d.clone(), p, m)));
    }
    let (_, first_path, first) = &all[0];
    for (_, p, m) in &all[1..] {
        if m.definition_hash != first.definition_hash {
            return Err(SweepError::Usage(format!(
                "{} is from another sweep than {} (definition {} against {}): merge the shards of one sweep",
                p.display(),
                first_path.display(),
                m.definition_hash,
                first.definition_hash
            )));
        }
    }
    let out = out.map_or_else(|| dirs[0].clone(), Path::to_path_buf);
    if out.exists() && !out.is_dir() {
        return Err(SweepError::Usage(format!(
            "--out {} is a file",
            out.display()
        )));
    }
    check_out(&out, &first.definition_hash)?;
    // Per task, the best status found (done over failed over pending).
    let rank = |s: &Status| match s {
        Status::Done => 2,
        Status::Failed => 1,
        Status::Pending => 0,
    };
    let mut best: BTreeMap<usize, (ManifestTask, PathBuf)> = BTreeMap::new();
    for (dir, _, m) in &all {
        for t in &m.tasks {
            let mut t = t.clone();
            if t.status == Status::Done && finished(dir, t.task).is_none() {
                t.status = Status::Pending;
            }
            // A task finished after its manifest was last written.
            if t.status != Status::Done && finished(dir, t.task).is_some() {
                t.status = Status::Done;
                t.message = None;
            }
            let better = best
                .get(&t.task)
                .is_none_or(|(b, _)| rank(&t.status) > rank(&b.status));
            if better {
                best.insert(t.task, (t, dir.clone()));
            }
        }
    }
    let mut results = BTreeMap::new();
    let mut entries = Vec::with_capacity(first.tasks_total);
    for index in 0..first.tasks_total {
        match best.remove(&index) {
            Some((mut t, dir)) => {
                if let Some(r) = finished(&dir, index).filter(|_| t.status == Status::Done) {
                    results.insert(index, r);
                }
                if dir != out {
                    t.folder = dir.join(task_folder(index)).display().to_string();
                }
                entries.push(t);
            }
            None => entries.push(ManifestTask {
                task: index,
                folder: task_folder(index),
                parameters: serde_json::Map::new(),
                status: Status::Pending,
                message: Some("in no shard's manifest".into()),
            }),
        }
    }
    let done = results.len();
    let manifest = Manifest {
        shard: None,
        tasks: entries,
        ..first.clone()
    };
    fs::create_dir_all(&out)
        .map_err(|e| SweepError::Io(format!("cannot create {}: {e}", out.display())))?;
    let text = serde_json::to_string_pretty(&manifest).map_err(io_error)?;
    write_atomic(&out.join("manifest.json"), &(text + "\n"))?;
    write_atomic(
        &out.join("results.csv"),
        &results_csv(&manifest.fields, &manifest.tasks, &results),
    )?;
    Ok((out, manifest.tasks_total, done))
}

/// `surfgrav sweep`.
///
/// # Errors
/// Bad input (exit 2, nothing written); failed tasks or I/O (exit 1, the rest written).
pub fn sweep_command(args: SweepArgs) -> Result<String, CliError> {
    if let Some(SweepAction::Merge { dirs, out, quiet }) = args.action {
        let (folder, total, done) = merge(&dirs, out.as_deref())?;
        return Ok(if quiet {
            String::new()
        } else {
            format!(
                "wrote {}/: results.csv, manifest.json ({total} tasks, {done} done, {} not done)",
                folder.display(),
                total - done
            )
        });
    }
    let file = args
        .file
        .ok_or_else(|| CliError::Input("give the sweep file: surfgrav sweep SWEEP.toml".into()))?;
    let shard = args
        .shard
        .as_deref()
        .map(Shard::parse)
        .transpose()
        .map_err(SweepError::from)?;
    let jobs = match args.jobs.as_deref() {
        Some(j) => match j.trim().parse::<usize>() {
            Ok(n) if n >= 1 => n,
            _ => {
                return Err(CliError::Input(format!(
                    "--jobs {j}: expected a whole number of at least 1"
                )))
            }
        },
        None => std::thread::available_parallelism().map_or(1, usize::from),
    };
    let sweep = Sweep::load(&file)?;
    let out = match args.out {
        Some(o) => o,
        None => {
            if !output::folder_safe(&sweep.name) {
                return Err(CliError::Input(format!(
                    "the sweep name `{}` cannot name the default output folder: give --out DIR",
                    sweep.name
                )));
            }
            PathBuf::from(&sweep.name)
        }
    };
    let share = sweep
        .tasks
        .iter()
        .filter(|t| shard.is_none_or(|s| t.index % s.count == s.index))
        .count();
    let bar = crate::cli::progress_bar(args.quiet, share as u64, &sweep.name);
    let report = run_sweep(&sweep, &out, shard, jobs, &|| bar.inc(1));
    bar.finish_and_clear();
    let report = report?;
    if let Some((index, message)) = report.failed.first() {
        return Err(CliError::Failed(format!(
            "{} of {} tasks failed (see {}/{}); task {index:05}: {message}",
            report.failed.len(),
            report.selected,
            report.folder.display(),
            report.files.0
        )));
    }
    if args.quiet {
        return Ok(String::new());
    }
    Ok(format!(
        "wrote {}/: {}, {} ({} of {} tasks{}: {} run now, {} already done; {} jobs, {:.2} s wall)",
        report.folder.display(),
        report.files.1,
        report.files.0,
        report.selected,
        sweep.tasks.len(),
        shard.map_or(String::new(), |s| format!(
            ", shard {}/{}",
            s.index, s.count
        )),
        report.ran,
        report.skipped,
        jobs,
        report.wall_seconds
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn field_paths_parse_and_refuse() {
        let p = FieldPath::parse("body_a.semi_axes[2]").unwrap();
        assert_eq!(
            (p.dotted().as_str(), p.index),
            ("body_a.semi_axes", Some(2))
        );
        assert!(FieldPath::parse("body_a..mass").is_err());
        assert!(FieldPath::parse("body_a.mass[x]").is_err());
    }

    #[test]
    fn draws_are_deterministic_and_in_range() {
        let u = Distribution::new("uniform", 2.0, 3.0).unwrap();
        let l = Distribution::new("loguniform", 1e-3, 1e3).unwrap();
        let n = Distribution::new("normal", 5.0, 2.0).unwrap();
        let draw = |d: &Distribution, k: u64| d.sample(&mut SplitMix64::stream(7, k, 0));
        let mut mean = 0.0;
        let mut square = 0.0;
        for k in 0..20_000 {
            let x = draw(&u, k);
            assert!((2.0..3.0).contains(&x));
            let y = draw(&l, k);
            assert!((1e-3..=1e3).contains(&y));
            let z = draw(&n, k);
            mean += z / 20_000.0;
            square += z * z / 20_000.0;
            assert_eq!(draw(&n, k), z);
        }
        // Mean 5 ± 4σ/√N, variance 4 within 5 %.
        assert!((mean - 5.0).abs() < 4.0 * 2.0 / 20_000f64.sqrt(), "{mean}");
        assert!(((square - mean * mean) / 4.0 - 1.0).abs() < 0.05);
        assert_ne!(
            u.sample(&mut SplitMix64::stream(7, 0, 0)),
            u.sample(&mut SplitMix64::stream(8, 0, 0))
        );
        for (kind, a, b) in [
            ("normal", 0.0, 0.0),
            ("uniform", 1.0, 1.0),
            ("loguniform", 0.0, 1.0),
        ] {
            assert!(Distribution::new(kind, a, b).is_err());
        }
    }

    #[test]
    fn edits_replace_alternatives_and_keep_types() {
        let mut doc: Table =
            toml::from_str("[body_b]\nmass = 1.0\nspin = [0.0, 0.0, 1.0]\n[output]\nevery = 2\n")
                .unwrap();
        set_field(
            &mut doc,
            &FieldPath::parse("body_b.density").unwrap(),
            Value::Float(2.0),
        )
        .unwrap();
        set_field(
            &mut doc,
            &FieldPath::parse("body_b.angular_velocity[1]").unwrap(),
            Value::Integer(3),
        )
        .unwrap();
        set_field(
            &mut doc,
            &FieldPath::parse("output.every").unwrap(),
            Value::Float(5.0),
        )
        .unwrap();
        let b = doc["body_b"].as_table().unwrap();
        assert!(b.get("mass").is_none() && b.get("spin").is_none());
        assert_eq!(
            b["angular_velocity"],
            Value::Array(vec![
                Value::Float(0.0),
                Value::Float(3.0),
                Value::Float(1.0)
            ])
        );
        assert_eq!(doc["output"]["every"], Value::Integer(5));
    }
}
