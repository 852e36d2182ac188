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
        "output",
        "motion",
        "angular_momentum_vector_max_relative_drift",
        "linear_momentum_max_relative_drift",
        "spins",
        "mutual_orbit",
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
    // Point masses cannot rotate: the translation path, and no spins.
    assert_eq!(summary["motion"]["path"], "translation");
    assert!(summary["spins"][0]["libration_deg"].is_null());
    // 600 steps: every step is written, and the summary says so.
    assert_eq!(summary["output"]["every"], 1);
    assert_eq!(summary["output"]["rows"], 601);
    assert_eq!(summary["output"]["chosen_by"], "default");
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
        "t,xa,ya,za,xb,yb,zb,vxa,vya,vza,vxb,vyb,vzb,separation,energy,angular_momentum,\
         qwa,qxa,qya,qza,qwb,qxb,qyb,qzb,wxa,wya,wza,wxb,wyb,wzb,jx,jy,jz"
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
    let long_step = scene_with(&dir, "step = 0.1", "step = 500");
    let far_apart = scene_with(
        &dir,
        "position = [3.5, 0.0, 0.0]",
        "position = [1e307, 0.0, 0.0]",
    );
    let duplicate = scene_with(
        &dir,
        "polar_radius = 0.25",
        "polar_radius = 0.25\nmass = 2.0",
    );
    let tiny_mass = scene_with(&dir, "mass = 1.0", "mass = 1e-320");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["run", &long_step],
            "integrator.step: the step 500 is longer than the run (t_end − t_start = 300)",
        ),
        (
            vec!["run", "paper-2s", "--dt", "500"],
            "--dt: the step 500 is longer than the run",
        ),
        (
            vec!["run", "paper-2s", "--t-end", "0.05"],
            "--t-end: the step 0.1 is longer than the run",
        ),
        // Shorter than the run but longer than the orbit's time scale (τ = 13.1): two steps of
        // meaningless numbers once, now refused.
        (
            vec!["run", "paper-2s", "--dt", "200"],
            "--dt: the step 200 is longer than the orbit's dynamical time √(r³/G(m_A + m_B)) = 13.1",
        ),
        (vec!["run", &far_apart], "values out of range"),
        (vec!["run", &duplicate], "duplicate key `mass`"),
        // A subnormal mass: a short message with the number in scientific form.
        (vec!["run", &tiny_mass], "e-32"),
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
        // Short, with compact numbers (a subnormal mass once printed 330 digits), and never
        // the advice to relax a tolerance for values out of range.
        assert!(err.len() < 300, "{args:?}: {} characters", err.len());
        assert!(!err.contains("relax"), "{err}");
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

/// An output path that cannot be written is refused at once (exit 2, before any computation),
/// naming the missing folder or the file in the way, for run, report and bench alike.
#[test]
fn output_paths_are_checked_before_computing() {
    let dir = scratch("paths");
    fs::write(dir.join("afile"), "not a folder").unwrap();
    for command in [
        &["run", "paper-2s"][..],
        &["report"][..],
        &["bench", "--quick"][..],
    ] {
        for (out, expected) in [
            ("zz/yy", "the folder zz does not exist"),
            ("afile/x", "afile is a file, not a folder"),
        ] {
            let mut args = command.to_vec();
            args.extend(["--out", out]);
            let started = std::time::Instant::now();
            let result = surfgrav_in(&dir, &args);
            let seconds = started.elapsed().as_secs_f64();
            let err = stderr(&result);
            assert_eq!(result.status.code(), Some(2), "{args:?}: {err}");
            assert!(
                err.contains(expected),
                "{args:?}: `{err}` lacks `{expected}`"
            );
            assert_eq!(err.lines().count(), 1, "{err}");
            // Nothing was computed: the full run, report or bench take seconds; a refusal takes
            // the process start (measured ~5 ms; 1 s leaves room for a loaded machine).
            assert!(seconds < 1.0, "{args:?} took {seconds} s before refusing");
            assert_eq!(entries(&dir), ["afile"], "{args:?} left something behind");
        }
    }
    fs::remove_dir_all(&dir).unwrap();
}

