//! Polyhedra as a user meets them: a scene file naming a mesh beside it, the command-line spec
//! `polyhedron:mesh=PATH,...` in `potential` and `interact`, bad input refused with one line
//! (exit 2, nothing written), and the presets `kw4-polyhedra` and `didymos-standard` (listed,
//! round-tripping through `presets --show`, and the Didymos start equal to GUBAS's file).

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use surfgrav_potentials::{LengthUnit, Mesh, Polyhedron, Potential, Vec3};
use surfgrav_scenarios::presets;

fn surfgrav_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_surfgrav"))
        .args(args)
        .current_dir(dir)
        .env("RUST_BACKTRACE", "1")
        .output()
        .expect("the binary runs")
}

fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "surfgrav-cli-polyhedra-{test}-{}",
        std::process::id()
    ));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn ok(out: &Output) {
    assert!(out.status.success(), "stderr: {}", stderr(out));
}

fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn shapes() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/shapes")
}

fn didymos_standard() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/didymos-standard")
}

/// The cube of side 2 centred at the origin, faces counter-clockwise seen from outside.
const CUBE_OBJ: &str = "# cube, side 2\n\
v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n\
f 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";

/// A cube (mass 1) and a small sphere 4 apart on a near-circular orbit, G = 1; RK4, two steps.
fn cube_scene(mesh: &str) -> String {
    format!(
        "name = \"cube-sphere\"\n\
         t_end = 1.0\n\
         \n[body_a]\n\
         shape = \"polyhedron\"\n\
         mesh = \"{mesh}\"\n\
         mass = 1.0\n\
         position = [0.0, 0.0, 0.0]\n\
         velocity = [0.0, 0.0, 0.0]\n\
         \n[body_b]\n\
         shape = \"sphere\"\n\
         radius = 0.5\n\
         mass = 0.001\n\
         position = [4.0, 0.0, 0.0]\n\
         velocity = [0.0, 0.5, 0.0]\n\
         \n[integrator]\n\
         method = \"rk4\"\n\
         step = 0.5\n"
    )
}

