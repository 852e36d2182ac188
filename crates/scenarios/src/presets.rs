//! Built-in scenes as TOML text a user can print (`surfgrav presets --show NAME`), save, edit
//! and run: the founding paper's (Wold & Conway, *The planar two-body problem for spheroids and
//! disks*, Table 1 and Sect. 4), and full two-body scenes in 3-D with their provenance in the
//! text (`sphere-triaxial`, `kw4-ellipsoids`, `didymos-ellipsoids`).
//!
//! Every `paper-*` preset starts from the paper's initial conditions: $\mathbf R_A = (-3.5, 0, 0)$,
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
    Preset {
        name: "sphere-triaxial",
        summary: "a sphere and a librating triaxial ellipsoid in synchronous orbit; DOP853, 1e-11, t = 500",
        toml: SPHERE_TRIAXIAL,
    },
    Preset {
        name: "kw4-ellipsoids",
        summary: "1999 KW4 as two triaxial ellipsoids (Ho et al. 2021), SI; DOP853, 1e-12, 10 orbits",
        toml: KW4_ELLIPSOIDS,
    },
    Preset {
        name: "didymos-ellipsoids",
        summary: "the DART standard Didymos system, primary as its inertia-equivalent ellipsoid, SI; DOP853, 1e-12, 10 orbits",
        toml: DIDYMOS_ELLIPSOIDS,
    },
];

/// A spin–orbit scene (G = 1): a sphere and a triaxial ellipsoid on a circular orbit 4 apart,
/// the ellipsoid spinning at the mean motion with its long axis 0.1 rad off the line of
/// centres, so it librates (period about 51: the small-body limit 2π/(n_A√(3(B − A)/C)) = 49.7,
/// n_A² = G m_A/r³, plus a few per cent for its size and mass).
const SPHERE_TRIAXIAL: &str = r#"# A sphere and a triaxial ellipsoid in synchronous orbit: spin-orbit libration.
# Circular orbit of two point masses of the same masses, 4 apart (n = sqrt(1.1/4^3)), about the
# centre of mass; the ellipsoid spins at n about its c axis, its long axis turned 0.1 rad from
# the line of centres. It librates with a period of about 51 (the small-body limit
# 2 pi / (n_A sqrt(3 (B - A) / C)) = 49.7 with n_A^2 = G m_A / r^3, which the tests check,
# plus a few per cent for this body's size and mass); the orbit period is 48.
name = "sphere-triaxial"
description = "A sphere and a librating triaxial ellipsoid in synchronous orbit (G = 1)"
gravitational_constant = 1.0
t_end = 500.0

[body_a]
shape = "sphere"
radius = 1.0
mass = 1.0
position = [-0.36363636363636365, 0.0, 0.0]
velocity = [0.0, -0.04767312946227962, 0.0]

[body_b]
shape = "ellipsoid"
semi_axes = [0.5, 0.35, 0.25]
mass = 0.1
position = [3.6363636363636362, 0.0, 0.0]
velocity = [0.0, 0.4767312946227962, 0.0]
orientation = [0.0, 0.0, 0.1]
angular_velocity = [0.0, 0.0, 0.13110110602126895]

[integrator]
method = "dop853"
tolerance = 1e-11

[output]
interval = 0.5
"#;

/// 1999 KW4 as two ellipsoids: the numbers of `cargo run --release -p surfgrav-dynamics
/// --example kw4_ellipsoids toml`, from the published inputs quoted in the text.
const KW4_ELLIPSOIDS: &str = r#"# (66391) 1999 KW4 as two homogeneous triaxial ellipsoids, SI units.
# Inputs: Ho et al. 2021 (CeMDA 133:35), the input file of SIANS: masses 2.353e12 and
# 0.135e12 kg; semi-axes 766 x 747.5 x 673.5 m and 285 x 231.5 x 174.5 m; relative orbit
# a = 2548 m, e = 0.0004, i = 156.1 deg, node 105.4 deg, longitude of pericentre 319.7 deg,
# mean anomaly 0 (ecliptic frame); Tait-Bryan angles (3.2, 0, 0) and (0, 0, 0) deg, read as a
# yaw about the orbit normal from the orbit frame (x toward the secondary, z along the orbit
# normal); spins 2.2728 and 0.3611 rad/h about the c axes (the secondary's is synchronous).
# Positions and velocities about the centre of mass; orientations as rotation vectors; these
# numbers are printed by `cargo run --release -p surfgrav-dynamics --example kw4_ellipsoids toml`.
# Mutual period 62,713 s (17.42 h); 10 orbits.
name = "kw4-ellipsoids"
description = "1999 KW4 as two triaxial ellipsoids (Ho et al. 2021)"
gravitational_constant = 6.674e-11
t_end = 627135.0