/// A reader that closes the pipe early (`surfgrav run paper-2s | head -1`) ends the program
/// quietly: exit 0, no panic message, no backtrace (it once panicked with exit 101).
#[test]
fn a_closed_pipe_ends_quietly() {
    let dir = scratch("pipe");
    let commands: [&[&str]; 5] = [
        &["run", "paper-point", "--t-end", "30", "--out", "piped"],
        &["presets"],
        &["presets", "--show", "paper-2s"],
        &[
            "potential",
            "--body",
            "sphere:radius=1,mass=1",
            "--at",
            "3,0,0",
        ],
        &["--help"],
    ];
    for args in commands {
        let mut child = Command::new(env!("CARGO_BIN_EXE_surfgrav"))
            .args(args)
            .current_dir(&dir)
            .env("RUST_BACKTRACE", "1")
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("the binary starts");
        // Close the reading end before the program writes anything.
        drop(child.stdout.take());
        let out = child.wait_with_output().expect("the binary ends");
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(0), "{args:?}: {err}");
        assert!(
            !err.contains("panicked") && !err.contains("Broken pipe") && !err.contains("backtrace"),
            "{args:?}: {err}"
        );
    }
    // The run still wrote its folder whole.
    assert!(dir.join("piped/summary.json").is_file());
    fs::remove_dir_all(&dir).unwrap();
}

/// A scene name that cannot name a folder runs when --out is given, and without --out is
/// refused with the advice to give it.
#[test]
fn any_scene_name_runs_with_out() {
    let dir = scratch("names");
    let file = scene_with(
        &dir,
        "name = \"paper-2s\"",
        "name = \"Ψ ellipsoïdes / test\"",
    );
    let short = ["--t-end", "10", "--quiet"];
    let out = surfgrav_in(&dir, &["run", &file, short[0], short[1], short[2]]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("give --out"), "{}", stderr(&out));
    let out = surfgrav_in(
        &dir,
        &["run", &file, short[0], short[1], short[2], "--out", "psi"],
    );
    ok(&out);
    let summary = summary_without_time(&dir.join("psi"));
    assert_eq!(summary["scene"], "Ψ ellipsoïdes / test");
    fs::remove_dir_all(&dir).unwrap();
}

fn csv_rows(folder: &Path) -> Vec<Vec<f64>> {
    fs::read_to_string(folder.join("trajectory.csv"))
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect()
}

/// A long run writes a bounded trajectory by default (10,000 rows and the last, evenly spaced
/// steps), says so in summary.json, keeps its files small, and its diagnostics still see every
/// step. 300,000 RK4 steps of point masses.
#[test]
fn long_runs_write_proportionate_outputs() {
    let dir = scratch("long");
    ok(&surfgrav_in(
        &dir,
        &[
            "run",
            "paper-point",
            "--t-end",
            "3000",
            "--dt",
            "0.01",
            "--quiet",
            "--out",
            "long",
        ],
    ));
    let folder = dir.join("long");
    let summary = summary_without_time(&folder);
    assert_eq!(summary["steps"], 300_000);
    assert_eq!(summary["output"]["every"], 30);
    assert_eq!(summary["output"]["rows"], 10_001);
    assert_eq!(summary["output"]["chosen_by"], "default");
    let rows = csv_rows(&folder);
    assert_eq!(rows.len(), 10_001);
    // Every 30th step of 0.01: t = 0.3 k (to the accumulated round-off of the step times).
    for (k, row) in rows.iter().enumerate().step_by(997) {
        assert!((row[0] - 0.3 * k as f64).abs() < 1e-9, "{k}: {}", row[0]);
    }
    assert_eq!(rows.last().unwrap()[0], 3000.0);
    // Diagnostics from every step: 63 radial periods of 47.6177 fit; RK4's per-step energy
    // scatter is over 300,000 changes (the figure of Fig. 4 counts them).
    let period = summary["radial_period"].as_f64().unwrap();
    assert!((period - 47.6177).abs() < 1e-3, "{period}");
    for entry in fs::read_dir(&folder).unwrap() {
        let entry = entry.unwrap();
        let bytes = entry.metadata().unwrap().len();
        // 10,001 rows of 16 numbers are ~3 MB; figures are thinned to a page.
        assert!(bytes < 4_000_000, "{:?}: {bytes} bytes", entry.file_name());
    }
    fs::remove_dir_all(&dir).unwrap();
}

