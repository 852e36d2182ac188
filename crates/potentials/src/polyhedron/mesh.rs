//! Triangle meshes: reading Wavefront OBJ and the Didymos vertex/facet CSV pair, and a few
//! generated shapes.

use std::path::Path;

use super::validate::MeshError;
use crate::{Real, Vec3};

/// The length unit of the coordinates in a mesh file. Readers multiply coordinates by
/// [`LengthUnit::metres`], so every mesh comes out in metres.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LengthUnit {
    /// Metres (factor 1).
    Metres,
    /// Kilometres (factor 1000).
    Kilometres,
}

impl LengthUnit {
    /// Metres per unit.
    pub fn metres(self) -> Real {
        match self {
            LengthUnit::Metres => 1.0,
            LengthUnit::Kilometres => 1000.0,
        }
    }
}

impl std::str::FromStr for LengthUnit {
    type Err = MeshError;

    /// `m` or `km`.
    fn from_str(s: &str) -> Result<Self, MeshError> {
        match s.trim() {
            "m" => Ok(LengthUnit::Metres),
            "km" => Ok(LengthUnit::Kilometres),
            other => Err(MeshError::UnknownUnit {
                unit: other.to_string(),
            }),
        }
    }
}

/// A triangle mesh: vertex positions and faces as 0-based vertex indices, counter-clockwise
/// seen from outside. Not validated until it builds a [`super::Polyhedron`] (or
/// [`Mesh::validate`] is called).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    /// Vertex positions.
    pub vertices: Vec<Vec3>,
    /// Faces: three 0-based indices into `vertices` each.
    pub faces: Vec<[usize; 3]>,
}

fn io_error(path: &Path, e: impl std::fmt::Display) -> MeshError {
    MeshError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

/// `tobj` says neither which line of an OBJ text it could not read nor why: the first `v` or
/// `f` line that is not three numbers or three positive indices (`i`, `i/t`, `i/t/n`, `i//n`).
fn first_obj_problem(name: &str, text: &str) -> Option<MeshError> {
    let problem = |line: usize, message: String| MeshError::Parse {
        path: name.to_string(),
        line,
        message,
    };
    for (k, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                for _ in 0..3 {
                    let word = words.next().unwrap_or_default();
                    if let Err(e) = word.parse::<Real>() {
                        return Some(problem(k + 1, format!("coordinate {word:?}: {e}")));
                    }
                }
            }
            Some("f") => {
                for corner in words {
                    let index = corner.split('/').next().unwrap_or_default();
                    if !matches!(index.parse::<usize>(), Ok(i) if i > 0) {
                        return Some(problem(k + 1, format!("vertex index {index:?}")));
                    }
                }
            }
            _ => {}
        }
    }
    None
}

impl Mesh {
    /// Checks that the mesh bounds a solid: see [`MeshError`] for what is checked.
    pub fn validate(&self) -> Result<(), MeshError> {
        super::validate::validate(self).map(|_| ())
    }