/// A scene in a folder of its own names its mesh relative to that folder; the run starts in
/// another folder, finds the mesh, integrates, says what it did to the mesh's frame.
#[test]
fn scene_file_with_a_polyhedron_runs() {
    let dir = scratch("scene");
    fs::create_dir_all(dir.join("scenes/meshes")).unwrap();
    fs::write(dir.join("scenes/meshes/cube.obj"), CUBE_OBJ).unwrap();
    fs::write(dir.join("scenes/cube.toml"), cube_scene("meshes/cube.obj")).unwrap();
    let out = surfgrav_in(
        &dir,
        &["run", "scenes/cube.toml", "--out", "result", "--quiet"],
    );
    ok(&out);
    let summary: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(dir.join("result/summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["steps"], 2, "{summary}");
    // The cube is not symmetric enough to freeze the attitudes: rotation is integrated.
    assert_eq!(summary["motion"]["path"], "rotation", "{summary}");
    let rows = fs::read_to_string(dir.join("result/trajectory.csv")).unwrap();
    assert_eq!(rows.lines().count(), 1 + 3, "{rows}");
    // Without --quiet the note names the mesh, its size and its frame.
    let out = surfgrav_in(&dir, &["run", "scenes/cube.toml", "--out", "again"]);
    ok(&out);
    let note = stderr(&out);
    assert!(
        note.contains("body_a:")
            && note.contains("cube.obj: 8 vertices, 12 faces")
            && note.contains("axes as in the file"),
        "{note}"
    );
    fs::remove_dir_all(&dir).unwrap();
}

fn json(out: &Output) -> serde_json::Value {
    ok(out);
    serde_json::from_slice(&out.stdout).unwrap()
}

/// `potential` and `interact` take the spec; the CLI's numbers are the library's, and
/// the cube's far field is nearly that of a point (no quadrupole by symmetry: the first
/// correction is of order (a/r)^4 = 1e-4 at r = 10 for half-side a = 1).
#[test]
fn spec_string_works_in_potential_and_interact() {
    let dir = scratch("spec");
    fs::write(dir.join("cube.obj"), CUBE_OBJ).unwrap();
    let v = json(&surfgrav_in(
        &dir,
        &[
            "potential",
            "--body",
            "polyhedron:mesh=cube.obj,density=0.125",
            "--at",
            "10,0,0",
        ],
    ));
    let mesh = Mesh::read_obj(dir.join("cube.obj"), LengthUnit::Metres).unwrap();
    let cube = Polyhedron::with_density(&mesh, 0.125).unwrap();
    let field = cube.field(&Vec3::new(10.0, 0.0, 0.0));
    let phi = v["potential"].as_f64().unwrap();
    // The library's number to the field's stated accuracy (1e-13 relative,
    // potentials::tolerance::POLYHEDRON_REL; measured: 1 ulp apart, separate builds).
    assert!(
        ((phi - field.potential) / field.potential).abs() < 1e-13,
        "{phi} vs {}",
        field.potential
    );
    assert!((phi + 0.1).abs() < 1e-4 * 0.1, "{phi}");

    // Kilometres: the same cube read in km is 1000 times larger; at 10 km the potential of a
    // mass of 1 is -1e-4 (to the same 1e-4).
    let v = json(&surfgrav_in(
        &dir,
        &[
            "potential",
            "--body",
            "polyhedron:mesh=cube.obj,mass=1,units=km",
            "--at",
            "10000,0,0",
        ],
    ));
    let phi = v["potential"].as_f64().unwrap();
    assert!((phi + 1e-4).abs() < 1e-4 * 1e-4, "{phi}");

    // The Didymos CSV pair: a far point sees G M / r with M = rho V (V = 248548158.0017 m^3
    // from the data's README, 10 digits); at 100 km the quadrupole is below 1e-5 of it.
    let (vert, facet) = (
        shapes().join("Didymos_A_vert_met.csv"),
        shapes().join("Didymos_A_facet.csv"),
    );
    let spec = format!(
        "polyhedron:mesh={},facets={},density=2103.985767887719",
        vert.display(),
        facet.display()
    );
    let v = json(&surfgrav_in(
        &dir,
        &[
            "potential",
            "--body",
            &spec,
            "--at",
            "0,0,1e5",
            "--g",
            "6.67408e-11",
        ],
    ));
    let expected = -6.67408e-11 * 2103.985767887719 * 248548158.0017 / 1e5;
    let phi = v["potential"].as_f64().unwrap();
    assert!(
        ((phi - expected) / expected).abs() < 1e-5,
        "{phi} vs {expected}"
    );

    // interact: the cube and a sphere 5 apart attract as points to (a/r)^4 ~ 1e-3, along +x;
    // the third law holds to the engine's tolerance.
    let v = json(&surfgrav_in(
        &dir,
        &[
            "interact",
            "--a",
            "polyhedron:mesh=cube.obj,mass=1",
            "--b",
            "sphere:radius=0.5,mass=1",
            "--position",
            "5,0,0",
        ],
    ));
    let fa: Vec<f64> = v["force_on_a"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let fb: Vec<f64> = v["force_on_b"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!((fa[0] - 1.0 / 25.0).abs() < 2e-3 / 25.0, "{fa:?}");
    assert!(fa[1].abs() < 1e-12 && fa[2].abs() < 1e-12, "{fa:?}");
    for k in 0..3 {
        assert!((fa[k] + fb[k]).abs() < 1e-10 * fa[0], "{fa:?} {fb:?}");
    }
    fs::remove_dir_all(&dir).unwrap();
}

/// Every mistake: exit 2, one line on stderr naming the file (and line) or the flag, nothing
/// on stdout, no output folder.
#[test]
fn bad_input_is_one_line_exit_2_and_writes_nothing() {
    let dir = scratch("bad");
    fs::write(dir.join("cube.obj"), CUBE_OBJ).unwrap();
    // Face 3 (0-based) reversed: edge 5 -> 7 is then used twice in the same direction.
    let flipped = CUBE_OBJ.replace("f 5 7 8", "f 5 8 7");
    fs::write(dir.join("flipped.obj"), flipped).unwrap();
    fs::write(
        dir.join("broken.obj"),
        CUBE_OBJ.replace("v 1 1 1", "v 1 x 1"),
    )
    .unwrap();
    let base = cube_scene("cube.obj");
    let scene_cases: &[(&str, String, &str)] = &[
        (
            "missing",
            base.replace("cube.obj", "nowhere.obj"),
            "missing.toml:6: body_a.mesh: polyhedron: cannot read the mesh",
        ),
        (
            "flipped",
            base.replace("cube.obj", "flipped.obj"),
            "flipped.toml:6: body_a.mesh: polyhedron: the mesh",
        ),
        (
            "broken",
            base.replace("cube.obj", "broken.obj"),
            "broken.obj:8",
        ),
        (
            "both",
            base.replace("mass = 1.0\n", "mass = 1.0\ndensity = 0.125\n"),
            "both.toml:8: body_a.density: give either mass or density, not both",
        ),
        (
            "units",
            base.replace("mass = 1.0\n", "mass = 1.0\nmesh_units = \"mm\"\n"),
            "units.toml:8: body_a.mesh_units: must be \"m\" or \"km\"",
        ),
        (
            "csv",
            base.replace("cube.obj", "vertices.csv"),
            "csv.toml:6: body_a.mesh: `",
        ),
        (
            "builtin",
            base.replace("cube.obj", "builtin:eros.obj"),
            "no built-in shape model `eros.obj`",
        ),
        (
            "size",
            base.replace("mass = 1.0\n", "mass = 1.0\nradius = 2.0\n"),
            "size.toml:8: body_a.radius: a polyhedron has no radius",
        ),
    ];
    for (name, text, expected) in scene_cases {
        let file = format!("{name}.toml");
        fs::write(dir.join(&file), text).unwrap();
        let before = entries(&dir);
        let out = surfgrav_in(&dir, &["run", &file, "--out", "out"]);
        let message = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{name}: {message}");
        assert!(
            message.contains(expected),
            "{name}: `{message}` lacks `{expected}`"
        );
        assert_eq!(message.trim_end().lines().count(), 1, "{name}: {message}");
        assert!(out.stdout.is_empty(), "{name}");
        assert_eq!(entries(&dir), before, "{name}: something was written");
    }
    // The flipped face is named with its edge.
    let out = surfgrav_in(&dir, &["run", "flipped.toml", "--out", "out"]);
    assert!(stderr(&out).contains("edge"), "{}", stderr(&out));

    let spec_cases: &[(&str, &str)] = &[
        ("polyhedron:mesh=nowhere.obj,density=1", "nowhere.obj"),
        (
            "polyhedron:mesh=cube.obj,density=1,units=mm",
            "`units=mm`: expected m or km",
        ),
        ("polyhedron:mesh=cube.obj,density=1,mass=1", "not both"),
        ("polyhedron:density=1", "a polyhedron needs `mesh`"),
        ("polyhedron:mesh=v.csv,density=1", "facets"),
        ("polyhedron:mesh=flipped.obj,density=1", "edge"),
        (
            "polyhedron:mesh=cube.obj,density=-1",
            "density must be a positive",
        ),
    ];
    for (spec, expected) in spec_cases {
        let out = surfgrav_in(&dir, &["potential", "--body", spec, "--at", "10,0,0"]);
        let message = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{spec}: {message}");
        assert!(
            message.contains(expected),
            "{spec}: `{message}` lacks `{expected}`"
        );
        assert_eq!(message.trim_end().lines().count(), 1, "{spec}: {message}");
        assert!(out.stdout.is_empty(), "{spec}");
    }
    fs::remove_dir_all(&dir).unwrap();
}

fn summary_without_time(folder: &Path) -> serde_json::Value {
    let text = fs::read_to_string(folder.join("summary.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v.as_object_mut().unwrap().remove("wall_seconds");
    v
}

/// Both presets are listed, and a shown preset saved in any folder runs to the same output as
/// the preset itself (the meshes are built in, so the saved file finds them anywhere).
#[test]
fn polyhedron_presets_are_listed_and_round_trip() {
    let dir = scratch("presets");
    let list = surfgrav_in(&dir, &["presets"]);
    ok(&list);
    let list = String::from_utf8(list.stdout).unwrap();
    assert!(
        list.contains("kw4-polyhedra") && list.contains("didymos-standard"),
        "{list}"
    );
    for name in ["kw4-polyhedra", "didymos-standard"] {
        let shown = surfgrav_in(&dir, &["presets", "--show", name]);
        ok(&shown);
        let text = String::from_utf8(shown.stdout).unwrap();
        assert!(text.contains("mesh = \"builtin:"), "{text}");
        // Saved and read back: the same scene as the preset.
        let file = format!("{name}.toml");
        fs::create_dir_all(dir.join("elsewhere")).unwrap();
        fs::write(dir.join("elsewhere").join(&file), &text).unwrap();
        let preset = presets::find(name).unwrap().scene().unwrap();
        let path = dir.join("elsewhere").join(&file);
        let (parsed, source) = surfgrav_scenarios::scene::SceneFile::read(&path).unwrap();
        let saved = parsed.build(&source, &path.display().to_string()).unwrap();
        assert_eq!(saved.initial, preset.initial, "{name}");
        assert_eq!(saved.body_a, preset.body_a, "{name}");
        assert_eq!(saved.body_b, preset.body_b, "{name}");
    }
    // The Didymos run, short (one DOP853 step is ~12 evaluations of ~3 ms), both ways.
    let shown = surfgrav_in(&dir, &["presets", "--show", "didymos-standard"]);
    fs::write(dir.join("elsewhere/mine.toml"), &shown.stdout).unwrap();
    let args = ["--t-end", "100", "--quiet", "--out"];
    ok(&surfgrav_in(
        &dir,
        &[
            "run",
            "elsewhere/mine.toml",
            args[0],
            args[1],
            args[2],
            args[3],
            "from-file",
        ],
    ));
    ok(&surfgrav_in(
        &dir,
        &[
            "run",
            "didymos-standard",
            args[0],
            args[1],
            args[2],
            args[3],
            "from-preset",
        ],
    ));
    assert_eq!(
        summary_without_time(&dir.join("from-file")),
        summary_without_time(&dir.join("from-preset"))
    );
    assert_eq!(
        fs::read(dir.join("from-file/trajectory.csv")).unwrap(),
        fs::read(dir.join("from-preset/trajectory.csv")).unwrap()
    );
    fs::remove_dir_all(&dir).unwrap();
}

/// The numbers of GUBAS's `initstate_standard_MKS_units` and `systemdata_standard_MKS_units`.
fn gubas_file(name: &str) -> Vec<f64> {
    fs::read_to_string(didymos_standard().join(name))
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect()
}

/// The preset's start reproduces the GUBAS file: the separation, the relative momentum μv, both
/// bodies' angular momenta (I ω, with our inertia tensors from the mesh and the ellipsoid) and
/// the masses. Tolerances: the masses and inertia come from our own volume and moment sums over
/// the mesh, which agree with GUBAS's to rounding of sums of ~2,000 terms (1e-12 allowed); the
/// state itself is the file's numbers divided and split about the centre of mass (1e-14).
#[test]
fn didymos_standard_reproduces_the_gubas_initial_state() {
    let state = gubas_file("initstate_standard_MKS_units");
    let system = gubas_file("systemdata_standard_MKS_units");
    let (m_a, m_b, mu) = (system[22], system[23], system[24]);
    let i_a = nalgebra::Matrix3::from_row_slice(&system[4..13]);
    let i_b = nalgebra::Matrix3::from_row_slice(&system[13..22]);
    let scene = presets::find("didymos-standard").unwrap().scene().unwrap();
    let (a, b) = (&scene.initial.body_a, &scene.initial.body_b);
    let relative = b.position - a.position;
    let r_file = Vec3::new(state[0], state[1], state[2]);
    assert!(
        (relative - r_file).norm() < 1e-14 * r_file.norm(),
        "{relative:?}"
    );
    assert!(
        (relative.norm() - 1180.0).abs() < 1e-12,
        "{}",
        relative.norm()
    );
    let momentum = (b.velocity - a.velocity) * mu;
    let p_file = Vec3::new(state[3], state[4], state[5]);
    assert!(
        (momentum - p_file).norm() < 1e-14 * p_file.norm(),
        "{momentum:?}"
    );
    // The centre of mass is at rest at the origin.
    let centre = a.position * m_a + b.position * m_b;
    let drift = a.velocity * m_a + b.velocity * m_b;
    assert!(centre.norm() < 1e-14 * m_a * relative.norm(), "{centre:?}");
    assert!(drift.norm() < 1e-14 * momentum.norm(), "{drift:?}");

    let body_a = scene.body_a.potential();
    let body_b = scene.body_b.potential();
    let rel = |x: f64, y: f64| ((x - y) / y).abs();
    assert!(
        rel(body_a.mass(), m_a) < 1e-12,
        "{} vs {m_a}",
        body_a.mass()
    );
    assert!(
        rel(body_b.mass(), m_b) < 1e-14,
        "{} vs {m_b}",
        body_b.mass()
    );
    let inertia_a = *body_a.inertia().unwrap().tensor();
    let inertia_b = *body_b.inertia().unwrap().tensor();
    assert!((inertia_a - i_a).norm() < 1e-12 * i_a.norm(), "{inertia_a}");
    assert!((inertia_b - i_b).norm() < 1e-12 * i_b.norm(), "{inertia_b}");
    // H = I ω in the body frame (the orientations are the identity at the start).
    let h_a = inertia_a * a.angular_velocity;
    let h_b = inertia_b * b.angular_velocity;
    let h_a_file = Vec3::new(state[6], state[7], state[8]);
    let h_b_file = Vec3::new(state[9], state[10], state[11]);
    assert!((h_a - h_a_file).norm() < 1e-12 * h_a_file.norm(), "{h_a:?}");
    assert!((h_b - h_b_file).norm() < 1e-12 * h_b_file.norm(), "{h_b:?}");
    // The spin rates are the system file's.
    assert_eq!(a.angular_velocity.z, system[27]);
    assert_eq!(b.angular_velocity.z, system[30]);
}