/// `[output] interval` writes the states at t_start + kΔ exactly, from the dense output, for
/// fixed and adaptive integrators alike: DOP853 (its own continuous extension) and RK4 at a
/// small step (quintic Hermite) agree at every written time to the integrators' accuracy.
#[test]
fn output_interval_gives_evenly_spaced_rows_for_every_integrator() {
    let dir = scratch("interval");
    let shown = surfgrav_in(&dir, &["presets", "--show", "paper-point"]);
    let text = String::from_utf8(shown.stdout).unwrap();
    assert!(text.contains("figures = ["));
    fs::write(
        dir.join("points.toml"),
        text.replacen("figures = [", "interval = 0.5\nfigures = [", 1),
    )
    .unwrap();
    let common = ["--t-end", "100", "--quiet", "--out"];
    ok(&surfgrav_in(
        &dir,
        &[
            "run",
            "points.toml",
            common[0],
            common[1],
            common[2],
            common[3],
            "adaptive",
            "--integrator",
            "dop853",
            "--tolerance",
            "1e-12",
        ],
    ));
    ok(&surfgrav_in(
        &dir,
        &[
            "run",
            "points.toml",
            common[0],
            common[1],
            common[2],
            common[3],
            "fixed",
            "--dt",
            "0.01",
        ],
    ));
    let adaptive = csv_rows(&dir.join("adaptive"));
    let fixed = csv_rows(&dir.join("fixed"));
    let summary = summary_without_time(&dir.join("adaptive"));
    assert_eq!(summary["output"]["interval"], 0.5);
    assert_eq!(summary["output"]["chosen_by"], "scene");
    // t = 0, 0.5, …, 100: 201 rows, at exactly 0.5 k.
    assert_eq!((adaptive.len(), fixed.len()), (201, 201));
    // DOP853 at 1e-12 takes far fewer steps than it writes rows: no polygon of its own steps.
    assert!(
        summary["steps"].as_u64().unwrap() < 201,
        "{}",
        summary["steps"]
    );
    for (k, (a, f)) in adaptive.iter().zip(&fixed).enumerate() {
        assert_eq!(a[0], 0.5 * k as f64);
        assert_eq!(f[0], 0.5 * k as f64);
        // RK4 at dt = 0.01 is accurate to ~1e-8 in position over 100 time units (error ∝ dt⁴);
        // DOP853 to ~1e-10. Positions agree to 1e-6.
        for c in 1..7 {
            assert!(
                (a[c] - f[c]).abs() < 1e-6,
                "t = {}: column {c}: {} vs {}",
                a[0],
                a[c],
                f[c]
            );
        }
    }
    fs::remove_dir_all(&dir).unwrap();
}

/// An SI run prints its numbers with significant digits and SI units (Ω_p once printed
/// `0.000′`).
#[test]
fn si_runs_print_significant_digits_and_units() {
    let dir = scratch("si");
    // A point and a sphere of 1.5e10 kg 7 m apart at ±0.2 m/s: G(m_A + m_B) = 2.0 m³/s², the
    // paper's point-mass orbit in SI units (T_r = 47.6 s).
    let text = "name = \"si\"\nunits = \"si\"\nt_end = 300.0\n\
        [body_a]\nshape = \"point\"\nmass = 1.49828e10\nposition = [-3.5, 0.0, 0.0]\nvelocity = [0.0, 0.2, 0.0]\n\
        [body_b]\nshape = \"sphere\"\nradius = 0.5\nmass = 1.49828e10\nposition = [3.5, 0.0, 0.0]\nvelocity = [0.0, -0.2, 0.0]\n\
        [integrator]\nmethod = \"rk4\"\nstep = 0.1\n";
    fs::write(dir.join("si.toml"), text).unwrap();
    let out = surfgrav_in(&dir, &["run", "si.toml", "--out", "o"]);
    ok(&out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("′ per s"), "{stdout}");
    assert!(
        stdout.contains(" s, T_ψ = ") || stdout.contains("T_r = n/a"),
        "{stdout}"
    );
    assert!(!stdout.contains("0.000′"), "{stdout}");
    fs::remove_dir_all(&dir).unwrap();
}
