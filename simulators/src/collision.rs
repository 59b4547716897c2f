//! Collision geometry for an exported link: a set of convex hulls that follows the link's
//! mesh, within a budget (hulls per link, vertices per hull), and how well it fits.
//!
//! Simulators (MuJoCo, PyBullet, SAPIEN, PhysX) collide a mesh through its convex hull, so
//! a link's visual mesh as its collision makes a cabinet a solid block. Instead:
//! - each of the mesh's pieces ([`Mesh::pieces`]: the convex primitives a built-in object
//!   is made of, or the connected components of an asset's mesh) that is closed and convex
//!   (its hull's volume within [`CONVEX_TOLERANCE`] of its own) is its hull;
//! - a closed piece that is not convex is decomposed with parry's V-HACD
//!   ([`parry3d::transformation::vhacd`], resolution [`VHACD_RESOLUTION`], concavity
//!   [`VHACD_CONCAVITY`]), each part hulled from the piece's own triangles;
//! - an open or non-manifold piece (no inside to decompose) falls back to its hull, and a
//!   flat one (no volume) to its hull thickened by [`FLAT_THICKNESS`]; either is noted.
//!
//! Then, while the link has more hulls than [`Budget::max_hulls`], the two hulls whose
//! merged hull adds the least volume are merged; a hull with more than
//! [`Budget::max_vertices`] vertices keeps the farthest-point subset of that many (so it
//! shrinks slightly, never grows). Everything is deterministic: same mesh, same hulls.

use std::collections::BTreeMap;

use pairs::math::{Point3, Real};
use pairs::sampling::farthest_point_sampling;
use parry3d::transformation::try_convex_hull;
use parry3d::transformation::vhacd::{VHACDParameters, VHACD};
use serde::Serialize;

use crate::fit::{fit, Fit, Solid};

use articulated::mesh::Mesh;

/// A piece whose hull's volume exceeds its own by at most this fraction is convex.
pub const CONVEX_TOLERANCE: f64 = 0.02;
/// V-HACD's voxel resolution (voxels along the longest side) for a non-convex piece: 128
/// fits thin walls more closely than parry's default 64 (measured in docs/SIMULATORS.md).
pub const VHACD_RESOLUTION: u32 = 128;
/// V-HACD's concavity threshold for a non-convex piece.
pub const VHACD_CONCAVITY: Real = 0.01;
/// Most surface samples per direction when measuring the fit (a large asset mesh is
/// sampled at an even stride).
pub const MAX_SAMPLES: usize = 20_000;
/// Thickness given to a flat piece's hull, in object units (metres for the built-in
/// categories, which are modelled at real-world sizes).
pub const FLAT_THICKNESS: Real = 2e-3;

/// How much collision geometry a link may have.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Budget {
    /// Convex hulls per link.
    pub max_hulls: usize,
    /// Vertices per hull (PhysX's GPU pipeline takes at most 64, and 64 polygons).
    pub max_vertices: usize,
}

impl Default for Budget {
    fn default() -> Self {
        Self { max_hulls: 32, max_vertices: 64 }
    }
}

/// One convex hull: its vertices (rest frame) and outward triangles.
#[derive(Debug, Clone, PartialEq)]
pub struct Hull {
    /// Vertices.
    pub vertices: Vec<Point3>,
    /// Triangles, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

impl Hull {
    /// The hull of `points`, or `None` when they span no volume.
    fn of(points: &[Point3]) -> Option<Self> {
        if points.len() < 4 {
            return None;
        }
        let (vertices, triangles) = try_convex_hull(points).ok()?;
        let hull = Self { vertices, triangles };
        (hull.volume() > 0.0).then_some(hull)
    }

    /// Its volume.
    pub fn volume(&self) -> f64 {
        signed_volume(&self.vertices, &self.triangles)
    }

