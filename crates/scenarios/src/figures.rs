//! The founding paper's figures for one run, as [`Figure`]s for [`crate::plot::write_figure`].
//!
//! - [`orbits`] (Fig. 2): left, both centroids about the centre of mass
//!   $\mathbf R_{cm} = (m_A\mathbf R_A + m_B\mathbf R_B)/(m_A + m_B)$ (subtracted at every
//!   sample); right, B relative to A, $\mathbf r = \mathbf R_B - \mathbf R_A$. Bodies are drawn
//!   to scale as dashed circles of their equatorial radius (the outline in the x–y plane; for
//!   an ellipsoid the larger of its x and y semi-axes): at the start, and B also at closest
//!   approach. Point masses have no circle.
//! - [`conservation`] (Fig. 3): separation $r_{AB}$, $\Delta E_k = E_k - E_{k-1}$ and
//!   $\Delta J_k = |\mathbf J_k| - |\mathbf J_{k-1}|$ against time (per step).
//! - [`histograms`] (Fig. 4): the distributions of $\Delta E$ and $\Delta J$.
//!
//! The x–y projection is drawn: the paper's scenes move in the plane z = 0.

use std::path::{Path, PathBuf};

use surfgrav_potentials::Real;

use crate::plot::{
    write_figure, Circle, Figure, HistogramPanel, LinePanel, Panel, PlotError, Series, Style,
};
use crate::scene::FigureKind;
use crate::simulate::RunRecord;
use crate::spec::{BodyKind, BodySpec};

/// Bins of the histograms.
pub const HISTOGRAM_BINS: usize = 60;

/// The outline radius drawn for a body (0 for a point mass).
pub fn outline_radius(spec: &BodySpec) -> Real {
    match spec.kind {
        BodyKind::Point => 0.0,
        BodyKind::Sphere | BodyKind::Disk | BodyKind::Spheroid => spec.dimensions[0],
        BodyKind::Ellipsoid => spec.dimensions[0].max(spec.dimensions[1]),
    }
}

fn circle(centre: (Real, Real), radius: Real, label: &str) -> Option<Circle> {
    (radius > 0.0).then(|| Circle {
        centre,
        radius,
        label: Some(label.to_string()),
    })
}

/// Fig. 2: both orbits about the centre of mass, and B relative to A.
pub fn orbits(run: &RunRecord) -> Figure {
    let (ma, mb) = masses(run);
    let total = ma + mb;
    let mut a = Vec::with_capacity(run.samples.len());
    let mut b = Vec::with_capacity(run.samples.len());
    let mut rel = Vec::with_capacity(run.samples.len());
    for s in &run.samples {
        let (ra, rb) = (s.state.body_a.position, s.state.body_b.position);
        let cm = (ra * ma + rb * mb) / total;
        a.push((ra.x - cm.x, ra.y - cm.y));
        b.push((rb.x - cm.x, rb.y - cm.y));
        rel.push((rb.x - ra.x, rb.y - ra.y));
    }
    let (radius_a, radius_b) = (
        outline_radius(&run.scene.spec_a),
        outline_radius(&run.scene.spec_b),
    );
    let closest = run
        .samples
        .iter()
        .min_by(|p, q| p.state.separation().total_cmp(&q.state.separation()))
        .map(|s| s.state.relative_position());
    let left = LinePanel {
        title: "Centre-of-mass frame".into(),
        x_label: "x (length units)".into(),
        y_label: "y (length units)".into(),
        series: vec![
            Series {
                label: "body A".into(),
                points: a.clone(),
                style: Style::Line,
            },
            Series {
                label: "body B".into(),
                points: b.clone(),
                style: Style::Line,
            },
        ],
        circles: [
            a.first()
                .and_then(|&c| circle(c, radius_a, "A at t = start")),
            b.first()
                .and_then(|&c| circle(c, radius_b, "B at t = start")),
        ]
        .into_iter()
        .flatten()
        .collect(),
        equal_aspect: true,
    };
    let right = LinePanel {
        title: "B relative to A".into(),
        x_label: "x_B − x_A (length units)".into(),
        y_label: "y_B − y_A (length units)".into(),
        series: vec![Series {
            label: "B − A".into(),
            points: rel.clone(),
            style: Style::Line,
        }],
        circles: [
            circle((0.0, 0.0), radius_a, "A (at the origin)"),
            rel.first()
                .and_then(|&c| circle(c, radius_b, "B at t = start")),
            closest.and_then(|r| circle((r.x, r.y), radius_b, "B at closest approach")),
        ]
        .into_iter()
        .flatten()
        .collect(),
        equal_aspect: true,
    };
    Figure {
        title: format!(
            "{}: orbits, t = {}…{}{}",
            run.scene.name,
            run.scene.t_start,
            run.t_reached(),
            if radius_a > 0.0 || radius_b > 0.0 {
                " (bodies to scale, dashed)"
            } else {
                " (point masses)"
            }
        ),
        panels: vec![Panel::Lines(left), Panel::Lines(right)],
        columns: 2,
    }
}

