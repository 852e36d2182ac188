//! The founding paper's figures for one run, as [`Figure`]s for [`crate::plot::write_figure`].
//!
//! - [`orbits`] (Fig. 2): the orbit seen face-on in its own plane (the plane normal to the
//!   relative angular momentum $\mathbf r \times \dot{\mathbf r}$ at the start; the x–y plane
//!   for the paper's scenes), left both centroids about the centre of mass
//!   $\mathbf R\_{cm} = (m_A\mathbf R_A + m_B\mathbf R_B)/(m_A + m_B)$, right B relative to A,
//!   $\mathbf r = \mathbf R_B - \mathbf R_A$; below, B relative to A seen edge-on along each
//!   in-plane axis (two side views). Bodies are drawn to scale as their true outlines, dashed:
//!   the orthographic projection of the ellipsoid $\mathbf x^\top M^{-1}\mathbf x \le 1$,
//!   $M = R\\,\mathrm{diag}(a^2, b^2, c^2)R^\top$ at the body's orientation $R$, onto a view
//!   plane with unit axes $\mathbf u, \mathbf v$ is the ellipse of the 2 × 2 matrix
//!   $S = [\mathbf u\ \mathbf v]^\top M [\mathbf u\ \mathbf v]$ (a disk is the case
//!   c = 0, a sphere a = b = c); drawn at the start, and B also at the closest step.
//!   Point masses have no outline.
//! - [`conservation`] (Fig. 3): separation $r\_{AB}$ against time; the per-step changes
//!   $\Delta E_k = E_k - E\_{k-1}$ and $\Delta J_k = |\mathbf J_k| - |\mathbf J\_{k-1}|$; and the
//!   cumulative $(E - E_0)/|E_0|$ and $(J - J_0)/|J_0|$, which stay readable over long runs
//!   where the per-step panels fill solid.
//! - [`histograms`] (Fig. 4): the distributions of $\Delta E$ and $\Delta J$ (every step).
//! - [`rotation`] (`fig5_rotation`, drawn by default when the run integrated rotation): spin
//!   rates $|\boldsymbol\omega|$, obliquities (spin axis to the mutual orbit's normal) and
//!   libration angles (an elongated body's long axis to the line of centres, in the orbit
//!   plane; [`surfgrav_dynamics::spin`]) of both bodies, and the cumulative relative errors
//!   $(E - E_0)/|E_0|$ and $|\mathbf J - \mathbf J_0|/|\mathbf J_0|$ of the energy and of the
//!   angular-momentum vector.
//!
//! Data are thinned to what a page shows: time series keep the smallest and largest value of
//! each of [`PAGE_COLUMNS`] time slices (so peaks survive), orbits the written rows (at most
//! [`crate::simulate::KEPT_ROWS`]). Statistics never use the thinned data. Axis labels carry
//! the scene's units: m, s, kg, J in SI (G = 6.6743e-11), "length units" etc. otherwise.

use std::path::{Path, PathBuf};

use surfgrav_dynamics::BodyState;
use surfgrav_potentials::{Real, Vec3};

use crate::plot::{
    write_figure, Figure, HistogramPanel, LinePanel, Panel, PlotError, Series, Style,
};
use crate::scene::{FigureKind, Scene, G_SI};
use crate::simulate::RunRecord;
use crate::spec::Spec;

/// Points of a drawn path, in data units.
type Path2 = Vec<(Real, Real)>;

/// Bins of the histograms.
pub const HISTOGRAM_BINS: usize = 60;

/// Time slices a time-series panel keeps the extremes of (two points each).
pub const PAGE_COLUMNS: usize = 2000;

/// Points of a drawn outline.
const OUTLINE_POINTS: usize = 180;

/// The names of the units of a scene's numbers, for axis labels and printed figures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Units {
    /// `m` or `length units`.
    pub length: &'static str,
    /// `s` or `time units`.
    pub time: &'static str,
    /// `s` or `time unit` (after "per").
    pub time_singular: &'static str,
    /// `J` or `energy units`.
    pub energy: &'static str,
    /// `kg m²/s` or `angular-momentum units`.
    pub angular_momentum: &'static str,
    /// Whether these are SI units.
    pub si: bool,
}