    /// Distance from `p` to the solid hull (zero inside); see [`Solid`].
    pub fn distance(&self, p: &Point3) -> Real {
        Solid::new(self).distance(p)
    }
}

/// A link's collision geometry.
#[derive(Debug, Clone)]
pub struct LinkCollision {
    /// The hulls.
    pub hulls: Vec<Hull>,
    /// How well they fit.
    pub fit: Fit,
    /// Whether every piece of the mesh is closed (watertight, consistently oriented), so
    /// that it encloses a well-defined solid.
    pub closed: bool,
    /// What fell back to a plain hull, and why (empty when nothing did).
    pub notes: Vec<String>,
}

/// The collision geometry of a link's `mesh` within `budget`.
pub fn decompose(mesh: &Mesh, budget: Budget) -> LinkCollision {
    let mut notes = Vec::new();
    let mut hulls = Vec::new();
    let mut closed = true;
    // An open piece encloses no volume of its own: only closed pieces count.
    let mut visual_volume = 0.0;
    for (k, (vertices, triangles)) in pieces(mesh).into_iter().enumerate() {
        let piece_closed = is_closed(&vertices, &triangles);
        let own = signed_volume(&vertices, &triangles).abs();
        closed &= piece_closed;
        if piece_closed {
            visual_volume += own;
        }
        hulls.extend(piece_hulls(
            k,
            &vertices,
            &triangles,
            piece_closed.then_some(own),
            &mut notes,
        ));
    }
    if hulls.is_empty() {
        // Only possible for a mesh without vertices; the importer refuses those.
        notes.push("the mesh has no volume and no extent: no collision hull".into());
    }
    let mut hulls = merge_to(hulls, budget.max_hulls.max(1));
    for hull in &mut hulls {
        if hull.vertices.len() > budget.max_vertices.max(4) {
            if let Some(fewer) = Hull::of(&farthest_points(&hull.vertices, budget.max_vertices)) {
                *hull = fewer;
            }
        }
    }
    let fit = fit(mesh, visual_volume, &hulls);
    LinkCollision { hulls, fit, closed, notes }
}

/// Each piece's vertices and triangles (indices into its own vertices).
fn pieces(mesh: &Mesh) -> Vec<(Vec<Point3>, Vec<[u32; 3]>)> {
    let starts: Vec<u32> = if mesh.pieces.is_empty() { vec![0] } else { mesh.pieces.clone() };
    let piece_of = |v: u32| starts.partition_point(|&s| s <= v) - 1;
    let mut out: Vec<(Vec<Point3>, Vec<[u32; 3]>)> = starts
        .iter()
        .enumerate()
        .map(|(i, &s)| {
            let end = starts.get(i + 1).map_or(mesh.vertices.len(), |&e| e as usize);
            (mesh.vertices[s as usize..end].to_vec(), Vec::new())
        })
        .collect();
    for t in &mesh.triangles {
        let p = piece_of(t[0]);
        let s = starts[p];
        // A triangle across pieces (never made by the generator) stays with its first corner's.
        if t.iter().all(|&v| piece_of(v) == p) {
            out[p].1.push(t.map(|v| v - s));
        }
    }
    out
}

/// The hulls of piece `k`, noting any fallback; `closed_volume` is the piece's volume when
/// it is closed, `None` when it is open or non-manifold.
fn piece_hulls(
    k: usize,
    vertices: &[Point3],
    triangles: &[[u32; 3]],
    closed_volume: Option<f64>,
    notes: &mut Vec<String>,
) -> Vec<Hull> {
    let Some(hull) = Hull::of(vertices) else {
        let thick = thickened(vertices);
        if !thick.is_empty() {
            notes.push(format!("piece {k} is flat: its hull is thickened to {FLAT_THICKNESS}"));
        }
        return thick;
    };
    let Some(own) = closed_volume else {
        notes.push(format!("piece {k} is open or non-manifold: its convex hull stands in for it"));
        return vec![hull];
    };
    if hull.volume() <= own * (1.0 + CONVEX_TOLERANCE) {
        return vec![hull];
    }
    let parameters = VHACDParameters {
        resolution: VHACD_RESOLUTION,
        concavity: VHACD_CONCAVITY,
        ..VHACDParameters::default()
    };
    let parts = std::panic::catch_unwind(|| {
        VHACD::decompose(&parameters, vertices, triangles, true)
            .compute_exact_convex_hulls(vertices, triangles)
    });
    let hulls: Vec<Hull> = match parts {
        Ok(parts) => parts.iter().filter_map(|(points, _)| Hull::of(points)).collect(),
        Err(_) => Vec::new(),
    };
    if hulls.is_empty() {
        notes.push(format!("V-HACD found no parts in piece {k}: its convex hull stands in"));
        return vec![hull];
    }
    hulls
}

/// The hull of a flat set of points (or of a segment), thickened by [`FLAT_THICKNESS`]
/// across it; empty for a set with no extent at all.
fn thickened(points: &[Point3]) -> Vec<Hull> {
    use pairs::math::{perpendicular, try_unit};
    let Some(&first) = points.first() else { return Vec::new() };
    let span = |p: &&Point3| (*p - first).norm();
    let Some(far) = points.iter().max_by(|a, b| span(a).total_cmp(&span(b))) else {
        return Vec::new();
    };
    let Some(along) = try_unit(&(far - first)) else { return Vec::new() };
    // The normal of the plane, or any direction across a segment.
    let normal = points
        .iter()
        .map(|p| along.cross(&(p - first)))
        .max_by(|a, b| a.norm().total_cmp(&b.norm()))
        .and_then(|n| try_unit(&n))
        .unwrap_or_else(|| perpendicular(&along));
    let side = normal.cross(&along);
    let h = FLAT_THICKNESS * 0.5;
    let slab: Vec<Point3> = points.iter().flat_map(|p| [p - normal * h, p + normal * h]).collect();
    let wide: Vec<Point3> = slab.iter().flat_map(|p| [p - side * h, p + side * h]).collect();
    Hull::of(&slab).or_else(|| Hull::of(&wide)).into_iter().collect()
}

/// Whether every edge of `triangles` is used once in each direction (closed, consistently
/// oriented, manifold), after welding vertices at the same position.
fn is_closed(vertices: &[Point3], triangles: &[[u32; 3]]) -> bool {
    let mut id: BTreeMap<[u32; 3], u32> = BTreeMap::new();
    let welded: Vec<u32> = vertices
        .iter()
        .map(|p| {
            let next = id.len() as u32;
            *id.entry(p.coords.map(f32::to_bits).into()).or_insert(next)
        })
        .collect();
    let mut edges: BTreeMap<(u32, u32), i32> = BTreeMap::new();
    for t in triangles {
        let w = t.map(|v| welded[v as usize]);
        for (a, b) in [(w[0], w[1]), (w[1], w[2]), (w[2], w[0])] {
            if a == b {
                continue;
            }
            let (key, sign) = if a < b { ((a, b), 1) } else { ((b, a), -1) };
            *edges.entry(key).or_insert(0) += sign;
        }
    }
    // Closed and oriented: each undirected edge's two uses cancel.
    !edges.is_empty() && edges.values().all(|&s| s == 0)
}

/// Signed volume enclosed by triangles (positive when they face outwards).
pub fn signed_volume(vertices: &[Point3], triangles: &[[u32; 3]]) -> f64 {
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| vertices[i as usize].coords.cast::<f64>());
            a.dot(&b.cross(&c)) / 6.0
        })
        .sum()
}