    /// Reads a Wavefront OBJ file (`v` and `f` lines; every face a triangle; several objects
    /// are merged), coordinates multiplied by `unit` into metres.
    pub fn read_obj(path: impl AsRef<Path>, unit: LengthUnit) -> Result<Self, MeshError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| io_error(path, e))?;
        Mesh::parse_obj(&path.display().to_string(), &text, unit)
    }

    /// A Wavefront OBJ text, as [`Mesh::read_obj`] reads a file holding it (`name` names it in
    /// errors). The text is parsed by `tobj`; where `tobj` refuses it, the first line it could
    /// not read is named.
    pub fn parse_obj(name: &str, text: &str, unit: LengthUnit) -> Result<Self, MeshError> {
        let options = tobj::LoadOptions {
            single_index: false,
            triangulate: false,
            ignore_points: true,
            ignore_lines: true,
        };
        let no_materials = |_: &Path| Err(tobj::LoadError::OpenFileFailed);
        let (models, _materials) = tobj::load_obj_buf(&mut text.as_bytes(), &options, no_materials)
            .map_err(|e| {
                first_obj_problem(name, text).unwrap_or_else(|| MeshError::Io {
                    path: name.to_string(),
                    message: e.to_string(),
                })
            })?;
        let scale = unit.metres();
        let mut mesh = Mesh::default();
        for model in models {
            let m = &model.mesh;
            let base = mesh.vertices.len();
            if let Some(k) = m.face_arities.iter().position(|&n| n != 3) {
                return Err(MeshError::NotTriangle {
                    path: name.to_string(),
                    face: mesh.faces.len() + k,
                    corners: m.face_arities[k] as usize,
                });
            }
            mesh.vertices.extend(
                m.positions
                    .chunks_exact(3)
                    .map(|p| Vec3::new(p[0], p[1], p[2]) * scale),
            );
            mesh.faces.extend(m.indices.chunks_exact(3).map(|f| {
                [
                    base + f[0] as usize,
                    base + f[1] as usize,
                    base + f[2] as usize,
                ]
            }));
        }
        Ok(mesh)
    }

    /// Reads the vertex/facet CSV pair of the Didymos radar model: vertex lines
    /// `filler,x,y,z` (the first column unused), facet lines `i,j,k,,` with 1-based indices;
    /// coordinates multiplied by `unit` into metres.
    pub fn read_vertex_facet_csv(
        vertices: impl AsRef<Path>,
        facets: impl AsRef<Path>,
        unit: LengthUnit,
    ) -> Result<Self, MeshError> {
        let (vpath, fpath) = (vertices.as_ref(), facets.as_ref());
        let vtext = std::fs::read_to_string(vpath).map_err(|e| io_error(vpath, e))?;
        let ftext = std::fs::read_to_string(fpath).map_err(|e| io_error(fpath, e))?;
        Mesh::parse_vertex_facet_csv(
            &vpath.display().to_string(),
            &vtext,
            &fpath.display().to_string(),
            &ftext,
            unit,
        )
    }

    /// The vertex/facet CSV pair as texts, as [`Mesh::read_vertex_facet_csv`] reads files
    /// holding them (`vname`, `fname` name them in errors).
    pub fn parse_vertex_facet_csv(
        vname: &str,
        vtext: &str,
        fname: &str,
        ftext: &str,
        unit: LengthUnit,
    ) -> Result<Self, MeshError> {
        let parse_error = |path: &str, line: usize, message: String| MeshError::Parse {
            path: path.to_string(),
            line,
            message,
        };
        let scale = unit.metres();
        let mut mesh = Mesh::default();
        for (k, line) in vtext.lines().enumerate() {
            if line.trim().is_empty() {
                continue;
            }
            let fields: Vec<&str> = line.split(',').map(str::trim).collect();
            if fields.len() < 4 {
                return Err(parse_error(
                    vname,
                    k + 1,
                    format!("expected `filler,x,y,z`, got {line:?}"),
                ));
            }
            let mut xyz = [0.0; 3];
            for (i, x) in xyz.iter_mut().enumerate() {
                *x = fields[i + 1].parse().map_err(|e| {
                    parse_error(vname, k + 1, format!("coordinate {:?}: {e}", fields[i + 1]))
                })?;
            }
            mesh.vertices.push(Vec3::from(xyz) * scale);
        }
        for (k, line) in ftext.lines().enumerate() {
            if line.trim().is_empty() {
                continue;
            }
            let fields: Vec<&str> = line.split(',').map(str::trim).collect();
            if fields.len() < 3 || fields[3..].iter().any(|f| !f.is_empty()) {
                return Err(parse_error(
                    fname,
                    k + 1,
                    format!("expected a triangle `i,j,k,,`, got {line:?}"),
                ));
            }
            let mut face = [0usize; 3];
            for (i, v) in face.iter_mut().enumerate() {
                let one_based: usize = fields[i].parse().map_err(|e| {
                    parse_error(fname, k + 1, format!("vertex index {:?}: {e}", fields[i]))
                })?;
                if one_based == 0 {
                    return Err(parse_error(
                        fname,
                        k + 1,
                        "vertex indices are 1-based; got 0".into(),
                    ));
                }
                *v = one_based - 1;
            }
            mesh.faces.push(face);
        }
        Ok(mesh)
    }

    /// The axis-aligned cube of side `side` centred at the origin (12 faces).
    pub fn cube(side: Real) -> Self {
        let h = side / 2.0;
        let vertices = (0..8)
            .map(|k| {
                Vec3::new(
                    if k & 1 == 0 { -h } else { h },
                    if k & 2 == 0 { -h } else { h },
                    if k & 4 == 0 { -h } else { h },
                )
            })
            .collect();
        // Each square face split along a diagonal, counter-clockwise seen from outside.
        let quads = [
            [0, 2, 3, 1], // z = −h
            [4, 5, 7, 6], // z = +h
            [0, 1, 5, 4], // y = −h
            [2, 6, 7, 3], // y = +h
            [0, 4, 6, 2], // x = −h
            [1, 3, 7, 5], // x = +h
        ];
        let faces = quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        Mesh { vertices, faces }
    }

    /// The octahedron with vertices at ±`a`, ±`b`, ±`c` on the x, y, z axes (8 faces).
    pub fn octahedron(a: Real, b: Real, c: Real) -> Self {
        let vertices = vec![
            Vec3::new(a, 0.0, 0.0),
            Vec3::new(-a, 0.0, 0.0),
            Vec3::new(0.0, b, 0.0),
            Vec3::new(0.0, -b, 0.0),
            Vec3::new(0.0, 0.0, c),
            Vec3::new(0.0, 0.0, -c),
        ];
        let mut faces = Vec::new();
        for (x, sx) in [(0, 1.0), (1, -1.0)] {
            for (y, sy) in [(2, 1.0), (3, -1.0)] {
                for (z, sz) in [(4, 1.0), (5, -1.0)] {
                    // (x, y, z) is counter-clockwise from outside when the octant's sign
                    // product is positive.
                    if sx * sy * sz > 0.0 {
                        faces.push([x, y, z]);
                    } else {
                        faces.push([x, z, y]);
                    }
                }
            }
        }
        Mesh { vertices, faces }
    }

    /// A triangulated ellipsoid with semi-axes `a`, `b`, `c` inscribed in it (vertices on its
    /// surface): the icosahedron subdivided `levels` times (20·4^levels faces), projected to
    /// the unit sphere and stretched.
    pub fn ellipsoid(a: Real, b: Real, c: Real, levels: u32) -> Self {
        let t = (1.0 + 5f64.sqrt()) / 2.0;
        let mut vertices: Vec<Vec3> = [
            [-1.0, t, 0.0],
            [1.0, t, 0.0],
            [-1.0, -t, 0.0],
            [1.0, -t, 0.0],
            [0.0, -1.0, t],
            [0.0, 1.0, t],
            [0.0, -1.0, -t],
            [0.0, 1.0, -t],
            [t, 0.0, -1.0],
            [t, 0.0, 1.0],
            [-t, 0.0, -1.0],
            [-t, 0.0, 1.0],
        ]
        .iter()
        .map(|p| Vec3::from(*p).normalize())
        .collect();
        let mut faces: Vec<[usize; 3]> = vec![
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        for _ in 0..levels {
            let mut midpoints = std::collections::HashMap::new();
            let mut midpoint = |i: usize, j: usize, vertices: &mut Vec<Vec3>| {
                *midpoints.entry((i.min(j), i.max(j))).or_insert_with(|| {
                    vertices.push(((vertices[i] + vertices[j]) * 0.5).normalize());
                    vertices.len() - 1
                })
            };
            let mut next = Vec::with_capacity(faces.len() * 4);
            for &[i, j, k] in &faces {
                let ij = midpoint(i, j, &mut vertices);
                let jk = midpoint(j, k, &mut vertices);
                let ki = midpoint(k, i, &mut vertices);
                next.extend([[i, ij, ki], [j, jk, ij], [k, ki, jk], [ij, jk, ki]]);
            }
            faces = next;
        }
        for v in &mut vertices {
            *v = Vec3::new(v.x * a, v.y * b, v.z * c);
        }
        Mesh { vertices, faces }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn obj_text_errors_name_the_line() {
        let e = Mesh::parse_obj("m.obj", "v 0 0 0\nv 1 x 0\n", LengthUnit::Metres).unwrap_err();
        assert!(
            e.to_string().starts_with("m.obj:2: coordinate \"x\""),
            "{e}"
        );
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3 4\n";
        let e = Mesh::parse_obj("m.obj", text, LengthUnit::Metres).unwrap_err();
        assert!(e.to_string().contains("face 0 has 4 corners"), "{e}");
        let e = Mesh::parse_obj("m.obj", "v 0 0 0\nf 1 0 2\n", LengthUnit::Metres).unwrap_err();
        assert!(
            e.to_string().starts_with("m.obj:2: vertex index \"0\""),
            "{e}"
        );
    }

    #[test]
    fn csv_text_errors_name_the_file_and_line() {
        let e = Mesh::parse_vertex_facet_csv("v.csv", "0,1,2\n", "f.csv", "", LengthUnit::Metres)
            .unwrap_err();
        assert!(
            e.to_string()
                .starts_with("v.csv:1: expected `filler,x,y,z`"),
            "{e}"
        );
        let e = Mesh::parse_vertex_facet_csv(
            "v.csv",
            "0,0,0,0\n0,1,0,0\n0,0,1,0\n",
            "f.csv",
            "1,2,3,,\n0,1,2,,\n",
            LengthUnit::Metres,
        )
        .unwrap_err();
        assert!(
            e.to_string()
                .starts_with("f.csv:2: vertex indices are 1-based"),
            "{e}"
        );
    }

    #[test]
    fn obj_text_in_kilometres() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let mesh = Mesh::parse_obj("t.obj", text, LengthUnit::Kilometres).unwrap();
        assert_eq!(mesh.vertices[1], Vec3::new(1000.0, 0.0, 0.0));
        assert_eq!(mesh.faces, vec![[0, 1, 2]]);
    }
}
