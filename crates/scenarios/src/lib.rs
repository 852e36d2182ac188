//! Scenes, presets and the `surfgrav` command-line tool.
//!
//! The binary's commands live in [`cli`]; body specifications (`sphere:radius=1,mass=1`) in
//! [`spec`].

pub mod cli;
pub mod plot;
pub mod spec;
