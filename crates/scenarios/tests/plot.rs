//! Tests of the figure writer: files, sizes, text, data checks, degenerate ranges, and the three
//! kinds of figure of the paper (orbits to scale, stacked time series, histograms).
//!
//! The sample figures are written to `$SURFGRAV_PLOT_SAMPLES` when that is set (to look at
//! them), otherwise to a temporary folder that is removed.

use std::path::{Path, PathBuf};

use surfgrav_scenarios::plot::{
    write_figure, Circle, Figure, HistogramPanel, LinePanel, Panel, PlotError, Series, Style,
    PANEL_HEIGHT, PANEL_WIDTH,
};

/// A fresh folder for one test.
fn folder(name: &str) -> PathBuf {
    let dir = match std::env::var_os("SURFGRAV_PLOT_SAMPLES") {
        Some(d) => PathBuf::from(d),
        None => std::env::temp_dir().join(format!("surfgrav-plot-{}-{name}", std::process::id())),
    };
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn cleanup(dir: &Path) {
    if std::env::var_os("SURFGRAV_PLOT_SAMPLES").is_none() {
        let _ = std::fs::remove_dir_all(dir);
    }
}

/// Width and height from a PNG's signature and IHDR chunk (PNG spec §5.2, §11.2.2).
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert!(bytes.len() > 33, "PNG too short: {} bytes", bytes.len());
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
    assert_eq!(&bytes[8..12], &[0, 0, 0, 13], "IHDR length");
    assert_eq!(&bytes[12..16], b"IHDR");
    let w = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
    let h = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    // The last chunk is IEND with its fixed CRC.
    assert_eq!(&bytes[bytes.len() - 8..bytes.len() - 4], b"IEND");
    (w, h)
}

/// The contents of every `<text …>…</text>` element of an SVG.
fn svg_texts(svg: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(start) = rest.find("<text") {
        let after = &rest[start..];
        let open_end = after.find('>').unwrap();
        let close = after.find("</text>").unwrap();
        out.push(after[open_end + 1..close].trim().to_string());
        rest = &after[close + 7..];
    }
    out
}

fn series(label: &str, points: Vec<(f64, f64)>, style: Style) -> Series {
    Series {
        label: label.into(),
        points,
        style,
    }
}

fn lines(title: &str, x: &str, y: &str, series: Vec<Series>) -> LinePanel {
    LinePanel {
        title: title.into(),
        x_label: x.into(),
        y_label: y.into(),
        series,
        circles: vec![],
        equal_aspect: false,
    }
}

fn sine(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let t = i as f64 * 0.1;
            (t, t.sin())
        })
        .collect()
}

#[test]
fn writes_png_and_svg_of_the_expected_size() {
    let dir = folder("size");
    let fig = Figure {
        title: "Two panels".into(),
        panels: vec![
            Panel::Lines(lines(
                "sine",
                "t (time units)",
                "y",
                vec![series("sin t", sine(100), Style::Line)],
            )),
            Panel::Lines(lines(
                "points",
                "t (time units)",
                "y",
                vec![series("samples", sine(20), Style::Points)],
            )),
            Panel::Histogram(HistogramPanel {
                title: "values".into(),
                x_label: "y".into(),
                y_label: "count".into(),
                values: sine(200).into_iter().map(|p| p.1).collect(),
                bins: 20,
            }),
        ],
        columns: 2,
    };
    let paths = write_figure(&fig, &dir.join("size")).unwrap();
    assert_eq!(paths.len(), 2);
    assert_eq!(paths[0], dir.join("size.png"));
    assert_eq!(paths[1], dir.join("size.svg"));
    let png = std::fs::read(&paths[0]).unwrap();
    // 2 columns, 2 rows, plus the 50-pixel title band.
    assert_eq!(png_size(&png), (2 * PANEL_WIDTH, 2 * PANEL_HEIGHT + 50));
    let svg = std::fs::read_to_string(&paths[1]).unwrap();
    assert!(svg.starts_with("<svg"), "{}", &svg[..40.min(svg.len())]);
    assert!(svg.contains(&format!("width=\"{}\"", 2 * PANEL_WIDTH)));
    cleanup(&dir);
}

