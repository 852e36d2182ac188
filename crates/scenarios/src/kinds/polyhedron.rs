//! A homogeneous polyhedron from a triangle mesh file.
//!
//! Scene file:
//!
//! ```toml
//! shape = "polyhedron"
//! mesh = "kw4_alpha.obj"            # Wavefront OBJ; relative to the scene file's folder
//! mesh_units = "km"                 # "m" (default) or "km"
//! density = 1970.0                  # or mass = ...
//! # principal_axes = true           # turn the body frame to the principal axes (default false)
//! ```
//!
//! The Didymos radar model is a vertex/facet CSV pair: `mesh` names the vertex file
//! (`filler,x,y,z`) and `mesh_facets` the facet file (`i,j,k,,`, 1-based). A name of the form
//! `builtin:FILE` is one of the shape models shipped inside the binary (the files of the
//! repository's `data/shapes/`, see [`BUILTIN`]), so a scene using them runs from any folder.
//!
//! Command line: `polyhedron:mesh=PATH,density=D[,units=km][,facets=PATH][,principal_axes=true]`
//! (paths relative to the working folder).
//!
//! The mesh is validated (closed, consistently outward, no degenerate faces or
//! self-intersections, positive volume) and its errors name the file and the face or edge. The
//! body frame is the mesh's own axes moved to the centroid (positions in a scene are centroid
//! positions); with `principal_axes = true` it is also turned to the principal axes (A ≤ B ≤ C
//! about x, y, z). [`PolyhedronBody::note`] says what was applied.

use std::path::Path;

use surfgrav_potentials::{
    LengthUnit, Mesh, MeshError, Polyhedron, PolyhedronError, Potential, Real, Vec3,
};

use super::{Key, KeyError, Kind, ValueKind, Values};
use crate::spec::{compact, Amount, BuiltBody, Spec, SpecError};

/// The prefix naming a built-in shape model.
pub const BUILTIN_PREFIX: &str = "builtin:";

/// The shape models shipped inside the binary: the files of `data/shapes/` (provenance in
/// `data/shapes/README.md`).
pub const BUILTIN: &[(&str, &str)] = &[
    (
        "kw4_alpha.obj",
        include_str!("../../../../data/shapes/kw4_alpha.obj"),
    ),
    (
        "kw4_beta.obj",
        include_str!("../../../../data/shapes/kw4_beta.obj"),
    ),
    (
        "Didymos_A_vert_met.csv",
        include_str!("../../../../data/shapes/Didymos_A_vert_met.csv"),
    ),
    (
        "Didymos_A_facet.csv",
        include_str!("../../../../data/shapes/Didymos_A_facet.csv"),
    ),
];

/// The polyhedron.
pub(super) static KIND: Kind = Kind {
    name: "polyhedron",
    keys: &[
        Key {
            scene: "mesh",
            cli: &["mesh"],
            value: ValueKind::Path,
            required: true,
        },
        Key {
            scene: "mesh_facets",
            cli: &["facets"],
            value: ValueKind::Path,
            required: false,
        },
        Key {
            scene: "mesh_units",
            cli: &["units"],
            value: ValueKind::Unit,
            required: false,
        },
        Key {
            scene: "principal_axes",
            cli: &["principal_axes"],
            value: ValueKind::Flag,
            required: false,
        },
    ],
    solid: true,
    check,
    build,
    semi_axes: |_| None,
};

/// A built polyhedron with what was done to its frame.
#[derive(Debug, Clone)]
pub struct PolyhedronBody {
    /// The body (centroid at the origin; principal axes if asked).
    pub polyhedron: Polyhedron,
    /// The mesh as named (`builtin:...` or a path).
    pub source: String,
    /// The centroid in the mesh file's frame (the body was moved by minus this).
    pub centroid: Vec3,
    /// The rotation to the principal axes, new = R (old − centroid), if applied.
    pub rotation: Option<surfgrav_potentials::PrincipalFrame>,
}