impl Units {
    /// SI when the scene's G is the SI value (`units = "si"`), the paper's unit-less setting
    /// otherwise.
    pub fn of(scene: &Scene) -> Self {
        if scene.gravitational_constant == G_SI {
            Self {
                length: "m",
                time: "s",
                time_singular: "s",
                energy: "J",
                angular_momentum: "kg m²/s",
                si: true,
            }
        } else {
            Self {
                length: "length units",
                time: "time units",
                time_singular: "time unit",
                energy: "energy units",
                angular_momentum: "angular-momentum units",
                si: false,
            }
        }
    }

    /// ` s` in SI, nothing otherwise (after a printed time).
    pub fn time_suffix(&self) -> String {
        if self.si {
            format!(" {}", self.time)
        } else {
            String::new()
        }
    }

    /// ` m` in SI, nothing otherwise (after a printed length).
    pub fn length_suffix(&self) -> String {
        if self.si {
            format!(" {}", self.length)
        } else {
            String::new()
        }
    }
}

/// Semi-axes of a body along its body axes x, y, z (`None` for a point mass; a disk has c = 0).
pub fn semi_axes(spec: &Spec) -> Option<[Real; 3]> {
    spec.semi_axes()
}

/// The outline of a body (semi-axes `axes`, at `state`'s orientation) projected onto the plane
/// of unit axes `u`, `v`, centred on `centre` (in that plane's coordinates): a closed polygon.
pub fn projected_outline(
    axes: [Real; 3],
    state: &BodyState,
    u: &Vec3,
    v: &Vec3,
    centre: (Real, Real),
) -> Vec<(Real, Real)> {
    let rotation = state.orientation.to_rotation_matrix();
    let m = rotation.matrix()
        * nalgebra::Matrix3::from_diagonal(&Vec3::new(
            axes[0] * axes[0],
            axes[1] * axes[1],
            axes[2] * axes[2],
        ))
        * rotation.matrix().transpose();
    let (s11, s12, s22) = (u.dot(&(m * u)), u.dot(&(m * v)), v.dot(&(m * v)));
    // L Lᵀ = S (Cholesky; S is positive semi-definite): the ellipse is L times the unit circle.
    let l11 = s11.max(0.0).sqrt();
    let l21 = if l11 > 0.0 { s12 / l11 } else { 0.0 };
    let l22 = (s22 - l21 * l21).max(0.0).sqrt();
    (0..=OUTLINE_POINTS)
        .map(|k| {
            let t = std::f64::consts::TAU * k as Real / OUTLINE_POINTS as Real;
            let (c, s) = (t.cos(), t.sin());
            (centre.0 + l11 * c, centre.1 + l21 * c + l22 * s)
        })
        .collect()
}

/// A view: two unit axes spanning the drawing plane, with their names.
#[derive(Debug, Clone)]
pub struct View {
    /// Horizontal axis.
    pub u: Vec3,
    /// Vertical axis.
    pub v: Vec3,
    /// Name of `u` (`x`, `−z`, `e₁`).
    pub u_name: String,
    /// Name of `v`.
    pub v_name: String,
}

/// A world axis's name if `e` is one (`x`, `−z`), else `fallback`.
fn axis_name(e: &Vec3, fallback: &str) -> String {
    for (k, name) in ["x", "y", "z"].iter().enumerate() {
        if (e[k].abs() - 1.0).abs() < 1e-12 {
            return if e[k] > 0.0 {
                (*name).to_string()
            } else {
                format!("−{name}")
            };
        }
    }
    fallback.to_string()
}