/// Merges hulls, cheapest first (least added volume), until at most `max` remain.
fn merge_to(mut hulls: Vec<Hull>, max: usize) -> Vec<Hull> {
    if hulls.len() <= max {
        return hulls;
    }
    let cost = |a: &Hull, b: &Hull| -> Option<(f64, Hull)> {
        let mut points = a.vertices.clone();
        points.extend_from_slice(&b.vertices);
        let merged = Hull::of(&points)?;
        Some((merged.volume() - a.volume() - b.volume(), merged))
    };
    // Costs of every pair, kept up to date as hulls merge (hulls are few: a link has tens
    // of pieces, a budget tens of hulls).
    let mut pairs: BTreeMap<(usize, usize), (f64, Hull)> = BTreeMap::new();
    let mut alive: Vec<bool> = vec![true; hulls.len()];
    for i in 0..hulls.len() {
        for j in i + 1..hulls.len() {
            if let Some(c) = cost(&hulls[i], &hulls[j]) {
                pairs.insert((i, j), c);
            }
        }
    }
    let mut count = hulls.len();
    while count > max {
        let Some((&(i, j), _)) =
            pairs.iter().min_by(|a, b| a.1 .0.total_cmp(&b.1 .0).then(a.0.cmp(b.0)))
        else {
            break;
        };
        let (_, merged) = pairs.remove(&(i, j)).expect("the pair was just found");
        pairs.retain(|&(a, b), _| a != i && b != i && a != j && b != j);
        alive[i] = false;
        alive[j] = false;
        let n = hulls.len();
        hulls.push(merged);
        alive.push(true);
        for k in 0..n {
            if alive[k] {
                if let Some(c) = cost(&hulls[k], &hulls[n]) {
                    pairs.insert((k, n), c);
                }
            }
        }
        count -= 1;
    }
    hulls.into_iter().zip(alive).filter_map(|(h, a)| a.then_some(h)).collect()
}