impl PartialEq for PolyhedronBody {
    fn eq(&self, other: &Self) -> bool {
        let (a, b) = (&self.polyhedron, &other.polyhedron);
        self.source == other.source
            && self.centroid == other.centroid
            && self.rotation == other.rotation
            && a.vertices() == b.vertices()
            && a.faces() == b.faces()
            && a.mass().to_bits() == b.mass().to_bits()
            && a.gravitational_constant().to_bits() == b.gravitational_constant().to_bits()
    }
}

impl PolyhedronBody {
    /// One line saying what was read and what was done to the frame.
    pub fn note(&self) -> String {
        let p = &self.polyhedron;
        let c = self.centroid;
        let mut text = format!(
            "{}: {} vertices, {} faces, mass {}, density {}; body frame at its centroid ({}, {}, {}) of the file's frame",
            self.source,
            p.vertices().len(),
            p.faces().len(),
            compact(p.mass()),
            compact(p.density()),
            crate::cli::significant(c.x, 6),
            crate::cli::significant(c.y, 6),
            crate::cli::significant(c.z, 6),
        );
        match &self.rotation {
            Some(frame) => {
                let r = frame.rotation.scaled_axis();
                text.push_str(&format!(
                    ", turned to its principal axes by the rotation vector ({}, {}, {}) rad \
                     (moments {}, {}, {})",
                    crate::cli::significant(r.x, 6),
                    crate::cli::significant(r.y, 6),
                    crate::cli::significant(r.z, 6),
                    crate::cli::significant(frame.moments.x, 6),
                    crate::cli::significant(frame.moments.y, 6),
                    crate::cli::significant(frame.moments.z, 6),
                ));
            }
            None => text.push_str(", axes as in the file"),
        }
        text
    }
}

fn is_csv(path: &str) -> bool {
    path.to_ascii_lowercase().ends_with(".csv")
}

fn is_obj(path: &str) -> bool {
    path.to_ascii_lowercase().ends_with(".obj")
}

