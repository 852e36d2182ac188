//! Built-in scenes: the founding paper's (Wold & Conway, *The planar two-body problem for
//! spheroids and disks*, Table 1 and Sect. 4), as TOML text a user can print
//! (`surfgrav presets --show NAME`), save, edit and run.
//!
//! Every preset starts from the paper's initial conditions: $\mathbf R_A = (-3.5, 0, 0)$,
//! $\mathbf R_B = (3.5, 0, 0)$, $\mathbf V_A = (0, 0.2, 0)$, $\mathbf V_B = (0, -0.2, 0)$,
//! $G = 1$, masses 1, $t = 300$.

use crate::scene::{Scene, SceneError, SceneFile};

/// A built-in scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Preset {
    /// Name, as typed after `surfgrav run`.
    pub name: &'static str,
    /// One line.
    pub summary: &'static str,
    /// The scene as TOML.
    pub toml: &'static str,
}

impl Preset {
    /// The preset's scene, parsed and validated.
    ///
    /// # Errors
    /// None for the built-in texts (a test builds every one).
    pub fn scene(&self) -> Result<Scene, SceneError> {
        let file = format!("preset {}", self.name);
        SceneFile::parse(self.toml, &file)?.build(self.toml, &file)
    }
}

/// Two equal bodies of the given TOML body fields (shape and sizes) at the paper's start.
macro_rules! paper_scene {
    ($name:literal, $description:literal, $shape:literal, $method:literal, $step:literal) => {
        concat!(
            "# ",
            $description,
            "\n# Wold & Conway, The planar two-body problem for spheroids and disks (G = 1).\n",
            "name = \"",
            $name,
            "\"\n",
            "description = \"",
            $description,
            "\"\n",
            "gravitational_constant = 1.0\n",
            "t_end = 300.0\n",
            "\n[body_a]\n",
            $shape,
            "mass = 1.0\n",
            "position = [-3.5, 0.0, 0.0]\n",
            "velocity = [0.0, 0.2, 0.0]\n",
            "\n[body_b]\n",
            $shape,
            "mass = 1.0\n",
            "position = [3.5, 0.0, 0.0]\n",
            "velocity = [0.0, -0.2, 0.0]\n",
            "\n[integrator]\n",
            "method = \"",
            $method,
            "\"\n",
            "step = ",
            $step,
            "\n",
            "\n[interaction]\n",
            "tolerance = 1e-12   # relative accuracy of the surface integrals\n",
            "tabulate = true     # tabulated V(r): exact to ~1e-14, the pair is central\n",
            "\n[output]\n",
            "# every = 1       # every n-th step; or interval = 0.5 (dense output at t_start + k·0.5)\n",
            "# default: every step up to 10,000 rows, then a cadence that keeps ~10,000\n",
            "figures = [\"orbits\", \"conservation\", \"histograms\"]\n",
        )
    };
}

/// Every built-in scene.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "paper-2s",
        summary: "two oblate spheroids a = 1, c = 0.25, m = 1; RK4, dt = 0.1, t = 300 (paper's 2S)",
        toml: paper_scene!(
            "paper-2s",
            "Two oblate spheroids a = 1, c = 0.25, m = 1 (the paper's model 2S)",
            "shape = \"spheroid\"\nequatorial_radius = 1.0\npolar_radius = 0.25\n",
            "rk4",
            "0.1"
        ),
    },
    Preset {
        name: "paper-2s-prolate",
        summary: "two prolate spheroids a = 0.25, c = 1, m = 1; RK4, dt = 0.1, t = 300",
        toml: paper_scene!(
            "paper-2s-prolate",
            "Two prolate spheroids a = 0.25, c = 1, m = 1 (the paper's prolate variant of 2S)",
            "shape = \"spheroid\"\nequatorial_radius = 0.25\npolar_radius = 1.0\n",
            "rk4",
            "0.1"
        ),
    },
    Preset {
        name: "paper-2d",
        summary: "two uniform disks R = 1, m = 1; RK4, dt = 0.01, t = 300 (paper's 2D)",
        toml: paper_scene!(
            "paper-2d",
            "Two coplanar uniform thin disks R = 1, m = 1 (the paper's model 2D)",
            "shape = \"disk\"\nradius = 1.0\n",
            "rk4",
            "0.01"
        ),
    },
    Preset {
        name: "paper-point",
        summary: "two point masses m = 1; RK4, dt = 0.1, t = 300 (Kepler reference)",
        toml: paper_scene!(
            "paper-point",
            "Two point masses m = 1 (the Kepler reference)",
            "shape = \"point\"\n",
            "rk4",
            "0.1"
        ),
    },
    Preset {
        name: "paper-limit-round",
        summary:
            "two nearly spherical spheroids a = 1, c = 0.99, m = 1; RK4, dt = 0.1 (paper's Fig. 7)",
        toml: paper_scene!(
            "paper-limit-round",
            "Two nearly spherical spheroids a = 1, c = 0.99, m = 1 (the paper's Fig. 7)",
            "shape = \"spheroid\"\nequatorial_radius = 1.0\npolar_radius = 0.99\n",
            "rk4",
            "0.1"
        ),
    },
    Preset {
        name: "paper-limit-flat",
        summary: "two flat spheroids a = 1, c = 0.01, m = 1; RK4, dt = 0.1 (paper's Fig. 7)",
        toml: paper_scene!(
            "paper-limit-flat",
            "Two flat spheroids a = 1, c = 0.01, m = 1 (the paper's Fig. 7)",
            "shape = \"spheroid\"\nequatorial_radius = 1.0\npolar_radius = 0.01\n",
            "rk4",
            "0.1"
        ),
    },
];

/// The preset of that name.
pub fn find(name: &str) -> Option<&'static Preset> {
    PRESETS.iter().find(|p| p.name == name)
}

/// The names of every preset, comma-separated (for messages).
pub fn names() -> String {
    PRESETS
        .iter()
        .map(|p| p.name)
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_builds_and_round_trips_through_toml() {
        for preset in PRESETS {
            let file = SceneFile::parse(preset.toml, preset.name).unwrap();
            let scene = file.build(preset.toml, preset.name).unwrap();
            assert_eq!(scene.name, preset.name);
            // Serialised without comments, re-read: the same data and the same scene.
            let text = file.to_toml().unwrap();
            let again = SceneFile::parse(&text, "again").unwrap();
            assert_eq!(again, file, "{text}");
            assert_eq!(again.build(&text, "again").unwrap(), scene);
        }
    }

    #[test]
    fn presets_have_the_papers_initial_conditions() {
        for preset in PRESETS {
            let s = preset.scene().unwrap();
            let a = s.initial.body_a;
            let b = s.initial.body_b;
            assert_eq!(a.position.as_slice(), &[-3.5, 0.0, 0.0]);
            assert_eq!(b.position.as_slice(), &[3.5, 0.0, 0.0]);
            assert_eq!(a.velocity.as_slice(), &[0.0, 0.2, 0.0]);
            assert_eq!(b.velocity.as_slice(), &[0.0, -0.2, 0.0]);
            assert_eq!((s.t_start, s.t_end), (0.0, 300.0));
        }
        assert!(find("paper-2s").is_some() && find("paper-3s").is_none());
    }
}