fn masses(run: &RunRecord) -> (Real, Real) {
    let m = |b: &crate::spec::BuiltBody| b.into_potential().mass();
    (m(&run.scene.body_a), m(&run.scene.body_b))
}

/// Per-step changes $(t_k, x_k - x_{k-1})$.
pub fn step_changes(run: &RunRecord, values: &[Real]) -> Vec<(Real, Real)> {
    run.samples
        .iter()
        .skip(1)
        .zip(values.windows(2))
        .map(|(s, w)| (s.time, w[1] - w[0]))
        .collect()
}

/// Fig. 3: separation, ΔE and ΔJ against time.
pub fn conservation(run: &RunRecord) -> Figure {
    let separation: Vec<(Real, Real)> = run
        .samples
        .iter()
        .map(|s| (s.time, s.state.separation()))
        .collect();
    let line = |title: &str, y: &str, label: &str, points: Vec<(Real, Real)>| {
        Panel::Lines(LinePanel {
            title: title.into(),
            x_label: "time t (time units)".into(),
            y_label: y.into(),
            series: vec![Series {
                label: label.into(),
                points,
                style: Style::Line,
            }],
            circles: vec![],
            equal_aspect: false,
        })
    };
    Figure {
        title: format!(
            "{}: r_AB, ΔE, ΔJ ({})",
            run.scene.name,
            integrator_label(run)
        ),
        panels: vec![
            line(
                "Centroid separation",
                "r_AB (length units)",
                "r_AB",
                separation,
            ),
            line(
                "Energy change per step",
                "ΔE (energy units)",
                "ΔE",
                step_changes(run, &run.energies),
            ),
            line(
                "Angular-momentum change per step",
                "ΔJ (angular-momentum units)",
                "ΔJ",
                step_changes(run, &run.angular_momenta),
            ),
        ],
        columns: 1,
    }
}

/// Fig. 4: histograms of ΔE and ΔJ.
pub fn histograms(run: &RunRecord) -> Figure {
    let values =
        |v: &[Real]| -> Vec<Real> { step_changes(run, v).into_iter().map(|p| p.1).collect() };
    Figure {
        title: format!(
            "{}: distribution of the per-step changes ({} steps)",
            run.scene.name, run.summary.steps
        ),
        panels: vec![
            Panel::Histogram(HistogramPanel {
                title: "Energy change per step".into(),
                x_label: "ΔE (energy units)".into(),
                y_label: "count".into(),
                values: values(&run.energies),
                bins: HISTOGRAM_BINS,
            }),
            Panel::Histogram(HistogramPanel {
                title: "Angular-momentum change per step".into(),
                x_label: "ΔJ (angular-momentum units)".into(),
                y_label: "count".into(),
                values: values(&run.angular_momenta),
                bins: HISTOGRAM_BINS,
            }),
        ],
        columns: 2,
    }
}