fn check(values: &Values) -> Result<(), KeyError> {
    let mesh = values.text("mesh").unwrap_or_default();
    let facets = values.text("mesh_facets");
    for (key, path) in [("mesh", Some(mesh)), ("mesh_facets", facets)] {
        if let Some(name) = path.and_then(|p| p.strip_prefix(BUILTIN_PREFIX)) {
            if !BUILTIN.iter().any(|(n, _)| *n == name) {
                return Err(KeyError {
                    key,
                    message: format!(
                        "no built-in shape model `{name}`: expected one of {}",
                        BUILTIN
                            .iter()
                            .map(|(n, _)| format!("{BUILTIN_PREFIX}{n}"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                });
            }
        }
    }
    match (is_obj(mesh), is_csv(mesh), facets) {
        (true, _, None) | (_, true, Some(_)) => Ok(()),
        (true, _, Some(_)) => Err(KeyError {
            key: "mesh_facets",
            message: "an OBJ mesh holds its faces: remove the facet file (it is for a vertex CSV)"
                .into(),
        }),
        (_, true, None) => Err(KeyError {
            key: "mesh",
            message: format!(
                "`{mesh}` is a vertex CSV: name its facet file too (mesh_facets in a scene, facets= on the command line)"
            ),
        }),
        _ => Err(KeyError {
            key: "mesh",
            message: format!(
                "cannot tell the format of `{mesh}`: give a Wavefront .obj file, or a vertex .csv with its facet file"
            ),
        }),
    }
}

/// The text of a built-in shape model.
fn builtin_text(path: &str) -> Option<(&'static str, &'static str)> {
    let name = path.strip_prefix(BUILTIN_PREFIX)?;
    BUILTIN.iter().copied().find(|(n, _)| *n == name)
}

/// Reads the mesh a spec names (a file, or a built-in model).
pub fn read_mesh(values: &Values) -> Result<Mesh, SpecError> {
    let mesh = values.text("mesh").unwrap_or_default();
    let facets = values.text("mesh_facets");
    let unit = match values.text("mesh_units") {
        Some(u) => u.parse::<LengthUnit>().map_err(|source| SpecError::Mesh {
            path: mesh.to_string(),
            source,
        })?,
        None => LengthUnit::Metres,
    };
    let wrap = |source| SpecError::Mesh {
        path: mesh.to_string(),
        source,
    };
    let read = match (builtin_text(mesh), facets) {
        (Some((name, text)), None) => Mesh::parse_obj(name, text, unit),
        (Some((name, text)), Some(f)) => {
            let (fname, ftext) = builtin_text(f).ok_or_else(|| SpecError::Mesh {
                path: f.to_string(),
                source: MeshError::Io {
                    path: f.to_string(),
                    message: "a built-in vertex file needs a built-in facet file".into(),
                },
            })?;
            Mesh::parse_vertex_facet_csv(name, text, fname, ftext, unit)
        }
        (None, None) => Mesh::read_obj(mesh, unit),
        (None, Some(f)) => Mesh::read_vertex_facet_csv(mesh, f, unit),
    };
    read.map_err(wrap)
}

fn build(spec: &Spec, g: Real) -> Result<BuiltBody, SpecError> {
    let source = spec.values.text("mesh").unwrap_or_default().to_string();
    let mesh = read_mesh(&spec.values)?;
    let body = match spec.amount {
        Amount::Mass(m) => Polyhedron::with_mass(&mesh, m),
        Amount::Density(rho) => Polyhedron::with_density(&mesh, rho),
    }
    .and_then(|p| p.with_gravitational_constant(g).map_err(Into::into))
    .map_err(|e| match e {
        PolyhedronError::Mesh(source) => SpecError::Mesh {
            path: source_path(&spec.values),
            source,
        },
        PolyhedronError::Body(source) => SpecError::Body {
            kind: KIND.name,
            source,
        },
        other => SpecError::Polyhedron {
            message: other.to_string(),
        },
    })?;
    let centroid = body.centroid();
    let (polyhedron, rotation) = if spec.values.flag("principal_axes").unwrap_or(false) {
        let (p, frame) = body.to_principal_axes();
        (p, Some(frame))
    } else {
        (body, None)
    };
    Ok(BuiltBody::Polyhedron(std::sync::Arc::new(PolyhedronBody {
        polyhedron,
        source,
        centroid,
        rotation,
    })))
}

/// The mesh's file (and facet file) for messages.
fn source_path(values: &Values) -> String {
    let mesh = values.text("mesh").unwrap_or_default();
    match values.text("mesh_facets") {
        Some(f) => format!("{mesh} + {f}"),
        None => mesh.to_string(),
    }
}

/// Whether `path` names a built-in model rather than a file.
pub fn is_builtin(path: &str) -> bool {
    path.starts_with(BUILTIN_PREFIX)
}

/// Resolves a mesh path written in a scene file against the scene's folder (built-in names
/// and absolute paths unchanged).
pub fn resolve(path: &str, folder: Option<&Path>) -> String {
    if is_builtin(path) || Path::new(path).is_absolute() {
        return path.to_string();
    }
    match folder {
        Some(f) if !f.as_os_str().is_empty() => f.join(path).display().to_string(),
        _ => path.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn shapes() -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/shapes")
    }

    /// The embedded models are the repository's files, read the same way as the files are.
    #[test]
    fn builtin_models_equal_the_files() {
        for name in ["kw4_alpha.obj", "kw4_beta.obj"] {
            let (_, text) = builtin_text(&format!("builtin:{name}")).unwrap();
            let embedded = Mesh::parse_obj(name, text, LengthUnit::Kilometres).unwrap();
            let file = Mesh::read_obj(shapes().join(name), LengthUnit::Kilometres).unwrap();
            assert_eq!(embedded, file, "{name}");
        }
        let (_, v) = builtin_text("builtin:Didymos_A_vert_met.csv").unwrap();
        let (_, f) = builtin_text("builtin:Didymos_A_facet.csv").unwrap();
        let embedded = Mesh::parse_vertex_facet_csv("v", v, "f", f, LengthUnit::Metres).unwrap();
        let file = Mesh::read_vertex_facet_csv(
            shapes().join("Didymos_A_vert_met.csv"),
            shapes().join("Didymos_A_facet.csv"),
            LengthUnit::Metres,
        )
        .unwrap();
        assert_eq!(embedded, file);
        assert_eq!(
            (embedded.vertices.len(), embedded.faces.len()),
            (1000, 1996)
        );
    }
}