/// The orbit plane's axes and its normal: the normal is along $\mathbf r \times \dot{\mathbf r}$
/// at the start (any normal to $\mathbf r$ for a radial start); the x–y axes when the plane is
/// the x–y plane, else $\mathbf e_1$ along the start's $\mathbf r$ and
/// $\mathbf e_2 = \mathbf n \times \mathbf e_1$.
pub fn orbit_plane(run: &RunRecord) -> (View, Vec3, String) {
    let s = &run.first.state;
    let r = s.relative_position();
    let h = r.cross(&s.relative_velocity());
    let n = if h.norm() > 0.0 {
        h.normalize()
    } else {
        // Radial motion: any plane through r.
        let trial = if r.x.abs() < 0.9 * r.norm() {
            Vec3::x()
        } else {
            Vec3::y()
        };
        r.cross(&trial).normalize()
    };
    let (u, v, n) = if (n.z.abs() - 1.0).abs() < 1e-12 {
        // The x–y plane, seen from +z whichever way the orbit turns.
        (Vec3::x(), Vec3::y(), Vec3::z())
    } else {
        let e1 = r.normalize();
        (e1, n.cross(&e1), n)
    };
    let u_name = axis_name(&u, "e₁");
    let v_name = axis_name(&v, "e₂");
    let n_name = axis_name(&n, "n");
    (
        View {
            u,
            v,
            u_name,
            v_name,
        },
        n,
        n_name,
    )
}

fn project(p: &Vec3, view: &View) -> (Real, Real) {
    (p.dot(&view.u), p.dot(&view.v))
}

fn outline_series(
    spec: &Spec,
    state: &BodyState,
    view: &View,
    centre: (Real, Real),
    label: &str,
) -> Option<Series> {
    semi_axes(spec).map(|axes| Series {
        label: label.to_string(),
        points: projected_outline(axes, state, &view.u, &view.v, centre),
        style: Style::Dashed,
    })
}

fn lines(title: String, x: String, y: String, series: Vec<Series>, equal: bool) -> Panel {
    Panel::Lines(LinePanel {
        title,
        x_label: x,
        y_label: y,
        series,
        circles: vec![],
        equal_aspect: equal,
    })
}

/// Fig. 2: the orbits in their plane (about the centre of mass; B relative to A) and B
/// relative to A seen edge-on from two sides.
pub fn orbits(run: &RunRecord) -> Figure {
    let (ma, mb) = masses(run);
    let total = ma + mb;
    let units = Units::of(&run.scene);
    let (plane, normal, normal_name) = orbit_plane(run);
    let side_u = View {
        u: plane.u,
        v: normal,
        u_name: plane.u_name.clone(),
        v_name: normal_name.clone(),
    };
    let side_v = View {
        u: plane.v,
        v: normal,
        u_name: plane.v_name.clone(),
        v_name: normal_name,
    };
    let (spec_a, spec_b) = (&run.scene.spec_a, &run.scene.spec_b);
    let first = &run.first.state;
    let closest = &run.closest.state;
    let cm = |ra: Vec3, rb: Vec3| (ra * ma + rb * mb) / total;
    let about_cm = |view: &View| -> (Path2, Path2) {
        run.rows
            .iter()
            .map(|row| {
                let (ra, rb) = (row.state.body_a.position, row.state.body_b.position);
                let c = cm(ra, rb);
                (project(&(ra - c), view), project(&(rb - c), view))
            })
            .unzip()
    };
    let relative = |view: &View| -> Vec<(Real, Real)> {
        run.rows
            .iter()
            .map(|row| project(&row.state.relative_position(), view))
            .collect()
    };
    let relative_panel = |view: &View, title: String| {
        let mut series = vec![Series {
            label: "B − A".into(),
            points: relative(view),
            style: Style::Line,
        }];
        // A at the origin (the start's orientation), B at the start and at the closest step.
        series.extend(outline_series(
            spec_a,
            &first.body_a,
            view,
            (0.0, 0.0),
            "A (at the origin)",
        ));
        series.extend(outline_series(
            spec_b,
            &first.body_b,
            view,
            project(&first.relative_position(), view),
            "B at t = start",
        ));
        series.extend(outline_series(
            spec_b,
            &closest.body_b,
            view,
            project(&closest.relative_position(), view),
            "B at closest approach",
        ));
        lines(
            title,
            format!("{} ({})", view.u_name, units.length),
            format!("{} ({})", view.v_name, units.length),
            series,
            true,
        )
    };
    let (a, b) = about_cm(&plane);
    let c0 = cm(first.body_a.position, first.body_b.position);
    let mut cm_series = vec![
        Series {
            label: "body A".into(),
            points: a,
            style: Style::Line,
        },
        Series {
            label: "body B".into(),
            points: b,
            style: Style::Line,
        },
    ];
    cm_series.extend(outline_series(
        spec_a,
        &first.body_a,
        &plane,
        project(&(first.body_a.position - c0), &plane),
        "A at t = start",
    ));
    cm_series.extend(outline_series(
        spec_b,
        &first.body_b,
        &plane,
        project(&(first.body_b.position - c0), &plane),
        "B at t = start",
    ));
    let left = lines(
        "Centre-of-mass frame, orbit plane".into(),
        format!("{} ({})", plane.u_name, units.length),
        format!("{} ({})", plane.v_name, units.length),
        cm_series,
        true,
    );
    let right = relative_panel(&plane, "B relative to A, orbit plane".into());
    let side_1 = relative_panel(
        &side_u,
        format!("B relative to A, side view along {}", plane.v_name),
    );
    let side_2 = relative_panel(
        &side_v,
        format!("B relative to A, side view along {}", plane.u_name),
    );
    let bodies = semi_axes(spec_a).is_some() || semi_axes(spec_b).is_some();
    Figure {
        title: format!(
            "{}: orbits, t = {}…{}{}",
            run.scene.name,
            crate::spec::compact(run.scene.t_start),
            crate::spec::compact(run.t_reached()),
            if bodies {
                " (bodies to scale: projected outlines, dashed)"
            } else {
                " (point masses)"
            }
        ),
        panels: vec![left, right, side_1, side_2],
        columns: 2,
    }
}

