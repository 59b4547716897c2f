//! Triangle soups from files into [`Mesh`]es, the same way for every format.
//!
//! Vertices at the same position are welded and each connected component becomes one of
//! the mesh's convex pieces (the plausibility checks of `articulated::check` take the hull of
//! each piece): an asset built from separate closed solids gets exact checks, and any
//! other mesh still gets a conservative one. Vertices are numbered by first use, component
//! by component, so that one shape gives one mesh whichever file format or index layout
//! it came in.

use std::collections::HashMap;

use pairs::math::Point3;

use super::ImportError;
use articulated::mesh::Mesh;

/// A mesh from positions and triangles (indices into `positions`); `item` names the link
/// or file in errors. Triangles with a repeated corner are dropped.
pub fn build_mesh(
    item: &str,
    positions: &[Point3],
    triangles: &[[u32; 3]],
) -> Result<Mesh, ImportError> {
    let non_finite = || ImportError::NonFinite { item: item.into(), field: "vertex" };
    // Weld by exact position: the first vertex at a position stands for all of them.
    let mut first_at: HashMap<[u32; 3], u32> = HashMap::new();
    let mut welded = Vec::with_capacity(positions.len());
    for (i, p) in positions.iter().enumerate() {
        if !p.coords.iter().all(|c| c.is_finite()) {
            return Err(non_finite());
        }
        welded.push(*first_at.entry(p.coords.map(f32::to_bits).into()).or_insert(i as u32));
    }
    let mut soup = Vec::with_capacity(triangles.len());
    for t in triangles {
        let Some(w) =
            t.iter().map(|&i| welded.get(i as usize).copied()).collect::<Option<Vec<_>>>()
        else {
            return Err(ImportError::MeshFile {
                link: item.into(),
                file: item.into(),
                reason: "a triangle index is out of range".into(),
            });
        };
        if w[0] != w[1] && w[1] != w[2] && w[0] != w[2] {
            soup.push([w[0], w[1], w[2]]);
        }
    }
    if soup.is_empty() {
        return Err(ImportError::EmptyMesh { link: item.into() });
    }
    let component = components(positions.len(), &soup);
    // Components in order of their first triangle, vertices in order of first use.
    let mut seen_component: HashMap<u32, usize> = HashMap::new();
    for t in &soup {
        let c = component[t[0] as usize];
        let next = seen_component.len();
        seen_component.entry(c).or_insert(next);
    }
    let mut by_component: Vec<Vec<u32>> = vec![Vec::new(); seen_component.len()];
    let mut placed = vec![false; positions.len()];
    for t in &soup {
        for &v in t {
            if !std::mem::replace(&mut placed[v as usize], true) {
                by_component[seen_component[&component[v as usize]]].push(v);
            }
        }
    }
    let mut new_index = vec![0u32; positions.len()];
    let mut mesh = Mesh::default();
    for vertices in by_component {
        mesh.pieces.push(mesh.vertices.len() as u32);
        for v in vertices {
            new_index[v as usize] = mesh.vertices.len() as u32;
            mesh.vertices.push(positions[v as usize]);
        }
    }
    mesh.triangles = soup.iter().map(|t| t.map(|v| new_index[v as usize])).collect();
    Ok(mesh)
}

/// Connected component (a representative vertex) of every vertex, by union-find.
fn components(n: usize, triangles: &[[u32; 3]]) -> Vec<u32> {
    let mut parent: Vec<u32> = (0..n as u32).collect();
    fn find(parent: &mut [u32], mut v: u32) -> u32 {
        while parent[v as usize] != v {
            let up = parent[parent[v as usize] as usize];
            parent[v as usize] = up;
            v = up;
        }
        v
    }
    for t in triangles {
        let a = find(&mut parent, t[0]);
        for &v in &t[1..] {
            let b = find(&mut parent, v);
            if a != b {
                parent[b as usize] = a;
            }
        }
    }
    (0..n as u32).map(|v| find(&mut parent, v)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn separate_solids_become_pieces_and_duplicates_are_welded() {
        let a = Mesh::cuboid(Point3::origin(), Point3::new(1.0, 1.0, 1.0));
        let b = Mesh::cuboid(Point3::new(2.0, 0.0, 0.0), Point3::new(3.0, 1.0, 1.0));
        let both = Mesh::union([a, b]);
        // A soup with every triangle's corners duplicated, as an STL file has them.
        let positions: Vec<Point3> =
            both.triangles.iter().flat_map(|t| t.map(|i| both.vertices[i as usize])).collect();
        let triangles: Vec<[u32; 3]> =
            (0..both.triangles.len() as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
        let soup = build_mesh("t", &positions, &triangles).expect("mesh");
        let indexed = build_mesh("t", &both.vertices, &both.triangles).expect("mesh");
        assert_eq!(soup, indexed);
        assert_eq!(soup.convex_pieces().count(), 2);
        assert_eq!(soup.vertices.len(), 16);
    }

    #[test]
    fn bad_soups_are_errors() {
        let p = [Point3::origin(), Point3::new(1.0, 0.0, 0.0), Point3::new(f32::NAN, 0.0, 0.0)];
        assert!(matches!(build_mesh("t", &p, &[[0, 1, 2]]), Err(ImportError::NonFinite { .. })));
        assert!(matches!(
            build_mesh("t", &p[..2], &[[0, 1, 1]]),
            Err(ImportError::EmptyMesh { .. })
        ));
        assert!(matches!(
            build_mesh("t", &p[..2], &[[0, 1, 7]]),
            Err(ImportError::MeshFile { .. })
        ));
    }
}