#[test]
fn svg_holds_titles_axis_labels_and_legend() {
    let dir = folder("labels");
    let fig = Figure {
        title: "Figure title here".into(),
        panels: vec![Panel::Lines(lines(
            "Panel title here",
            "time t (time units)",
            "distance r (length units)",
            vec![
                series("first curve", sine(50), Style::Line),
                series("second curve", sine(30), Style::Dashed),
                series("", sine(10), Style::Points),
            ],
        ))],
        columns: 1,
    };
    let paths = write_figure(&fig, &dir.join("labels")).unwrap();
    let texts = svg_texts(&std::fs::read_to_string(&paths[1]).unwrap());
    for want in [
        "Figure title here",
        "Panel title here",
        "time t (time units)",
        "distance r (length units)",
        "first curve",
        "second curve",
    ] {
        assert!(
            texts.iter().any(|t| t == want),
            "{want} missing in {texts:?}"
        );
    }
    // The unlabelled series adds no legend entry: no empty text element.
    assert!(texts.iter().all(|t| !t.is_empty()), "{texts:?}");
    cleanup(&dir);
}

#[test]
fn non_finite_points_are_an_error_naming_the_series() {
    let dir = folder("nan");
    let mut bad = sine(10);
    bad[7].1 = f64::NAN;
    let fig = Figure {
        title: "bad".into(),
        panels: vec![Panel::Lines(lines(
            "energy",
            "t",
            "E",
            vec![
                series("good", sine(10), Style::Line),
                series("broken one", bad, Style::Line),
            ],
        ))],
        columns: 1,
    };
    let e = write_figure(&fig, &dir.join("nan")).unwrap_err();
    match &e {
        PlotError::NonFinite {
            panel,
            series,
            index,
            ..
        } => {
            assert_eq!(panel, "energy");
            assert_eq!(series, "broken one");
            assert_eq!(*index, 7);
        }
        other => panic!("wrong error {other:?}"),
    }
    assert!(e.to_string().contains("broken one"), "{e}");
    // Nothing was written.
    assert!(!dir.join("nan.png").exists());
    assert!(!dir.join("nan.svg").exists());

    let hist = Figure {
        title: "bad".into(),
        panels: vec![Panel::Histogram(HistogramPanel {
            title: "dE".into(),
            x_label: "dE".into(),
            y_label: "count".into(),
            values: vec![1.0, f64::INFINITY],
            bins: 3,
        })],
        columns: 1,
    };
    assert!(matches!(
        write_figure(&hist, &dir.join("nan")),
        Err(PlotError::NonFinite { index: 1, .. })
    ));
    cleanup(&dir);
}

#[test]
fn bad_figures_are_typed_errors() {
    let dir = folder("bad");
    let stem = dir.join("bad");
    let empty = Figure {
        title: "empty".into(),
        panels: vec![],
        columns: 1,
    };
    assert!(matches!(
        write_figure(&empty, &stem),
        Err(PlotError::EmptyFigure { .. })
    ));
    let no_points = Figure {
        title: "x".into(),
        panels: vec![Panel::Lines(lines(
            "nothing",
            "t",
            "y",
            vec![series("empty", vec![], Style::Line)],
        ))],
        columns: 1,
    };
    assert!(matches!(
        write_figure(&no_points, &stem),
        Err(PlotError::NoData { .. })
    ));
    let zero_columns = Figure {
        columns: 0,
        ..no_points.clone()
    };
    assert!(matches!(
        write_figure(&zero_columns, &stem),
        Err(PlotError::Layout { .. })
    ));
    let log = Figure {
        title: "log".into(),
        panels: vec![Panel::Log {
            lines: lines(
                "errors",
                "time (s)",
                "error",
                vec![series("rule", vec![(1.0, 1e-3), (2.0, 0.0)], Style::Line)],
            ),
            log_x: true,
            log_y: true,
        }],
        columns: 1,
    };
    assert!(matches!(
        write_figure(&log, &stem),
        Err(PlotError::NonPositiveOnLogAxis {
            index: 1,
            axis: "y",
            ..
        })
    ));
    let no_bins = Figure {
        title: "h".into(),
        panels: vec![Panel::Histogram(HistogramPanel {
            title: "h".into(),
            x_label: "v".into(),
            y_label: "count".into(),
            values: vec![1.0],
            bins: 0,
        })],
        columns: 1,
    };
    assert!(matches!(
        write_figure(&no_bins, &stem),
        Err(PlotError::NoBins { .. })
    ));
    // A folder that does not exist: an I/O error naming the file.
    let missing = dir.join("no-such-folder").join("f");
    let e = write_figure(&no_points_ok(), &missing).unwrap_err();
    assert!(matches!(e, PlotError::Io { .. }), "{e:?}");
    assert!(e.to_string().contains("no-such-folder"), "{e}");
    cleanup(&dir);
}