fn masses(run: &RunRecord) -> (Real, Real) {
    let m = |b: &crate::spec::BuiltBody| b.into_potential().mass();
    (m(&run.scene.body_a), m(&run.scene.body_b))
}

/// Per-step changes $(t_k, x_k - x\_{k-1})$ over every step.
pub fn step_changes(run: &RunRecord, values: &[Real]) -> Vec<(Real, Real)> {
    run.step_times
        .iter()
        .skip(1)
        .zip(values.windows(2))
        .map(|(&t, w)| (t, w[1] - w[0]))
        .collect()
}

/// Thins a time series to what a page shows: for each of `columns` equal time slices over
/// the series' span, the points of smallest and largest value, in time order. Series of at
/// most `2 · columns` points are returned whole.
pub fn thin_to_page(points: Vec<(Real, Real)>, columns: usize) -> Vec<(Real, Real)> {
    let columns = columns.max(1);
    if points.len() <= 2 * columns {
        return points;
    }
    let (t0, t1) = (points[0].0, points[points.len() - 1].0);
    let width = (t1 - t0) / columns as Real;
    if width.is_nan() || width <= 0.0 {
        return points;
    }
    let mut out = Vec::with_capacity(2 * columns + 2);
    let mut start = 0;
    while start < points.len() {
        let column = (((points[start].0 - t0) / width).floor() as usize).min(columns - 1);
        let mut end = start + 1;
        while end < points.len()
            && (((points[end].0 - t0) / width).floor() as usize).min(columns - 1) == column
        {
            end += 1;
        }
        let group = &points[start..end];
        let (mut lo, mut hi) = (0, 0);
        for (i, p) in group.iter().enumerate() {
            if p.1 < group[lo].1 {
                lo = i;
            }
            if p.1 > group[hi].1 {
                hi = i;
            }
        }
        out.push(group[lo.min(hi)]);
        if lo != hi {
            out.push(group[lo.max(hi)]);
        }
        start = end;
    }
    out
}

/// $(t_k, (x_k - x_0)/|x_0|)$ over every step ($x_k - x_0$ when $x_0 = 0$).
pub fn cumulative_relative_change(run: &RunRecord, values: &[Real]) -> Vec<(Real, Real)> {
    let Some(&x0) = values.first() else {
        return Vec::new();
    };
    let scale = if x0 != 0.0 { x0.abs() } else { 1.0 };
    run.step_times
        .iter()
        .zip(values)
        .map(|(&t, &x)| (t, (x - x0) / scale))
        .collect()
}