/// `count` of `points` spread as far apart as possible: farthest point sampling
/// ([`pairs::sampling`]) from the first point with the lowest coordinates.
fn farthest_points(points: &[Point3], count: usize) -> Vec<Point3> {
    let Some(start) = (0..points.len()).min_by(|&a, &b| {
        let key = |p: &Point3| [p.x, p.y, p.z];
        key(&points[a]).partial_cmp(&key(&points[b])).unwrap_or(std::cmp::Ordering::Equal)
    }) else {
        return Vec::new();
    };
    farthest_point_sampling(points, count, start).into_iter().map(|i| points[i]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn corner(x: Real, y: Real, z: Real) -> Point3 {
        Point3::new(x, y, z)
    }

    #[test]
    fn hull_distances_are_exact() {
        // A thin 1.6 cm slab (a scissors blade's piece): its own corners are on it, a point
        // 1 cm above its top is 1 cm away, its centre is inside.
        let mesh = Mesh::cuboid(corner(0.0, 0.0, 0.0), corner(0.016, 0.006, 0.004));
        let hull = Hull::of(&mesh.vertices).expect("a hull");
        for v in &mesh.vertices {
            assert!(hull.distance(v) < 1e-7, "{v:?}: {}", hull.distance(v));
        }
        assert!((hull.distance(&corner(0.008, 0.016, 0.002)) - 0.01).abs() < 1e-6);
        assert!((hull.distance(&corner(0.026, 0.016, 0.002)) - 0.01 * 2f32.sqrt()).abs() < 1e-6);
        assert_eq!(hull.distance(&corner(0.008, 0.003, 0.002)), 0.0);
    }

    #[test]
    fn a_box_is_its_own_hull() {
        let mesh = Mesh::cuboid(corner(0.0, 0.0, 0.0), corner(1.0, 2.0, 3.0));
        let c = decompose(&mesh, Budget::default());
        assert_eq!(c.hulls.len(), 1);
        assert!(c.notes.is_empty(), "{:?}", c.notes);
        assert!((c.fit.hull_volume - 6.0).abs() < 1e-5, "{:?}", c.fit);
        assert!((c.fit.visual_volume - 6.0).abs() < 1e-5, "{:?}", c.fit);
        assert!(c.fit.hausdorff < 1e-6, "{:?}", c.fit);
    }

    /// An open-topped box of five walls (a container): five hulls, no hull spans the inside.
    fn open_box() -> Mesh {
        let t = 0.05;
        Mesh::union([
            Mesh::cuboid(corner(0.0, 0.0, 0.0), corner(1.0, t, 1.0)),
            Mesh::cuboid(corner(0.0, 0.0, 0.0), corner(t, 1.0, 1.0)),
            Mesh::cuboid(corner(1.0 - t, 0.0, 0.0), corner(1.0, 1.0, 1.0)),
            Mesh::cuboid(corner(0.0, 0.0, 0.0), corner(1.0, 1.0, t)),
            Mesh::cuboid(corner(0.0, 0.0, 1.0 - t), corner(1.0, 1.0, 1.0)),
        ])
    }

    #[test]
    fn a_container_keeps_its_inside_free() {
        let c = decompose(&open_box(), Budget::default());
        assert_eq!(c.hulls.len(), 5);
        let centre = corner(0.5, 0.5, 0.5);
        for h in &c.hulls {
            assert!(h.distance(&centre) > 0.4);
        }
        assert!(c.fit.hausdorff < 1e-6);
    }

    #[test]
    fn the_budget_merges_the_cheapest_hulls_and_caps_vertices() {
        let c = decompose(&open_box(), Budget { max_hulls: 3, max_vertices: 64 });
        assert_eq!(c.hulls.len(), 3);
        assert!(c.fit.hull_volume >= c.fit.visual_volume * 0.99, "{:?}", c.fit);
        let sphere = Mesh::sphere(corner(0.0, 0.0, 0.0), 1.0, 24);
        assert!(sphere.vertices.len() > 100);
        let c = decompose(&sphere, Budget { max_hulls: 4, max_vertices: 20 });
        assert_eq!(c.hulls.len(), 1);
        assert!(c.hulls[0].vertices.len() <= 20);
        // Fewer vertices: inside the sphere, and within the Hausdorff distance reported.
        assert!(c.fit.hull_volume < c.fit.visual_volume);
        assert!(c.fit.hausdorff > 0.0 && c.fit.hausdorff < 0.5, "{:?}", c.fit);
    }

    #[test]
    fn a_non_convex_closed_piece_is_decomposed() {
        // One connected, closed L-shaped solid (an asset's component): two hulls or more,
        // and far less volume than its hull.
        let l = [(0.0, 0.0), (2.0, 0.0), (2.0, 0.5), (0.5, 0.5), (0.5, 2.0), (0.0, 2.0)];
        let mut vertices = Vec::new();
        for z in [0.0, 1.0] {
            vertices.extend(l.iter().map(|&(x, y)| corner(x, y, z)));
        }
        let mut triangles: Vec<[u32; 3]> = Vec::new();
        // Bottom (facing -z) and top (+z) as fans over a convex split of the L.
        for (a, b, c) in [(0, 2, 1), (0, 3, 2), (0, 5, 4), (0, 4, 3)] {
            triangles.push([a, b, c]);
            triangles.push([a + 6, c + 6, b + 6]);
        }
        for i in 0..6u32 {
            let j = (i + 1) % 6;
            triangles.push([i, j, j + 6]);
            triangles.push([i, j + 6, i + 6]);
        }
        let mesh = Mesh { vertices, triangles, pieces: vec![0] };
        assert!(is_closed(&mesh.vertices, &mesh.triangles));
        assert!((signed_volume(&mesh.vertices, &mesh.triangles) - 1.75).abs() < 1e-6);
        let c = decompose(&mesh, Budget::default());
        assert!(c.notes.is_empty(), "{:?}", c.notes);
        assert!(c.hulls.len() >= 2, "{}", c.hulls.len());
        assert!(c.fit.hull_volume < 2.5, "{:?}", c.fit);
        // V-HACD is deterministic: the same mesh gives the same hulls.
        assert_eq!(decompose(&mesh, Budget::default()).hulls, c.hulls);
    }

    #[test]
    fn open_and_flat_pieces_fall_back_to_a_hull_with_a_note() {
        // A square without thickness: flat.
        let square = Mesh {
            vertices: vec![
                corner(0.0, 0.0, 0.0),
                corner(1.0, 0.0, 0.0),
                corner(1.0, 0.0, 1.0),
                corner(0.0, 0.0, 1.0),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            pieces: vec![0],
        };
        let c = decompose(&square, Budget::default());
        assert_eq!(c.hulls.len(), 1);
        assert!(c.notes[0].contains("flat"), "{:?}", c.notes);
        assert!((c.fit.hull_volume - f64::from(FLAT_THICKNESS)).abs() < 1e-5, "{:?}", c.fit);
        // A box with one face missing: open.
        let mut open = Mesh::cuboid(corner(0.0, 0.0, 0.0), corner(1.0, 1.0, 1.0));
        open.triangles.truncate(10);
        let c = decompose(&open, Budget::default());
        assert_eq!(c.hulls.len(), 1);
        assert!(c.notes[0].contains("open"), "{:?}", c.notes);
    }
}