fn no_points_ok() -> Figure {
    Figure {
        title: "ok".into(),
        panels: vec![Panel::Lines(lines(
            "ok",
            "t",
            "y",
            vec![series("s", sine(5), Style::Line)],
        ))],
        columns: 1,
    }
}

/// Tick labels of a figure with a single panel: every text that is not a title.
fn tick_labels(svg: &str, titles: &[&str]) -> Vec<String> {
    svg_texts(svg)
        .into_iter()
        .filter(|t| !titles.contains(&t.as_str()))
        .collect()
}

/// Tick labels must be finite numbers, distinct, short, and increasing along the axis.
fn assert_readable(labels: &[String]) {
    assert!(labels.len() >= 4, "too few tick labels: {labels:?}");
    for l in labels {
        let v: f64 = l
            .parse()
            .unwrap_or_else(|_| panic!("tick label {l:?} is not a number ({labels:?})"));
        assert!(v.is_finite(), "{l}");
        assert!(l.len() <= 10, "tick label {l:?} too long ({labels:?})");
    }
    let mut sorted = labels.to_vec();
    sorted.sort();
    sorted.dedup();
    assert_eq!(sorted.len(), labels.len(), "repeated labels {labels:?}");
}

#[test]
fn tiny_and_constant_ranges_give_readable_axes() {
    let dir = folder("tiny");
    let cases: Vec<(&str, Vec<(f64, f64)>)> = vec![
        // Angular-momentum differences at machine level.
        (
            "tiny",
            (0..100)
                .map(|i| (1000.0 + i as f64, 1e-17 * (1.0 + (i as f64 * 0.3).sin())))
                .collect(),
        ),
        // Constant small value.
        (
            "constant",
            (0..50).map(|i| (1000.0 + i as f64, 1e-17)).collect(),
        ),
        // Constant zero.
        ("zero", (0..50).map(|i| (1000.0 + i as f64, 0.0)).collect()),
        // A large value with a tiny relative variation: drawn against an offset.
        (
            "offset",
            (0..100)
                .map(|i| (1000.0 + i as f64, -0.25 + 1e-13 * (i as f64 * 0.2).cos()))
                .collect(),
        ),
        // A single point.
        ("single", vec![(3.0, 7.0)]),
    ];
    for (name, points) in cases {
        let fig = Figure {
            title: format!("case {name}"),
            panels: vec![Panel::Lines(lines(
                "panel",
                "t (time units)",
                "dJ (angular momentum units)",
                vec![series("values", points, Style::Line)],
            ))],
            columns: 1,
        };
        let paths = write_figure(&fig, &dir.join(name)).unwrap();
        let svg = std::fs::read_to_string(&paths[1]).unwrap();
        let texts = svg_texts(&svg);
        let y_title = texts
            .iter()
            .find(|t| t.starts_with("dJ (angular momentum units)"))
            .unwrap_or_else(|| panic!("{name}: no y title in {texts:?}"))
            .clone();
        if name == "offset" {
            assert!(y_title.contains("(-0.25)"), "{y_title}");
        } else {
            assert_eq!(y_title, "dJ (angular momentum units)");
        }
        let labels = tick_labels(
            &svg,
            &[
                &format!("case {name}"),
                "panel",
                "t (time units)",
                &y_title,
                "values",
            ],
        );
        assert_readable(&labels);
        for text in &texts {
            assert!(!text.contains("NaN") && !text.contains("inf"), "{text}");
        }
    }
    cleanup(&dir);
}

// ---------------------------------------------------------------------------------------------
// The paper's three kinds of figure, from synthetic data of the right shape and size.

/// A precessing ellipse for the relative orbit: r(ψ) = p / (1 + e cos(κ ψ)).
fn relative_orbit(n: usize) -> Vec<(f64, f64)> {
    let (p, e, kappa) = (4.0, 0.45, 0.95);
    (0..n)
        .map(|i| {
            let psi = i as f64 * 0.01;
            let r = p / (1.0 + e * (kappa * psi).cos());
            (r * psi.cos(), r * psi.sin())
        })
        .collect()
}

