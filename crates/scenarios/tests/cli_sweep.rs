//! `surfgrav sweep` as a user meets it: a grid of paper-2s variants gives one task and one row per
//! parameter set, each equal to `surfgrav run` of that scene; a re-run skips finished tasks;
//! shards merge into the unsharded results; Monte Carlo draws follow the seed; bad input is one
//! line, exit code 2 and nothing written.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

fn surfgrav_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_surfgrav"))
        .args(args)
        .current_dir(dir)
        .env("RUST_BACKTRACE", "1")
        .output()
        .expect("the binary runs")
}

fn scratch(test: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("surfgrav-cli-sweep-{test}-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn ok(out: &Output) {
    assert!(
        out.status.success(),
        "stdout: {}\nstderr: {}",
        stdout(out),
        stderr(out)
    );
}

fn json(path: &Path) -> Value {
    serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap()
}

/// results.csv as rows of cells (no quoted commas in these sweeps' cells but the vectors').
fn csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    (
        header,
        lines
            .map(|l| l.split(',').map(str::to_string).collect())
            .collect(),
    )
}

/// The rows without the wall_seconds column (which differs between runs).
fn without_wall(path: &Path) -> Vec<Vec<String>> {
    let (header, rows) = csv(path);
    let wall = header.iter().position(|h| h == "wall_seconds").unwrap();
    rows.into_iter()
        .map(|mut r| {
            r.remove(wall);
            r
        })
        .collect()
}

/// summary.json without wall_seconds.
fn summary(path: &Path) -> Value {
    let mut v = json(path);
    v.as_object_mut().unwrap().remove("wall_seconds");
    v
}

const GRID: &str = r#"
base = "paper-2s"
name = "grid"

[set]
t_end = 10.0

[[vary]]
field = "body_b.mass"
values = [0.8, 1.25]

[[vary]]
field = "body_b.polar_radius"
linspace = [0.25, 0.4, 2]
"#;

/// The paper-2s scene with B's mass and polar radius changed and t = 10, written by hand.
fn paper_2s_variant(mass: &str, polar: &str) -> String {
    let preset = surfgrav_in(&std::env::temp_dir(), &["presets", "--show", "paper-2s"]);
    ok(&preset);
    let text = stdout(&preset).replace("t_end = 300.0", "t_end = 10.0");
    let b = "polar_radius = 0.25\nmass = 1.0\nposition = [3.5";
    assert!(text.contains(b));
    text.replace(
        b,
        &format!("polar_radius = {polar}\nmass = {mass}\nposition = [3.5"),
    )
}

