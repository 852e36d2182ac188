//! Scenes, presets and the `surfgrav` command-line tool.
//!
//! The binary's commands live in [`cli`]; body specifications (`sphere:radius=1,mass=1`) in
//! [`spec`].

pub mod bench;
pub mod cli;
pub mod figures;
pub mod kinds;
pub mod output;
pub mod plot;
pub mod presets;
pub mod report;
pub mod scene;
pub mod simulate;
pub mod spec;
pub mod sweep;