/// Fig. 3: separation, ΔE and ΔJ per step, and the cumulative relative changes of E and J,
/// against time.
pub fn conservation(run: &RunRecord) -> Figure {
    let units = Units::of(&run.scene);
    let separation: Vec<(Real, Real)> = run
        .rows
        .iter()
        .map(|row| (row.time, row.state.separation()))
        .collect();
    let time_label = format!("time t ({})", units.time);
    let line = |title: &str, y: String, label: &str, points: Vec<(Real, Real)>| {
        lines(
            title.into(),
            time_label.clone(),
            y,
            vec![Series {
                label: label.into(),
                points: thin_to_page(points, PAGE_COLUMNS),
                style: Style::Line,
            }],
            false,
        )
    };
    Figure {
        title: format!(
            "{}: r_AB, ΔE, ΔJ and their drift ({})",
            run.scene.name,
            integrator_label(run)
        ),
        panels: vec![
            line(
                "Centroid separation",
                format!("r_AB ({})", units.length),
                "r_AB",
                separation,
            ),
            line(
                "Energy change per step",
                format!("ΔE ({})", units.energy),
                "ΔE",
                step_changes(run, &run.energies),
            ),
            line(
                "Angular-momentum change per step",
                format!("ΔJ ({})", units.angular_momentum),
                "ΔJ",
                step_changes(run, &run.angular_momenta),
            ),
            line(
                "Energy drift since the start",
                "(E − E0)/|E0| (dimensionless)".into(),
                "(E − E0)/|E0|",
                cumulative_relative_change(run, &run.energies),
            ),
            line(
                "Angular-momentum drift since the start",
                "(J − J0)/|J0| (dimensionless)".into(),
                "(J − J0)/|J0|",
                cumulative_relative_change(run, &run.angular_momenta),
            ),
        ],
        columns: 1,
    }
}

/// Fig. 4: histograms of ΔE and ΔJ.
pub fn histograms(run: &RunRecord) -> Figure {
    let units = Units::of(&run.scene);
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
                x_label: format!("ΔE ({})", units.energy),
                y_label: "count".into(),
                values: values(&run.energies),
                bins: HISTOGRAM_BINS,
            }),
            Panel::Histogram(HistogramPanel {
                title: "Angular-momentum change per step".into(),
                x_label: format!("ΔJ ({})", units.angular_momentum),
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
            format!("{}, dt = {}", method.name(), crate::spec::compact(step))
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
        FigureKind::Rotation => "fig5_rotation",
    }
}

/// The figure of one kind.
pub fn figure(run: &RunRecord, kind: FigureKind) -> Figure {
    match kind {
        FigureKind::Orbits => orbits(run),
        FigureKind::Conservation => conservation(run),
        FigureKind::Histograms => histograms(run),
        FigureKind::Rotation => rotation(run),
    }
}

/// The figures a run draws: the scene's list, plus [`FigureKind::Rotation`] for a run that
/// integrated rotation when the scene did not choose its figures.
pub fn kinds(run: &RunRecord) -> Vec<FigureKind> {
    let mut kinds = run.scene.figures.clone();
    if run.path.is_rotation()
        && kinds == FigureKind::ALL.to_vec()
        && !kinds.contains(&FigureKind::Rotation)
    {
        kinds.push(FigureKind::Rotation);
    }
    kinds
}