fn paper_fig2() -> Figure {
    let rel = relative_orbit(1600);
    let a: Vec<_> = rel.iter().map(|&(x, y)| (-0.5 * x, -0.5 * y)).collect();
    let b: Vec<_> = rel.iter().map(|&(x, y)| (0.5 * x, 0.5 * y)).collect();
    let cm = |title: &str| {
        Panel::Lines(LinePanel {
            title: title.into(),
            x_label: "x (length units)".into(),
            y_label: "y (length units)".into(),
            series: vec![
                series("A", a.clone(), Style::Line),
                series("B", b.clone(), Style::Line),
            ],
            circles: vec![
                Circle {
                    centre: a[0],
                    radius: 1.0,
                    label: Some("A at t = 0".into()),
                },
                Circle {
                    centre: b[0],
                    radius: 1.0,
                    label: Some("B at t = 0".into()),
                },
            ],
            equal_aspect: true,
        })
    };
    let relative = |title: &str| {
        Panel::Lines(LinePanel {
            title: title.into(),
            x_label: "x_B − x_A (length units)".into(),
            y_label: "y_B − y_A (length units)".into(),
            series: vec![series("B relative to A", rel.clone(), Style::Line)],
            circles: vec![
                Circle {
                    centre: (0.0, 0.0),
                    radius: 1.0,
                    label: Some("A".into()),
                },
                Circle {
                    centre: rel[0],
                    radius: 1.0,
                    label: Some("B at t = 0".into()),
                },
            ],
            equal_aspect: true,
        })
    };
    Figure {
        title: "Trajectories (paper Fig. 2)".into(),
        panels: vec![
            cm("2S: centre-of-mass frame"),
            relative("2S: B relative to A"),
            cm("2D: centre-of-mass frame"),
            relative("2D: B relative to A"),
        ],
        columns: 2,
    }
}

