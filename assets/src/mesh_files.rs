//! Mesh files: OBJ (every group, or the groups kept apart) and STL (ASCII or binary).

use std::io::Cursor;
use std::path::Path;

use pairs::math::Point3;

use super::mesh_build::build_mesh;
use super::surface::{self, Surface};
use super::{text, ImportError};
use articulated::mesh::Mesh;

/// Triangles of one OBJ group (or object): its name, positions and triangles.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjGroup {
    /// The `g` or `o` name (`unnamed_object` when the file has none).
    pub name: String,
    /// Vertex positions.
    pub positions: Vec<Point3>,
    /// Triangles, indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
    /// The triangles' corners, texture coordinates and materials (`mtllib`), for renders.
    pub surface: Surface,
}

/// The groups of an OBJ text that have faces, in order of first appearance; a group that
/// appears twice (split by `usemtl` or repeated `g` lines) is one group. Polygons are fanned
/// into triangles; points and lines are ignored. `mtllib` files (beside `path`) and their
/// `map_Kd` textures are read for the groups' surfaces; one that cannot be read is logged
/// and left out.
pub fn parse_obj(path: &Path, text: &str) -> Result<Vec<ObjGroup>, ImportError> {
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let warned = std::cell::RefCell::new(Vec::new());
    let (models, materials) = tobj::load_obj_buf(&mut Cursor::new(text), &options, |mtl| {
        surface::load_mtl(path, mtl, &mut |w| warned.borrow_mut().push(w))
    })
    .map_err(|e| ImportError::Parse {
        path: path.into(),
        format: "OBJ",
        reason: e.to_string(),
    })?;
    let mut warnings = warned.into_inner();
    let materials = match materials {
        Ok(m) => surface::materials(path, &m, &mut |w| warnings.push(w)),
        Err(_) => Vec::new(),
    };
    for w in warnings {
        tracing::warn!("{}: materials: {w}", path.display());
    }
    let mut groups: Vec<ObjGroup> = Vec::new();
    for model in models {
        let mesh = model.mesh;
        if mesh.indices.is_empty() {
            continue;
        }
        let index = match groups.iter().position(|g| g.name == model.name) {
            Some(i) => i,
            None => {
                groups.push(ObjGroup {
                    name: model.name,
                    positions: Vec::new(),
                    triangles: Vec::new(),
                    surface: Surface::default(),
                });
                groups.len() - 1
            }
        };
        let group = &mut groups[index];
        let offset = group.positions.len() as u32;
        let positions: Vec<Point3> =
            mesh.positions.chunks_exact(3).map(|c| Point3::new(c[0], c[1], c[2])).collect();
        let material = mesh.material_id.and_then(|m| materials.get(m).cloned());
        for t in mesh.indices.chunks_exact(3) {
            let Some(corners) =
                t.iter().map(|&i| positions.get(i as usize).copied()).collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            group.surface.corners.push([corners[0], corners[1], corners[2]]);
            group.surface.uv.push(surface::corner_uv(&mesh.texcoords, t));
            group.surface.material.push(material.clone());
        }
        group.positions.extend(positions);
        group.triangles.extend(
            mesh.indices.chunks_exact(3).map(|t| [t[0] + offset, t[1] + offset, t[2] + offset]),
        );
    }
    Ok(groups)
}

/// The mesh of a mesh file referenced by `link` (OBJ, every group merged, or STL) and its
/// surface (materials from an OBJ's `mtllib`; none for STL). Any other format, and any
/// unreadable file, is an error naming the link and the file.
pub fn read_mesh_file(link: &str, path: &Path) -> Result<(Mesh, Surface), ImportError> {
    let fail =
        |reason: String| ImportError::MeshFile { link: link.into(), file: path.into(), reason };
    let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    let bytes = std::fs::read(path).map_err(|e| fail(e.to_string()))?;
    let (positions, triangles, surface) = match extension.as_str() {
        "obj" => {
            let text = text::utf8(path, bytes).map_err(|e| fail(e.to_string()))?;
            let groups = parse_obj(path, &text).map_err(|e| fail(e.to_string()))?;
            merge_groups(groups)
        }
        "stl" => {
            let (positions, triangles) = read_stl(&bytes).map_err(fail)?;
            let surface = Surface::plain(&positions, &triangles);
            (positions, triangles, surface)
        }
        other => {
            return Err(fail(format!(
                "format {other:?} is not supported; convert the mesh to OBJ or STL"
            )))
        }
    };
    let mesh = build_mesh(link, &positions, &triangles).map_err(|e| match e {
        ImportError::EmptyMesh { .. } => fail("the file has no triangles".into()),
        other => other,
    })?;
    Ok((mesh, surface))
}

/// All groups of an OBJ as one triangle soup, and their surfaces as one.
fn merge_groups(groups: Vec<ObjGroup>) -> (Vec<Point3>, Vec<[u32; 3]>, Surface) {
    let (mut positions, mut triangles, mut surface) = (Vec::new(), Vec::new(), Surface::default());
    for g in groups {
        let offset = positions.len() as u32;
        positions.extend(g.positions);
        triangles.extend(g.triangles.into_iter().map(|t| t.map(|i| i + offset)));
        surface.append(g.surface);
    }
    (positions, triangles, surface)
}

/// An STL file (ASCII or binary) as positions and triangles.
pub fn read_stl(bytes: &[u8]) -> Result<(Vec<Point3>, Vec<[u32; 3]>), String> {
    let mesh =
        stl_io::read_stl(&mut Cursor::new(bytes)).map_err(|e| format!("not valid STL: {e}"))?;
    let positions = mesh.vertices.iter().map(|v| Point3::new(v[0], v[1], v[2])).collect();
    let mut triangles = Vec::with_capacity(mesh.faces.len());
    for f in &mesh.faces {
        let t = f.vertices.map(|i| u32::try_from(i).unwrap_or(u32::MAX));
        triangles.push(t);
    }
    Ok((positions, triangles))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn binary_and_ascii_stl_give_one_mesh() {
        let corners = [[0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
        let faces = [[0usize, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let mut ascii = String::from("solid t\n");
        let mut binary = vec![0u8; 80];
        binary.extend((faces.len() as u32).to_le_bytes());
        for f in faces {
            ascii.push_str("facet normal 0 0 0\nouter loop\n");
            binary.extend([0u8; 12]);
            for v in f {
                let [x, y, z] = corners[v];
                ascii.push_str(&format!("vertex {x} {y} {z}\n"));
                [x, y, z].iter().for_each(|c| binary.extend(c.to_le_bytes()));
            }
            ascii.push_str("endloop\nendfacet\n");
            binary.extend([0u8; 2]);
        }
        ascii.push_str("endsolid t\n");
        let (a, b) =
            (read_stl(ascii.as_bytes()).expect("ascii"), read_stl(&binary).expect("binary"));
        assert_eq!(a, b);
        let mesh = build_mesh("t", &a.0, &a.1).expect("mesh");
        assert_eq!((mesh.vertices.len(), mesh.triangles.len()), (4, 4));
        assert!(read_stl(&binary[..100]).is_err(), "a cut file is an error");
    }

    #[test]
    fn obj_groups_split_by_usemtl_are_one_part() {
        let text = "g a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl x\nf 1 2 3\nusemtl y\nf 1 2 4\ng b\nf 2 3 4\n";
        let groups = parse_obj(Path::new("t.obj"), text).expect("obj");
        let names: Vec<_> = groups.iter().map(|g| (g.name.as_str(), g.triangles.len())).collect();
        assert_eq!(names, [("a", 2), ("b", 1)]);
    }
}