/// Spin rates, obliquities and libration angles of both bodies against time (the written rows),
/// and the drifts of E and of the vector J (every step).
pub fn rotation(run: &RunRecord) -> Figure {
    use surfgrav_dynamics::{libration_deg, long_axis, obliquity_deg};
    let units = Units::of(&run.scene);
    let time_label = format!("time t ({})", units.time);
    let inertia = |b: &crate::spec::BuiltBody| b.into_potential().inertia();
    let axes = [
        long_axis(inertia(&run.scene.body_a)),
        long_axis(inertia(&run.scene.body_b)),
    ];
    let per_body = |f: &dyn Fn(&crate::simulate::OutputRow, usize) -> Option<Real>| {
        ["A", "B"]
            .iter()
            .enumerate()
            .map(|(k, name)| Series {
                label: format!("body {name}"),
                points: thin_to_page(
                    run.rows
                        .iter()
                        .filter_map(|row| f(row, k).map(|y| (row.time, y)))
                        .collect(),
                    PAGE_COLUMNS,
                ),
                style: Style::Line,
            })
            .filter(|s| !s.points.is_empty())
            .collect::<Vec<_>>()
    };
    let spin = per_body(&|row, k| {
        let b = if k == 0 {
            &row.state.body_a
        } else {
            &row.state.body_b
        };
        Some(b.angular_velocity.norm())
    });
    let obliquity = per_body(&|row, k| obliquity_deg(&row.state, k));
    let libration = per_body(&|row, k| axes[k].and_then(|a| libration_deg(&row.state, k, &a)));
    let series = |label: &str, points: Vec<(Real, Real)>| {
        vec![Series {
            label: label.into(),
            points: thin_to_page(points, PAGE_COLUMNS),
            style: Style::Line,
        }]
    };
    let j_errors: Vec<(Real, Real)> = run
        .step_times
        .iter()
        .copied()
        .zip(run.angular_momentum_errors.iter().copied())
        .collect();
    Figure {
        title: format!(
            "{}: spins and libration ({})",
            run.scene.name,
            run.scene.integrator.method().name()
        ),
        panels: {
            // Panels with nothing to show (no spin, no elongated body) are left out.
            let mut panels = Vec::new();
            for (title, y, data) in [
                (
                    "Spin rates",
                    format!("|ω| (rad per {})", units.time_singular),
                    spin,
                ),
                (
                    "Obliquity: spin axis to the mutual orbit's normal",
                    "obliquity (degrees)".to_string(),
                    obliquity,
                ),
                (
                    "Libration: long axis to the line of centres",
                    "libration angle (degrees)".to_string(),
                    libration,
                ),
            ] {
                if !data.is_empty() {
                    panels.push(lines(title.into(), time_label.clone(), y, data, false));
                }
            }
            panels.push(lines(
                "Energy error since the start".into(),
                time_label.clone(),
                "(E − E0)/|E0| (dimensionless)".into(),
                series(
                    "(E − E0)/|E0|",
                    cumulative_relative_change(run, &run.energies),
                ),
                false,
            ));
            panels.push(lines(
                "Angular-momentum vector error since the start".into(),
                time_label,
                "|J − J0|/|J0| (dimensionless)".into(),
                series("|J − J0|/|J0|", j_errors),
                false,
            ));
            panels
        },
        columns: 1,
    }
}