#[test]
fn grid_tasks_equal_single_runs_and_resume_skips_finished_ones() {
    let dir = scratch("grid");
    fs::write(dir.join("grid.toml"), GRID).unwrap();
    let out = surfgrav_in(&dir, &["sweep", "grid.toml", "--quiet"]);
    ok(&out);
    assert!(stdout(&out).is_empty() && stderr(&out).is_empty());
    let root = dir.join("grid");
    let (header, rows) = csv(&root.join("results.csv"));
    assert_eq!(
        header[..4],
        ["task", "status", "body_b.mass", "body_b.polar_radius"]
    );
    assert_eq!(rows.len(), 4);
    let manifest = json(&root.join("manifest.json"));
    assert_eq!(manifest["tasks_total"], 4);
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    // Last [[vary]] fastest: (0.8, 0.25), (0.8, 0.4), (1.25, 0.25), (1.25, 0.4).
    let expected = [
        ("0.8", "0.25"),
        ("0.8", "0.4"),
        ("1.25", "0.25"),
        ("1.25", "0.4"),
    ];
    for (k, (mass, polar)) in expected.iter().enumerate() {
        let row = &rows[k];
        assert_eq!(row[0], k.to_string());
        assert_eq!(row[1], "done");
        assert_eq!((row[2].as_str(), row[3].as_str()), (*mass, *polar));
        assert_eq!(manifest["tasks"][k]["status"], "done");
        // The same scene run on its own gives the same summary, value for value.
        let scene = dir.join(format!("single-{k}.toml"));
        fs::write(&scene, paper_2s_variant(mass, polar)).unwrap();
        let single = dir.join(format!("single-{k}"));
        ok(&surfgrav_in(
            &dir,
            &[
                "run",
                scene.to_str().unwrap(),
                "--out",
                single.to_str().unwrap(),
                "--quiet",
            ],
        ));
        let task = root.join(format!("tasks/{k:05}"));
        let (mine, theirs) = (
            summary(&task.join("summary.json")),
            summary(&single.join("summary.json")),
        );
        assert_eq!(mine, theirs, "task {k}");
        // The row carries the summary's key outputs.
        // (serde_json's default float parser may miss the last bit: one ulp allowed here; the
        // summaries above are compared as parsed alike.)
        let number = |c: &str| row[col(c)].parse::<f64>().unwrap();
        let same = |x: f64, y: &Value| {
            let y = y.as_f64().unwrap();
            assert!((x - y).abs() <= f64::EPSILON * y.abs(), "{x} against {y}");
        };
        same(number("min_separation"), &theirs["min_separation"]);
        same(
            number("energy_drift"),
            &theirs["energy"]["max_relative_drift"],
        );
        same(
            number("angular_momentum_drift"),
            &theirs["angular_momentum"]["max_relative_drift"],
        );
        assert_eq!(number("mass_b"), mass.parse::<f64>().unwrap());
        assert_eq!(number("t_reached"), 10.0);
        assert_eq!(row[col("termination")], "completed");
        // Only what was asked for: no trajectory or figures.
        assert!(!task.join("trajectory.csv").exists());
        assert!(task.join("scene.toml").is_file() && task.join("task.toml").is_file());
    }
    // The tasks differ (the grid reached the scenes).
    assert_ne!(
        rows[0][col("min_separation")],
        rows[3][col("min_separation")]
    );

    // A re-run skips every finished task: nothing is rewritten.
    let stamp = |k: usize| {
        fs::metadata(root.join(format!("tasks/{k:05}/summary.json")))
            .unwrap()
            .modified()
            .unwrap()
    };
    let before: Vec<_> = (0..4).map(stamp).collect();
    let again = surfgrav_in(&dir, &["sweep", "grid.toml"]);
    ok(&again);
    assert!(
        stdout(&again).contains("0 run now, 4 already done"),
        "{}",
        stdout(&again)
    );
    assert_eq!((0..4).map(stamp).collect::<Vec<_>>(), before);
    assert_eq!(
        without_wall(&root.join("results.csv")),
        rows.iter()
            .map(|r| {
                let mut r = r.clone();
                r.remove(col("wall_seconds"));
                r
            })
            .collect::<Vec<_>>()
    );
    // A task killed mid-way leaves only a hidden partial folder: it is not finished and runs
    // again; so does a task whose folder was removed.
    fs::remove_dir_all(root.join("tasks/00002")).unwrap();
    fs::create_dir(root.join("tasks/.00002.partial-4999999")).unwrap();
    fs::write(root.join("tasks/.00002.partial-4999999/scene.toml"), "x").unwrap();
    let third = surfgrav_in(&dir, &["sweep", "grid.toml", "--jobs", "1"]);
    ok(&third);
    assert!(
        stdout(&third).contains("1 run now, 3 already done"),
        "{}",
        stdout(&third)
    );
    assert_eq!(
        summary(&root.join("tasks/00002/summary.json")),
        summary(&dir.join("single-2/summary.json"))
    );
    assert!(!root.join("tasks/.00002.partial-4999999").exists());
    assert_eq!((0..4).filter(|k| stamp(*k) == before[*k]).count(), 3);
    // The same folder refuses another sweep.
    fs::write(dir.join("other.toml"), GRID.replace("0.8", "0.9")).unwrap();
    let other = surfgrav_in(&dir, &["sweep", "other.toml", "--out", "grid"]);
    assert_eq!(other.status.code(), Some(2), "{}", stderr(&other));
    assert!(stderr(&other).contains("belongs to another sweep"));
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn shards_merge_into_the_unsharded_results() {
    let dir = scratch("shards");
    let sweep = GRID.replace("values = [0.8, 1.25]", "values = [0.8, 1.0, 1.25]");
    fs::write(dir.join("grid.toml"), &sweep).unwrap();
    ok(&surfgrav_in(
        &dir,
        &["sweep", "grid.toml", "--out", "whole", "--quiet"],
    ));
    // Both shards into one folder, as a job array on a shared file system does.
    for k in ["0/2", "1/2"] {
        let out = surfgrav_in(
            &dir,
            &["sweep", "grid.toml", "--out", "shared", "--shard", k],
        );
        ok(&out);
        assert!(
            stdout(&out).contains("3 of 6 tasks, shard"),
            "{}",
            stdout(&out)
        );
    }
    let (_, first) = csv(&dir.join("shared/results-shard-0-of-2.csv"));
    assert_eq!(
        first.iter().map(|r| r[0].as_str()).collect::<Vec<_>>(),
        ["0", "2", "4"]
    );
    assert!(!dir.join("shared/results.csv").exists());
    let merged = surfgrav_in(&dir, &["sweep", "merge", "shared"]);
    ok(&merged);
    assert!(
        stdout(&merged).contains("6 tasks, 6 done"),
        "{}",
        stdout(&merged)
    );
    assert_eq!(
        without_wall(&dir.join("shared/results.csv")),
        without_wall(&dir.join("whole/results.csv"))
    );
    // Shards in separate folders, merged into a third.
    for (k, folder) in [("0/2", "s0"), ("1/2", "s1")] {
        ok(&surfgrav_in(
            &dir,
            &[
                "sweep",
                "grid.toml",
                "--out",
                folder,
                "--shard",
                k,
                "--quiet",
            ],
        ));
    }
    ok(&surfgrav_in(
        &dir,
        &["sweep", "merge", "s1", "s0", "--out", "m"],
    ));
    assert_eq!(
        without_wall(&dir.join("m/results.csv")),
        without_wall(&dir.join("whole/results.csv"))
    );
    // A shard of another sweep is refused.
    fs::write(dir.join("other.toml"), sweep.replace("0.8", "0.9")).unwrap();
    ok(&surfgrav_in(
        &dir,
        &[
            "sweep",
            "other.toml",
            "--out",
            "o1",
            "--shard",
            "1/2",
            "--quiet",
        ],
    ));
    let bad = surfgrav_in(&dir, &["sweep", "merge", "s0", "o1", "--out", "m2"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(
        stderr(&bad).contains("from another sweep"),
        "{}",
        stderr(&bad)
    );
    assert_eq!(stderr(&bad).lines().count(), 1);
    assert!(!dir.join("m2").exists());
    fs::remove_dir_all(&dir).unwrap();
}

const MONTE_CARLO: &str = r#"
base = "paper-2s"
draws = 4
seed = 11
remove = []

[set]
t_end = 5.0

[[vary]]
field = "body_b.density"
loguniform = [0.5, 2.0]

[[vary]]
field = "body_a.polar_radius"
distribution = "uniform(0.2, 0.3)"

[[vary]]
field = "body_b.angular_velocity[2]"
normal = [0.0, 0.05]
"#;

#[test]
fn monte_carlo_draws_follow_the_seed_and_derived_masses_follow() {
    let dir = scratch("mc");
    fs::write(dir.join("mc.toml"), MONTE_CARLO).unwrap();
    fs::write(
        dir.join("mc7.toml"),
        MONTE_CARLO.replace("seed = 11", "seed = 7"),
    )
    .unwrap();
    ok(&surfgrav_in(
        &dir,
        &["sweep", "mc.toml", "--out", "a", "--quiet"],
    ));
    ok(&surfgrav_in(
        &dir,
        &["sweep", "mc.toml", "--out", "b", "--quiet", "--jobs", "1"],
    ));
    ok(&surfgrav_in(
        &dir,
        &["sweep", "mc7.toml", "--out", "c", "--quiet"],
    ));
    let (header, a) = csv(&dir.join("a/results.csv"));
    assert_eq!(a.len(), 4);
    assert_eq!(
        without_wall(&dir.join("a/results.csv")),
        without_wall(&dir.join("b/results.csv"))
    );
    let (_, c) = csv(&dir.join("c/results.csv"));
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    for k in 0..4 {
        let value = |rows: &[Vec<String>], f: &str| rows[k][col(f)].parse::<f64>().unwrap();
        let density = value(&a, "body_b.density");
        assert!((0.5..=2.0).contains(&density));
        assert!((0.2..0.3).contains(&value(&a, "body_a.polar_radius")));
        assert_ne!(density, value(&c, "body_b.density"));
        // The base's mass is dropped for the density; the mass follows from density × volume.
        let volume = 4.0 / 3.0 * std::f64::consts::PI * 0.25;
        let mass = value(&a, "mass_b");
        assert!((mass / (density * volume) - 1.0).abs() < 1e-14, "{mass}");
        // B spins about z with the drawn rate (a translation-only scene keeps it).
        assert!(
            (value(&a, "final_spin_b") - value(&a, "body_b.angular_velocity[2]").abs()).abs()
                < 1e-12
        );
        let scene = fs::read_to_string(dir.join(format!("a/tasks/{k:05}/scene.toml"))).unwrap();
        let b = &scene[scene.find("[body_b]").unwrap()..];
        let b = &b[..b.find("\n[").unwrap_or(b.len())];
        assert!(b.contains("density =") && !b.contains("mass ="), "{scene}");
    }
    // Draws differ from one another.
    assert_ne!(a[0][col("body_b.density")], a[1][col("body_b.density")]);
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_sweeps_are_one_line_exit_2_and_write_nothing() {
    let dir = scratch("bad");
    let base = "base = \"paper-2s\"\n[set]\nt_end = 5.0\n";
    let cases: &[(&str, &str)] = &[
        (
            "[[vary]]\nfield = \"body_b.colour\"\nvalues = [1.0]\n",
            "body_b.colour: unknown field `colour`",
        ),
        (
            "[[vary]]\nfield = \"body_b.mass\"\nvalues = []\n",
            "values is empty",
        ),
        (
            "[[vary]]\nfield = \"body_b.mass\"\nlinspace = [1.0, 2.0, 0]\n",
            "empty range",
        ),
        (
            "draws = 3\n[[vary]]\nfield = \"body_b.mass\"\nnormal = [1.0, 0.0]\n",
            "needs sd > 0",
        ),
        (
            "draws = 3\n[[vary]]\nfield = \"body_b.mass\"\nuniform = [2.0, 1.0]\n",
            "needs lo < hi",
        ),
        (
            "draws = 3\n[[vary]]\nfield = \"body_b.mass\"\ndistribution = \"loguniform(0, 1)\"\n",
            "needs 0 < lo < hi",
        ),
        (
            "[[vary]]\nfield = \"body_b.mass\"\nvalues = [1.0, -2.0]\n",
            "body_b.mass: must be a positive finite number, got -2 (task 00001: body_b.mass = -2)",
        ),
        (
            "[[vary]]\nfield = \"body_b.position\"\nlinspace = [1.0, 2.0, 3]\n",
            "is a vector of 3 numbers",
        ),
    ];
    for (k, (body, words)) in cases.iter().enumerate() {
        // The [[vary]] tables after `[set]` would land in it: put top-level keys first.
        let (top, rest) = match body.split_once("[[vary]]") {
            Some((top, rest)) => (top, format!("[[vary]]{rest}")),
            None => (*body, String::new()),
        };
        let text = format!("{top}{base}{rest}");
        let file = format!("bad{k}.toml");
        fs::write(dir.join(&file), &text).unwrap();
        let out = surfgrav_in(&dir, &["sweep", &file, "--out", "out"]);
        assert_eq!(out.status.code(), Some(2), "{text}\n{}", stderr(&out));
        let err = stderr(&out);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with(&format!("error: {file}:")), "{err}");
        assert!(err.contains(words), "`{err}` lacks `{words}`");
        assert!(stdout(&out).is_empty());
        assert!(!dir.join("out").exists(), "{text}");
    }
    // A shard K ≥ N.
    fs::write(
        dir.join("good.toml"),
        format!("{base}[[vary]]\nfield = \"body_b.mass\"\nvalues = [1.0]\n"),
    )
    .unwrap();
    for shard in ["2/2", "1/0", "x"] {
        let out = surfgrav_in(
            &dir,
            &["sweep", "good.toml", "--shard", shard, "--out", "out"],
        );
        assert_eq!(out.status.code(), Some(2));
        assert_eq!(stderr(&out).lines().count(), 1);
        assert!(stderr(&out).contains("--shard"), "{}", stderr(&out));
        assert!(!dir.join("out").exists());
    }
    let names: Vec<_> = fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert_eq!(names.len(), cases.len() + 1, "{names:?}");
    fs::remove_dir_all(&dir).unwrap();
}

/// A file's text without the lines naming `wall_seconds` (they differ between runs).
fn text_without_wall(path: &Path) -> String {
    fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.contains("wall_seconds"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// A sweep of rotating scenes with trajectories (the bodies the same in every task, only B's
/// velocity varies, so one worker runs task after task of the same pair): each task's
/// summary.json and trajectory.csv equal a separate `surfgrav run` of its scene byte for byte
/// (but the wall time).
#[test]
fn rotating_tasks_equal_single_runs_byte_for_byte() {
    let dir = scratch("rotating");
    fs::write(
        dir.join("reuse.toml"),
        r#"
base = "paper-2s"
name = "reuse"
save_trajectory = true

[set]
t_end = 3.0
body_a.angular_velocity = [0.1, 0.2, 0.3]

[[vary]]
field = "body_b.velocity[1]"
values = [-0.2, -0.19, -0.21]
"#,
    )
    .unwrap();
    ok(&surfgrav_in(
        &dir,
        &["sweep", "reuse.toml", "--jobs", "1", "--quiet"],
    ));
    for k in 0..3 {
        let task = dir.join(format!("reuse/tasks/{k:05}"));
        let single = dir.join(format!("single-{k}"));
        ok(&surfgrav_in(
            &dir,
            &[
                "run",
                task.join("scene.toml").to_str().unwrap(),
                "--out",
                single.to_str().unwrap(),
                "--quiet",
            ],
        ));
        let summary = text_without_wall(&task.join("summary.json"));
        assert!(
            summary.contains("\"rotation\""),
            "task {k} must integrate rotation"
        );
        assert_eq!(
            summary,
            text_without_wall(&single.join("summary.json")),
            "task {k}"
        );
        assert_eq!(
            fs::read_to_string(task.join("trajectory.csv")).unwrap(),
            fs::read_to_string(single.join("trajectory.csv")).unwrap(),
            "task {k}"
        );
    }
    let _ = fs::remove_dir_all(&dir);
}
