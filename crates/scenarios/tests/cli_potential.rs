//! The `potential` command as a user meets it: JSON on success; one line on stderr, nothing on
//! stdout and exit code 2 on bad input; never a panic or a backtrace.

use std::process::{Command, Output};

fn surfgrav(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_surfgrav"))
        .args(args)
        .env("RUST_BACKTRACE", "1")
        .output()
        .expect("the binary runs")
}

fn json(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("stdout is one JSON object")
}

#[test]
fn sphere_outside_is_kepler() {
    let out = surfgrav(&[
        "potential",
        "--body",
        "sphere:radius=1,mass=2",
        "--at",
        "3,0,-4",
        "--g",
        "0.5",
    ]);
    let v = json(&out);
    let phi = v["potential"].as_f64().unwrap();
    assert!((phi - (-0.5 * 2.0 / 5.0)).abs() < 1e-15, "{phi}");
    let a: Vec<f64> = v["acceleration"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let expected = [-0.5 * 2.0 * 3.0 / 125.0, 0.0, 0.5 * 2.0 * 4.0 / 125.0];
    for (x, e) in a.iter().zip(expected) {
        assert!((x - e).abs() < 1e-16, "{a:?}");
    }
}

#[test]
fn every_kind_answers_with_finite_json() {
    for body in [
        "point:mass=1",
        "sphere:radius=1,density=0.2",
        "spheroid:equatorial=1,polar=0.25,mass=1",
        "spheroid:equatorial=0.25,polar=1,mass=1",
        "ellipsoid:a=3,b=2,c=1,mass=1",
        "disk:radius=1,mass=1",
    ] {
        let v = json(&surfgrav(&[
            "potential",
            "--body",
            body,
            "--at",
            "0.3,-0.2,0.1",
        ]));
        let phi = v["potential"].as_f64().unwrap();
        assert!(phi.is_finite() && phi < 0.0, "{body}: {phi}");
    }
}

#[test]
fn bad_input_is_one_line_exit_2() {
    let cases: &[(&[&str], &str)] = &[
        (
            &[
                "potential",
                "--body",
                "sphere:radius=-1,mass=1",
                "--at",
                "2,0,0",
            ],
            "radius",
        ),
        (
            &[
                "potential",
                "--body",
                "sphere:radius=0,mass=1",
                "--at",
                "2,0,0",
            ],
            "radius",
        ),
        (
            &[
                "potential",
                "--body",
                "sphere:radius=nan,mass=1",
                "--at",
                "2,0,0",
            ],
            "radius",
        ),
        (
            &[
                "potential",
                "--body",
                "spheroid:equatorial=1,polar=inf,mass=1",
                "--at",
                "2,0,0",
            ],
            "polar",
        ),
        (
            &[
                "potential",
                "--body",
                "spheroid:equatorial=1,mass=1",
                "--at",
                "2,0,0",
            ],
            "polar",
        ),
        (
            &["potential", "--body", "cube:side=1,mass=1", "--at", "2,0,0"],
            "cube",
        ),
        (
            &[
                "potential",
                "--body",
                "disk:radius=1,mass=1,thickness=1",
                "--at",
                "2,0,0",
            ],
            "thickness",
        ),
        (
            &[
                "potential",
                "--body",
                "sphere:radius=1,mass=1",
                "--at",
                "2,0",
            ],
            "--at",
        ),
        (
            &[
                "potential",
                "--body",
                "sphere:radius=1,mass=1",
                "--at",
                "2,0,nan",
            ],
            "--at",
        ),
        (
            &[
                "potential",
                "--body",
                "sphere:radius=1,mass=1",
                "--at",
                "2,0,0",
                "--g",
                "-1",
            ],
            "--g",
        ),
        (
            &["potential", "--body", "point:mass=1", "--at", "0,0,0"],
            "point mass",
        ),
        (&["potential", "--at", "2,0,0"], "--body"),
        (&["potentail"], "potentail"),
    ];
    for (args, needle) in cases {
        let out = surfgrav(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(out.stdout.is_empty(), "{args:?} printed to stdout");
        assert_eq!(
            stderr.trim_end().lines().count(),
            1,
            "{args:?}: not one line: {stderr}"
        );
        assert!(
            stderr.contains(needle),
            "{args:?}: `{stderr}` does not name `{needle}`"
        );
        assert!(
            !stderr.contains("panicked") && !stderr.contains("backtrace"),
            "{stderr}"
        );
    }
}

/// A point on a disk's rim is refused plainly (the in-plane attraction is infinite there),
/// never answered with a finite stand-in (it once printed −22.997); just inside the rim the
/// answer follows the logarithmic asymptote a_ρ = −2Gσ(ln(8R/d) − 2), σ = M/(πR²).
#[test]
fn the_disk_rim_is_refused_and_near_rim_values_follow_the_asymptote() {
    for at in ["1,0,0", "0,-1,0", "-1,0,0"] {
        let out = surfgrav(&["potential", "--body", "disk:radius=1,mass=1", "--at", at]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{at}: {err}");
        assert!(out.stdout.is_empty());
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains("rim") && err.contains("infinite"), "{err}");
        // The finite potential on the rim, −4GσR = −4/π, is said too.
        assert!(err.contains("-1.273239"), "{err}");
    }
    for (d, quoted) in [(1e-6f64, -8.85), (1e-10, -14.71)] {
        let at = format!("{},0,0", 1.0 - d);
        let v = json(&surfgrav(&[
            "potential",
            "--body",
            "disk:radius=1,mass=1",
            "--at",
            &at,
        ]));
        let ax = v["acceleration"][0].as_f64().unwrap();
        let d_exact = 1.0 - (1.0 - d);
        let asymptote = -2.0 / std::f64::consts::PI * ((8.0 / d_exact).ln() - 2.0);
        assert!(
            ((ax - asymptote) / asymptote).abs() < 10.0 * d,
            "{ax} vs {asymptote}"
        );
        assert!((ax - quoted).abs() < 5e-3, "{ax} vs {quoted}");
    }
}