/// `rk4, dt = 0.1` or `dopri5, tol = 1e-10`.
pub fn integrator_label(run: &RunRecord) -> String {
    match run.scene.integrator {
        crate::scene::IntegratorChoice::Fixed { method, step } => {
            format!("{}, dt = {step}", method.name())
        }
        crate::scene::IntegratorChoice::Adaptive { method, tolerance } => {
            format!("{}, tolerance = {tolerance:e}", method.name())
        }
    }
}

/// The file stem of a figure kind.
pub fn stem(kind: FigureKind) -> &'static str {
    match kind {
        FigureKind::Orbits => "fig2_orbits",
        FigureKind::Conservation => "fig3_conservation",
        FigureKind::Histograms => "fig4_histograms",
    }
}

/// Writes the scene's figures into `folder`; returns the files written.
///
/// # Errors
/// The plot module's errors.
pub fn write_all(run: &RunRecord, folder: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let mut files = Vec::new();
    for &kind in &run.scene.figures {
        let figure = match kind {
            FigureKind::Orbits => orbits(run),
            FigureKind::Conservation => conservation(run),
            FigureKind::Histograms => histograms(run),
        };
        files.extend(write_figure(&figure, &folder.join(stem(kind)))?);
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::presets;
    use crate::simulate::run_scene;

    fn paper_2s(t_end: f64) -> RunRecord {
        let mut scene = presets::find("paper-2s").unwrap().scene().unwrap();
        scene.override_with(Some(t_end), None, None, None).unwrap();
        run_scene(&scene).unwrap()
    }

    #[test]
    fn orbit_figure_draws_bodies_to_scale() {
        let run = paper_2s(40.0);
        let figure = orbits(&run);
        assert_eq!(figure.columns, 2);
        let [Panel::Lines(left), Panel::Lines(right)] = &figure.panels[..] else {
            panic!("two line panels");
        };
        assert!(left.equal_aspect && right.equal_aspect);
        assert_eq!(left.series.len(), 2);
        assert_eq!(left.series[0].points.len(), run.samples.len());
        // Equal masses: the centre of mass is the midpoint, A starts at (−3.5, 0).
        assert_eq!(left.series[0].points[0], (-3.5, 0.0));
        let radii: Vec<(f64, (f64, f64))> =
            left.circles.iter().map(|c| (c.radius, c.centre)).collect();
        assert_eq!(radii, [(1.0, (-3.5, 0.0)), (1.0, (3.5, 0.0))]);
        // Right panel: A at the origin, B at the start (7, 0) and at closest approach, whose
        // distance is the smallest sampled separation (the interpolated minimum is 2.5472;
        // samples every 0.1 miss it by less than 1e-3).
        assert_eq!(right.circles.len(), 3);
        assert_eq!(right.circles[1].centre, (7.0, 0.0));
        let (x, y) = right.circles[2].centre;
        let d = x.hypot(y);
        assert!((d - 2.5472).abs() < 1e-3, "{d}");
        assert!(figure.title.contains("to scale"));
    }

    #[test]
    fn conservation_and_histograms_use_every_step() {
        let run = paper_2s(20.0);
        let steps = run.summary.steps;
        let c = conservation(&run);
        assert_eq!(c.panels.len(), 3);
        let Panel::Lines(de) = &c.panels[1] else {
            panic!("line panel")
        };
        assert_eq!(de.series[0].points.len(), steps);
        let expected = run.energies[1] - run.energies[0];
        assert_eq!(de.series[0].points[0], (run.samples[1].time, expected));
        let h = histograms(&run);
        let Panel::Histogram(hj) = &h.panels[1] else {
            panic!("histogram")
        };
        assert_eq!(hj.values.len(), steps);
        assert!(hj.x_label.contains("ΔJ"));
    }
}