[body_a]
shape = "ellipsoid"
semi_axes = [766.0, 747.5, 673.5]
mass = 2.353e12
position = [38.32740053558199, 128.97595789330913, 31.552217309373646]
velocity = [0.012163772512341143, -0.0047492525980894675, 0.004637823724933635]
orientation = [-1.5303290615437433, 2.2730824660021964, -0.18450169229336363]
angular_velocity = [0.0002465957329060106, 6.792378133091137e-5, -0.0005771989970712317]

[body_b]
shape = "ellipsoid"
semi_axes = [285.0, 231.5, 174.5]
mass = 0.135e12
position = [-668.0323960016624, -2248.003177207084, -549.9434616959718]
velocity = [-0.21201004978917562, 0.08277771380225568, -0.08083554981310254]
orientation = [-1.5948463030384303, 2.2317698717567627, -0.19998806663217072]
angular_velocity = [3.917886270343208e-5, 1.0791656739964842e-5, -9.170475089863682e-5]

[integrator]
method = "dop853"
tolerance = 1e-12

[output]
interval = 600.0
"#;

/// The DART Dynamics Working Group's standard Didymos system (as shipped with GUBAS), the
/// primary replaced by its inertia-equivalent ellipsoid.
const DIDYMOS_ELLIPSOIDS: &str = r#"# The DART standard Didymos system (Agrusa et al. 2020, Icarus 349, 113849; the GUBAS inputs
# "systemdata_standard_MKS_units" and "initstate_standard_MKS_units"), SI units, G = 6.67408e-11.
# Primary: M_A = 522941787070.368835 kg, as the homogeneous ellipsoid with its inertia tensor
# I_A = diag(3.1348424975008636e16, 3.1920248302583308e16, 3.2790416201495100e16) kg m^2:
# a^2 = 5 (I2 + I3 - I1) / (2 M) and cyclic gives 399.366 x 392.461 x 381.714 m.
# Secondary: M_B = 4842963890.058684 kg, the triaxial ellipsoid of I_B
# (103.678 x 79.753 x 66.461 m). Separation 1180 m along the primary's x axis, relative velocity
# n r = 0.172776 m/s with n = 1.4642023926126924e-4 rad/s (P = 11.92 h); spins
# 7.7226958052846407e-4 and 1.488075e-4 rad/s about the c axes; positions and velocities about
# the centre of mass. 10 orbits.
name = "didymos-ellipsoids"
description = "The DART standard Didymos system, primary as its inertia-equivalent ellipsoid"
gravitational_constant = 6.67408e-11
t_end = 429120.0

[body_a]
shape = "ellipsoid"
semi_axes = [399.3658533990928, 392.46109883304524, 381.71426914779266]
mass = 522941787070.368835
position = [-10.827704627445227, 0.0, 0.0]
velocity = [0.0, -0.0015853951022008824, 0.0]
angular_velocity = [0.0, 0.0, 7.7226958052846407e-4]

[body_b]
shape = "ellipsoid"
semi_axes = [103.67778603285892, 79.75260472664658, 66.46050384649364]
mass = 4842963890.058684
position = [1169.1722953725548, 0.0, 0.0]
velocity = [0.0, 0.17119048722609684, 0.0]
angular_velocity = [0.0, 0.0, 1.488075e-4]

[integrator]
method = "dop853"
tolerance = 1e-12

[output]
interval = 600.0
"#;

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
        for preset in PRESETS.iter().filter(|p| p.name.starts_with("paper-")) {
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