/// Deterministic pseudo-noise in [−1, 1].
fn noise(i: usize) -> f64 {
    let x = (i as u64)
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((x >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
}

fn paper_fig3() -> Figure {
    let n = 3000;
    let t: Vec<f64> = (0..n).map(|i| i as f64 * 0.1).collect();
    let r: Vec<f64> = t
        .iter()
        .map(|&t| 4.75 - 2.2 * (t * 0.09).cos().powi(3))
        .collect();
    let column = |model: &str, de: f64, dj: f64| {
        let r_series: Vec<_> = t.iter().zip(&r).map(|(&t, &r)| (t, r)).collect();
        let de_series: Vec<_> = (0..n)
            .map(|i| (t[i], de * noise(i) / (r[i] - 2.0).powi(3)))
            .collect();
        let dj_series: Vec<_> = (0..n)
            .map(|i| (t[i], dj * noise(i + n) / (r[i] - 2.0).powi(3)))
            .collect();
        vec![
            Panel::Lines(lines(
                &format!("{model}: centroid distance"),
                "t (time units)",
                "r_AB (length units)",
                vec![series("r_AB", r_series, Style::Line)],
            )),
            Panel::Lines(lines(
                &format!("{model}: energy change per step"),
                "t (time units)",
                "ΔE (energy units)",
                vec![series("ΔE", de_series, Style::Line)],
            )),
            Panel::Lines(lines(
                &format!("{model}: angular-momentum change per step"),
                "t (time units)",
                "ΔJ (angular momentum units)",
                vec![series("ΔJ", dj_series, Style::Line)],
            )),
        ]
    };
    let left = column("2S", 3e-8, 7e-8);
    let right = column("2D", 6e-6, 2e-16);
    let mut panels = Vec::new();
    for (l, r) in left.into_iter().zip(right) {
        panels.push(l);
        panels.push(r);
    }
    Figure {
        title: "Error analysis (paper Fig. 3)".into(),
        panels,
        columns: 2,
    }
}

fn paper_fig4() -> Figure {
    let values = |scale: f64, shift: usize| -> Vec<f64> {
        (0..3000)
            .map(|i| scale * (noise(i + shift) + noise(i + shift + 7) + noise(i + shift + 13)))
            .collect()
    };
    let hist = |title: &str, x: &str, v: Vec<f64>| {
        Panel::Histogram(HistogramPanel {
            title: title.into(),
            x_label: x.into(),
            y_label: "count".into(),
            values: v,
            bins: 40,
        })
    };
    Figure {
        title: "Distributions of ΔE and ΔJ (paper Fig. 4)".into(),
        panels: vec![
            hist("2S: ΔE", "ΔE (energy units)", values(3e-8, 0)),
            hist(
                "2S: ΔJ",
                "ΔJ (angular momentum units)",
                values(7e-8, 10_000),
            ),
            hist("2D: ΔE", "ΔE (energy units)", values(6e-6, 20_000)),
            hist(
                "2D: ΔJ",
                "ΔJ (angular momentum units)",
                values(2e-16, 30_000),
            ),
        ],
        columns: 2,
    }
}

fn work_precision() -> Figure {
    let curve = |label: &str, order: f64, c: f64| {
        let pts = (0..8)
            .map(|k| {
                let n = 4.0 * 2f64.powi(k);
                (1e-6 * n * n, c * n.powf(-order))
            })
            .collect();
        series(label, pts, Style::Line)
    };
    Figure {
        title: "Work-precision (sample)".into(),
        panels: vec![Panel::Log {
            lines: lines(
                "force at separation 2.55",
                "time per evaluation (s)",
                "relative error of the force",
                vec![
                    curve("Gauss–Legendre, smooth (θ, φ)", 6.0, 1.0),
                    curve("Gauss–Legendre, paper's (φ, z)", 2.0, 0.1),
                    curve("adaptive G7K15", 4.0, 10.0),
                ],
            ),
            log_x: true,
            log_y: true,
        }],
        columns: 1,
    }
}

#[test]
fn paper_figures_are_written() {
    let dir = folder("paper");
    for (name, fig, (columns, rows)) in [
        ("fig2_orbits", paper_fig2(), (2, 2)),
        ("fig3_errors", paper_fig3(), (2, 3)),
        ("fig4_histograms", paper_fig4(), (2, 2)),
        ("work_precision", work_precision(), (1, 1)),
    ] {
        let paths = write_figure(&fig, &dir.join(name)).unwrap();
        let png = std::fs::read(&paths[0]).unwrap();
        assert_eq!(
            png_size(&png),
            (columns * PANEL_WIDTH, rows * PANEL_HEIGHT + 50),
            "{name}"
        );
        let svg = std::fs::read_to_string(&paths[1]).unwrap();
        let texts = svg_texts(&svg);
        assert!(texts.contains(&fig.title), "{name}: {texts:?}");
        assert!(
            texts
                .iter()
                .all(|t| !t.contains("NaN") && !t.contains("inf")),
            "{name}: {texts:?}"
        );
    }
    cleanup(&dir);
}

#[test]
fn many_series_and_single_points_are_drawn_and_listed() {
    let dir = folder("many");
    // Twelve sweeps (more than the ten colours: the last two get another marker shape) and a
    // one-point line series, which must still be visible (drawn as a dot).
    let mut all: Vec<Series> = (0..12)
        .map(|k| {
            series(
                &format!("sweep {k}"),
                (1..6)
                    .map(|i| (i as f64 * 1e-5, 10f64.powi(-(i * (k + 1)) % 16 - 1)))
                    .collect(),
                Style::LinePoints,
            )
        })
        .collect();
    all.push(series("one point", vec![(2e-5, 1e-9)], Style::Line));
    let fig = Figure {
        title: "many".into(),
        panels: vec![Panel::Log {
            lines: lines("log-log", "time (s)", "error", all),
            log_x: true,
            log_y: true,
        }],
        columns: 1,
    };
    let paths = write_figure(&fig, &dir.join("many")).unwrap();
    let svg = std::fs::read_to_string(&paths[1]).unwrap();
    let texts = svg_texts(&svg);
    for k in 0..12 {
        let label = format!("sweep {k}");
        assert!(texts.contains(&label), "{label} missing");
    }
    assert!(texts.contains(&"one point".to_string()));
    // Markers: circles for the first ten series, squares after.
    assert!(svg.contains("<circle"), "no circle markers");
    // Series 10 and 11: five squares each plus their legend samples (the background adds one
    // more rectangle).
    let rects = svg.matches("<rect").count();
    assert!(
        rects >= 2 * 5 + 2,
        "only {rects} rectangles: no square markers"
    );
    cleanup(&dir);
}