/// Writes the scene's figures into `folder`; returns the files written.
///
/// # Errors
/// The plot module's errors.
pub fn write_all(run: &RunRecord, folder: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let mut files = Vec::new();
    for kind in kinds(run) {
        files.extend(write_figure(&figure(run, kind), &folder.join(stem(kind)))?);
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::presets;
    use crate::scene::SceneFile;
    use crate::simulate::run_scene;

    fn paper_2s(t_end: f64) -> RunRecord {
        let mut scene = presets::find("paper-2s").unwrap().scene().unwrap();
        scene.override_with(Some(t_end), None, None, None).unwrap();
        run_scene(&scene).unwrap()
    }

    fn extent(points: &[(f64, f64)]) -> (f64, f64, f64, f64) {
        points.iter().fold(
            (
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            ),
            |(a, b, c, d), &(x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
        )
    }

    /// Outlines are true projections: a 1.5 × 1.0 × 0.5 ellipsoid seen along z spans ±1.5 by
    /// ±1.0 (not a circle of 1.5), seen along y ±1.5 by ±0.5; a disk of radius 2 tilted by 60°
    /// about x spans ±2 by ±2 cos 60° = ±1; rotating the ellipsoid by 90° about z swaps its
    /// extents. The extremes of 180 outline points reach the true ones to 1 − cos(π/180).
    #[test]
    fn outlines_are_projected_ellipses_at_the_orientation() {
        let tol = 2e-4 * 2.0;
        let at = |orientation: Vec3| {
            let mut b = BodyState::new(Vec3::zeros(), Vec3::zeros());
            b.orientation = nalgebra::UnitQuaternion::from_scaled_axis(orientation);
            b
        };
        let (x, y, z) = (Vec3::x(), Vec3::y(), Vec3::z());
        let check = |pts: Vec<(f64, f64)>, hu: f64, hv: f64| {
            let (x0, x1, y0, y1) = extent(&pts);
            for (got, want) in [(-x0, hu), (x1, hu), (-y0, hv), (y1, hv)] {
                assert!((got - want).abs() <= tol * want.max(1.0), "{got} vs {want}");
            }
        };
        let e = [1.5, 1.0, 0.5];
        check(
            projected_outline(e, &at(Vec3::zeros()), &x, &y, (0.0, 0.0)),
            1.5,
            1.0,
        );
        check(
            projected_outline(e, &at(Vec3::zeros()), &x, &z, (0.0, 0.0)),
            1.5,
            0.5,
        );
        let quarter = Vec3::new(0.0, 0.0, std::f64::consts::FRAC_PI_2);
        check(
            projected_outline(e, &at(quarter), &x, &y, (0.0, 0.0)),
            1.0,
            1.5,
        );
        let tilt = Vec3::new(std::f64::consts::FRAC_PI_3, 0.0, 0.0);
        check(
            projected_outline([2.0, 2.0, 0.0], &at(tilt), &x, &y, (0.0, 0.0)),
            2.0,
            1.0,
        );
        // Edge-on, a disk is a segment: no height.
        check(
            projected_outline([2.0, 2.0, 0.0], &at(Vec3::zeros()), &x, &z, (0.0, 0.0)),
            2.0,
            0.0,
        );
        // The centre shifts the outline.
        let shifted = projected_outline(e, &at(Vec3::zeros()), &x, &y, (3.0, -1.0));
        let (x0, x1, _, _) = extent(&shifted);
        assert!((x0 - 1.5).abs() < tol && (x1 - 4.5).abs() < tol);
    }

    #[test]
    fn orbit_figure_draws_the_orbit_plane_two_side_views_and_outlines() {
        let run = paper_2s(40.0);
        let figure = orbits(&run);
        assert_eq!((figure.columns, figure.panels.len()), (2, 4));
        let panels: Vec<&LinePanel> = figure
            .panels
            .iter()
            .map(|p| match p {
                Panel::Lines(l) => l,
                _ => panic!("line panels"),
            })
            .collect();
        assert!(panels.iter().all(|p| p.equal_aspect));
        // The paper's orbit lies in the x–y plane: face-on x–y, side views x–z and y–z.
        assert!(panels[0].x_label.starts_with("x (") && panels[0].y_label.starts_with("y ("));
        assert!(panels[2].x_label.starts_with("x (") && panels[2].y_label.starts_with("z ("));
        assert!(panels[3].x_label.starts_with("y (") && panels[3].y_label.starts_with("z ("));
        // Equal masses: the centre of mass is the midpoint, A starts at (−3.5, 0).
        assert_eq!(panels[0].series[0].points[0], (-3.5, 0.0));
        assert_eq!(panels[0].series[0].points.len(), run.rows.len());
        // A's outline at the start: the spheroid a = 1 seen face-on is a circle of radius 1
        // about (−3.5, 0); edge-on (side view) it is 2 wide and 2c = 0.5 high.
        let outline = &panels[0].series[2];
        assert_eq!(outline.style, Style::Dashed);
        let (x0, x1, y0, y1) = extent(&outline.points);
        assert!(
            (x0 + 4.5).abs() < 1e-3 && (x1 + 2.5).abs() < 1e-3,
            "{x0} {x1}"
        );
        assert!((y1 - 1.0).abs() < 1e-3 && (y0 + 1.0).abs() < 1e-3);
        let a_side = &panels[2].series[1];
        let (x0, x1, y0, y1) = extent(&a_side.points);
        assert!((x1 - x0 - 2.0).abs() < 1e-3 && (y1 - y0 - 0.5).abs() < 1e-3);
        // B at closest approach: the closest step's separation (minimum 2.5472 between steps;
        // steps of 0.1 miss it by less than 1e-3).
        let closest = &panels[1].series[3];
        let (x0, x1, y0, y1) = extent(&closest.points);
        let d = (0.5 * (x0 + x1)).hypot(0.5 * (y0 + y1));
        assert!((d - 2.5472).abs() < 1e-3, "{d}");
        assert!(figure.title.contains("to scale"));
    }

    /// An orbit in the x–z plane is drawn face-on (not as a line): its plane is spanned by the
    /// start's r and n × r, and the side views show the thin direction.
    #[test]
    fn an_orbit_in_the_x_z_plane_is_drawn_face_on() {
        let text = presets::find("paper-point")
            .unwrap()
            .toml
            .replace("velocity = [0.0, 0.2, 0.0]", "velocity = [0.0, 0.0, 0.2]")
            .replace("velocity = [0.0, -0.2, 0.0]", "velocity = [0.0, 0.0, -0.2]")
            .replace("t_end = 300.0", "t_end = 50.0");
        let scene = SceneFile::parse(&text, "xz.toml")
            .unwrap()
            .build(&text, "xz.toml")
            .unwrap();
        let run = run_scene(&scene).unwrap();
        let figure = orbits(&run);
        let Panel::Lines(face) = &figure.panels[1] else {
            panic!("line panel")
        };
        let (x0, x1, y0, y1) = extent(&face.series[0].points);
        // Face-on, the Kepler ellipse (pericentre 2.722, apocentre 7) is wide in both axes.
        assert!(x1 - x0 > 5.0 && y1 - y0 > 3.0, "{x0} {x1} {y0} {y1}");
        assert!(
            face.x_label.starts_with("x (") && face.y_label.starts_with("−z ("),
            "{}",
            face.y_label
        );
        let Panel::Lines(side) = &figure.panels[2] else {
            panic!("line panel")
        };
        let (_, _, y0, y1) = extent(&side.series[0].points);
        assert!(y1 - y0 < 1e-9, "the side view is edge-on");
    }

    #[test]
    fn conservation_and_histograms_use_every_step() {
        let run = paper_2s(20.0);
        let steps = run.summary.steps;
        let c = conservation(&run);
        assert_eq!(c.panels.len(), 5);
        let Panel::Lines(de) = &c.panels[1] else {
            panic!("line panel")
        };
        assert_eq!(de.series[0].points.len(), steps);
        let expected = run.energies[1] - run.energies[0];
        assert_eq!(de.series[0].points[0], (run.step_times[1], expected));
        let Panel::Lines(cumulative) = &c.panels[3] else {
            panic!("line panel")
        };
        let last = cumulative.series[0].points.last().unwrap().1;
        let e = &run.energies;
        assert_eq!(last, (e[e.len() - 1] - e[0]) / e[0].abs());
        assert!(de.x_label.contains("time units"));
        let h = histograms(&run);
        let Panel::Histogram(hj) = &h.panels[1] else {
            panic!("histogram")
        };
        assert_eq!(hj.values.len(), steps);
        assert!(hj.x_label.contains("ΔJ"));
    }

    /// Thinning keeps each time slice's extremes: a spike of one sample survives among 10⁵.
    #[test]
    fn thinning_keeps_the_extremes_of_each_slice() {
        let mut points: Vec<(f64, f64)> =
            (0..100_000).map(|k| (k as f64, (k % 7) as f64)).collect();
        points[54_321].1 = 1e3;
        points[12_345].1 = -1e3;
        let thin = thin_to_page(points, 1000);
        assert!(thin.len() <= 2000, "{}", thin.len());
        assert!(thin.contains(&(54_321.0, 1e3)) && thin.contains(&(12_345.0, -1e3)));
        assert!(thin.windows(2).all(|w| w[0].0 < w[1].0));
        let short: Vec<(f64, f64)> = (0..10).map(|k| (k as f64, 1.0)).collect();
        assert_eq!(thin_to_page(short.clone(), 1000), short);
    }

    /// An SI scene is labelled in m, s, J.
    #[test]
    fn si_scenes_are_labelled_in_si_units() {
        let text = presets::find("paper-point")
            .unwrap()
            .toml
            .replace("gravitational_constant = 1.0", "units = \"si\"")
            .replace("mass = 1.0", "mass = 1e10")
            .replace("t_end = 300.0", "t_end = 100.0")
            .replace("step = 0.1", "step = 1.0");
        let scene = SceneFile::parse(&text, "si.toml")
            .unwrap()
            .build(&text, "si.toml")
            .unwrap();
        let run = run_scene(&scene).unwrap();
        let Panel::Lines(p) = &orbits(&run).panels[0] else {
            panic!("line panel")
        };
        assert_eq!(p.x_label, "x (m)");
        let c = conservation(&run);
        let Panel::Lines(de) = &c.panels[1] else {
            panic!("line panel")
        };
        assert_eq!(de.x_label, "time t (s)");
        assert_eq!(de.y_label, "ΔE (J)");
    }
}
