//! `surfgrav presets` and `surfgrav run` as a user meets them: the files a run writes, the
//! summary's keys, no progress bar on a pipe, and bad input refused with one line, exit code 2
//! and no output folder.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn surfgrav_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_surfgrav"))
        .args(args)
        .current_dir(dir)
        .env("RUST_BACKTRACE", "1")
        .output()
        .expect("the binary runs")
}

/// A fresh empty folder for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("surfgrav-cli-run-{test}-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn ok(out: &Output) {
    assert!(out.status.success(), "stderr: {}", stderr(out));
}

#[test]
fn presets_lists_and_shows_toml() {
    let dir = scratch("presets");
    let out = surfgrav_in(&dir, &["presets"]);
    ok(&out);
    let text = String::from_utf8(out.stdout).unwrap();
    for name in [
        "paper-2s",
        "paper-2s-prolate",
        "paper-2d",
        "paper-point",
        "paper-limit-round",
        "paper-limit-flat",
    ] {
        assert!(
            text.lines().any(|l| l.starts_with(name)),
            "{name} in {text}"
        );
    }
    let out = surfgrav_in(&dir, &["presets", "--show", "paper-2d"]);
    ok(&out);
    let toml = String::from_utf8(out.stdout).unwrap();
    assert!(
        toml.contains("shape = \"disk\"") && toml.contains("step = 0.01"),
        "{toml}"
    );
    let out = surfgrav_in(&dir, &["presets", "--show", "paper-3s"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("unknown preset `paper-3s`"));
    fs::remove_dir_all(&dir).unwrap();
}

/// The summary without its wall time.
fn summary_without_time(folder: &Path) -> serde_json::Value {
    let text = fs::read_to_string(folder.join("summary.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v.as_object_mut().unwrap().remove("wall_seconds");
    v
}

#[test]
fn run_writes_whole_folder_with_exact_summary_keys() {
    let dir = scratch("run");
    let out = surfgrav_in(&dir, &["run", "paper-point", "--t-end", "60"]);
    ok(&out);
    // stderr is a pipe here: no progress bar, nothing at all.
    assert_eq!(stderr(&out), "");
    assert!(String::from_utf8_lossy(&out.stdout).contains("wrote paper-point/"));
    // Only the final folder, no temporary left behind.
    assert_eq!(entries(&dir), vec!["paper-point".to_string()]);
    let folder = dir.join("paper-point");
    assert_eq!(
        entries(&folder),
        [
            "fig2_orbits.png",
            "fig2_orbits.svg",
            "fig3_conservation.png",
            "fig3_conservation.svg",
            "fig4_histograms.png",
            "fig4_histograms.svg",
            "summary.json",
            "trajectory.csv",
        ]
    );
    let summary: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(folder.join("summary.json")).unwrap()).unwrap();
    let keys: Vec<&str> = summary
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    let mut expected = vec![
        "scene",
        "t_end",
        "steps",
        "force_evaluations",
        "wall_seconds",
        "min_separation",
        "radial_period",
        "azimuthal_period",
        "precession_angle_deg",
        "precession_rate_arcmin",
        "energy",
        "angular_momentum",
    ];
    let mut got = keys.clone();
    got.sort_unstable();
    expected.sort_unstable();
    assert_eq!(got, expected);
    for quantity in ["energy", "angular_momentum"] {
        let mut inner: Vec<&str> = summary[quantity]
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        inner.sort_unstable();
        assert_eq!(
            inner,
            [
                "initial",
                "max_relative_drift",
                "mean_step_change",
                "slope",
                "std_error",
                "std_step_change"
            ]
        );
    }
    assert_eq!(summary["scene"], "paper-point");
    assert_eq!(summary["t_end"], 60.0);
    assert_eq!(summary["steps"], 600);
    // RK4 reuses the last stage: 4 evaluations per step plus the start.
    assert_eq!(summary["force_evaluations"], 2401);
    // One apocentre cycle (T_r = 47.6177) fits in 60 time units: the first pericentre is the
    // minimum separation 2.72222 of the Kepler orbit.
    let min = summary["min_separation"].as_f64().unwrap();
    assert!((min - 2.72222).abs() < 5e-6, "{min}");

    let csv = fs::read_to_string(folder.join("trajectory.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t,xa,ya,za,xb,yb,zb,vxa,vya,vza,vxb,vyb,vzb,separation,energy,angular_momentum"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 601);
    assert_eq!(rows[0][..7], [0.0, -3.5, 0.0, 0.0, 3.5, 0.0, 0.0]);
    let last = &rows[600];
    assert_eq!(last[0], 60.0);
    // Separation column agrees with the positions; energy column with E0 = T + V = 0.04 − 1/7.
    let d = ((last[4] - last[1]).powi(2) + (last[5] - last[2]).powi(2)).sqrt();
    assert!((last[13] - d).abs() <= 1e-14 * d);
    assert!((rows[0][14] - (0.04 - 1.0 / 7.0)).abs() < 1e-16);

    // Plots are real images.
    let png = fs::read(folder.join("fig2_orbits.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let svg = fs::read_to_string(folder.join("fig3_conservation.svg")).unwrap();
    assert!(svg.contains("<svg"));

    // A second run without --out goes to a new folder, never over the first.
    ok(&surfgrav_in(
        &dir,
        &["run", "paper-point", "--t-end", "1", "--quiet"],
    ));
    assert_eq!(entries(&dir), ["paper-point", "paper-point-2"]);
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn shown_preset_round_trips_through_a_file() {
    let dir = scratch("roundtrip");
    let shown = surfgrav_in(&dir, &["presets", "--show", "paper-2s"]);
    ok(&shown);
    fs::write(dir.join("mine.toml"), &shown.stdout).unwrap();
    let args = ["--t-end", "30", "--quiet", "--out"];
    ok(&surfgrav_in(
        &dir,
        &[
            "run",
            "mine.toml",
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
            "paper-2s",
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

#[test]
fn overrides_change_the_integrator_and_step() {
    let dir = scratch("overrides");
    for (args, steps) in [
        (&["--dt", "0.05"][..], Some(200)),
        (&["--integrator", "yoshida4"][..], Some(100)),
        (
            &["--integrator", "dop853", "--tolerance", "1e-10"][..],
            None,
        ),
    ] {
        let mut all = vec![
            "run",
            "paper-point",
            "--t-end",
            "10",
            "--quiet",
            "--out",
            "o",
        ];
        all.extend_from_slice(args);
        ok(&surfgrav_in(&dir, &all));
        let s = summary_without_time(&dir.join("o"));
        assert_eq!(s["t_end"], 10.0);
        if let Some(n) = steps {
            assert_eq!(s["steps"], n, "{args:?}");
        } else {
            assert!(s["steps"].as_u64().unwrap() > 0);
        }
        fs::remove_dir_all(dir.join("o")).unwrap();
    }
    fs::remove_dir_all(&dir).unwrap();
}

/// The paper-2s scene file with one substitution.
fn scene_with(dir: &Path, from: &str, to: &str) -> String {
    let shown = surfgrav_in(dir, &["presets", "--show", "paper-2s"]);
    let text = String::from_utf8(shown.stdout).unwrap();
    assert!(text.contains(from), "{from}");
    let name = format!("case-{}.toml", entries(dir).len());
    fs::write(dir.join(&name), text.replacen(from, to, 1)).unwrap();
    name
}

#[test]
fn bad_input_is_one_line_exit_2_and_no_folder() {
    let dir = scratch("bad");
    let malformed = scene_with(&dir, "t_end = 300.0", "t_end = = 300");
    let unknown_field = scene_with(
        &dir,
        "polar_radius = 0.25",
        "polar_radius = 0.25\nspin_rate = 1",
    );
    let unknown_method = scene_with(&dir, "method = \"rk4\"", "method = \"euler\"");
    let negative_size = scene_with(&dir, "polar_radius = 0.25", "polar_radius = -0.25");
    let zero_mass = scene_with(&dir, "mass = 1.0", "mass = 0.0");
    let zero_step = scene_with(&dir, "step = 0.1", "step = 0.0");
    let negative_end = scene_with(&dir, "t_end = 300.0", "t_end = -5.0");
    let overlap = scene_with(
        &dir,
        "position = [3.5, 0.0, 0.0]",
        "position = [-2.0, 0.0, 0.0]",
    );
    let tilted = scene_with(
        &dir,
        "velocity = [0.0, 0.2, 0.0]",
        "velocity = [0.0, 0.2, 0.0]\norientation = [0.3, 0.0, 0.0]",
    );
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["run", &tilted], "needs rotational dynamics"),
        (
            vec!["run", "missing.toml"],
            "missing.toml: cannot read the scene file",
        ),
        (vec!["run", "paper-3s"], "`paper-3s` is neither a preset"),
        (vec!["run", &malformed], ":6: "),
        (vec!["run", &unknown_field], "unknown field `spin_rate`"),
        (
            vec!["run", &unknown_method],
            "integrator.method: unknown integrator 'euler'",
        ),
        (
            vec!["run", &negative_size],
            "body_a.polar_radius: must be a positive",
        ),
        (vec!["run", &zero_mass], "body_a.mass: must be a positive"),
        (
            vec!["run", &zero_step],
            "integrator.step: must be a positive",
        ),
        (
            vec!["run", &negative_end],
            "t_end: must be finite and greater",
        ),
        (vec!["run", &overlap], "overlap"),
        (
            vec!["run", "paper-2s", "--integrator", "euler"],
            "--integrator: unknown integrator",
        ),
        (
            vec!["run", "paper-2s", "--dt", "0"],
            "--dt must be a positive",
        ),
        (
            vec!["run", "paper-2s", "--dt", "-0.1"],
            "--dt must be a positive",
        ),
        (
            vec!["run", "paper-2s", "--t-end", "0"],
            "--t-end must be finite and greater",
        ),
        (
            vec!["run", "paper-2s", "--t-end", "nan"],
            "--t-end must be a finite number",
        ),
        (
            vec!["run", "paper-2s", "--tolerance", "1e-9"],
            "--tolerance does not apply",
        ),
        (
            vec!["run", "paper-2s", "--integrator", "dopri5"],
            "needs --tolerance",
        ),
        (
            vec![
                "run",
                "paper-point",
                "--integrator",
                "dopri5",
                "--tolerance",
                "1e-300",
            ],
            "--tolerance: must lie in [1e-15, 1)",
        ),
    ];
    let before = entries(&dir);
    for (args, expected) in cases {
        let out = surfgrav_in(&dir, &args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
        assert_eq!(err.lines().count(), 1, "{args:?}: one line, got {err}");
        assert!(
            err.starts_with("error: ") && err.contains(expected),
            "{args:?}: `{err}` lacks `{expected}`"
        );
        assert!(
            !err.contains("panicked") && !err.contains("backtrace"),
            "{err}"
        );
        assert_eq!(entries(&dir), before, "{args:?} left something behind");
    }
    // An explicit --out that holds files is refused before running.
    fs::create_dir(dir.join("taken")).unwrap();
    fs::write(dir.join("taken/keep.txt"), "mine").unwrap();
    let out = surfgrav_in(&dir, &["run", "paper-point", "--out", "taken"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("already exists"), "{}", stderr(&out));
    assert_eq!(entries(&dir.join("taken")), ["keep.txt"]);
    for command in ["report", "bench"] {
        let out = surfgrav_in(&dir, &[command, "--out", "taken"]);
        assert_eq!(out.status.code(), Some(2), "{command}");
        assert!(stderr(&out).contains("already exists"), "{}", stderr(&out));
        assert_eq!(entries(&dir.join("taken")), ["keep.txt"]);
    }
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn failed_run_exits_1_and_leaves_no_folder() {
    let dir = scratch("failed");
    // Two point masses released at rest fall onto each other at t = (π/2) √(r0³ / (2GM)) =
    // 14.546: the adaptive step collapses below its floor there, a failure found only while
    // running (a tolerance out of range is bad input instead, exit 2).
    let scene = "name = \"infall\"\nt_end = 300.0\n\
        [body_a]\nshape = \"point\"\nmass = 1.0\nposition = [-3.5, 0.0, 0.0]\nvelocity = [0.0, 0.0, 0.0]\n\
        [body_b]\nshape = \"point\"\nmass = 1.0\nposition = [3.5, 0.0, 0.0]\nvelocity = [0.0, 0.0, 0.0]\n\
        [integrator]\nmethod = \"dopri5\"\ntolerance = 1e-10\n";
    fs::write(dir.join("infall.toml"), scene).unwrap();
    let out = surfgrav_in(&dir, &["run", "infall.toml"]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("at t = 14.54"),
        "the failure names its time: {err}"
    );
    assert_eq!(entries(&dir), ["infall.toml"]);
    fs::remove_dir_all(&dir).unwrap();
}
