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
            circle((0.0, 0.0), radius_a, "A"),
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
            "{}: orbits, t = {}…{} (bodies to scale, dashed)",
            run.scene.name,
            run.scene.t_start,
            run.t_reached()
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
