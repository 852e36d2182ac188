//! `surfgrav report`: REPORT.md with the precession table, Table 2, the Fig. 7 comparison and
//! the Maclaurin remark, every figure beside it, the folder appearing whole.

use std::fs;
use std::process::Command;

#[test]
fn report_writes_tables_and_figures() {
    let dir = std::env::temp_dir().join(format!("surfgrav-cli-report-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    let run = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_surfgrav"))
            .args(args)
            .current_dir(&dir)
            .output()
            .expect("the binary runs")
    };
    let out = run(&["report", "--out", "rep"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.stderr.is_empty(), "no progress bar on a pipe");
    let names: Vec<String> = fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["rep"], "no temporary folder left");
    let md = fs::read_to_string(dir.join("rep/REPORT.md")).unwrap();
    for needle in [
        "## Precession",
        "| paper-2s | 18.9638 | 18 | 18.964 | 24.028 | 23 | 24.03 |",
        "| paper-2d | 30.2225 | 30 | 30.2225 |",
        "## Conservation (the paper's Table 2)",
        "| paper-2s | ΔE | paper | -3.0e-11 | 3.0e-8 |",
        "| paper-2s | ΔE | surfgrav |",
        "c/a = 0.99 vs point masses",
        "c/a = 0.01 vs uniform disks",
        "c/a = 0.01 vs point masses",
        "c/a = 0.99 vs uniform disks",
        "Maclaurin disk",
        "![Fig. 7](fig7_limiting_cases.png)",
    ] {
        assert!(md.contains(needle), "REPORT.md lacks `{needle}`");
    }
    // Nothing a user reads points at the project's issue tracker.
    let stdout = String::from_utf8_lossy(&out.stdout);
    for text in [&md[..], &stdout[..]] {
        assert!(
            !text.to_lowercase().contains("issue"),
            "a user-visible text mentions an issue"
        );
    }
    // Every image the report links exists.
    for link in md.split("](").skip(1) {
        let target = &link[..link.find(')').unwrap()];
        assert!(dir.join("rep").join(target).is_file(), "{target}");
    }
    let files = fs::read_dir(dir.join("rep")).unwrap().count();
    assert_eq!(
        files,
        1 + 2 * (6 * 3 + 1),
        "REPORT.md and 19 figures as PNG and SVG"
    );

    // The same folder again is refused, untouched.
    let again = run(&["report", "--out", "rep"]);
    assert_eq!(again.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&again.stderr).contains("already exists"));
    assert_eq!(fs::read_to_string(dir.join("rep/REPORT.md")).unwrap(), md);
    fs::remove_dir_all(&dir).unwrap();
}
