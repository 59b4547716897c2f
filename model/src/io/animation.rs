//! The paper's animation application: each segment of P moves from its place in P to its
//! place in Q along the SE(3) geodesic of its motion ([`pairs::screw`]), written as a
//! binary glTF 2.0 file (`.glb`): one node per segment holding that segment's points (a
//! POINTS primitive coloured by segment), a static node with Q's points in grey, and one
//! animation whose translation, rotation and scale keyframes drive the segment nodes.

use std::path::Path;

use pairs::dataset::viz::part_colour;
use pairs::math::{Point3, Real};
use pairs::screw::interpolate_screw;
use pairs::transform::Similarity;
use serde_json::{json, Value};

use crate::io::pointfile::PointFileError;

/// Keyframes of the animation and its length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnimationParams {
    /// Keyframes from P's state (first) to Q's (last), at least 2.
    pub keyframes: usize,
    /// Seconds from the first keyframe to the last.
    pub seconds: Real,
}

impl Default for AnimationParams {
    /// 31 keyframes over 2 seconds.
    fn default() -> Self {
        Self { keyframes: 31, seconds: 2.0 }
    }
}

/// Accumulates the binary chunk with its buffer views and accessors.
#[derive(Default)]
struct Buffer {
    bytes: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Buffer {
    /// Adds float data of `kind` (`SCALAR`, `VEC3`, `VEC4`) as an accessor; returns its index.
    fn floats(&mut self, values: &[f32], kind: &str, width: usize, bounds: bool) -> usize {
        self.bytes.resize(self.bytes.len().next_multiple_of(4), 0);
        let offset = self.bytes.len();
        for v in values {
            self.bytes.extend(v.to_le_bytes());
        }
        self.views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": values.len() * 4}));
        let mut accessor = json!({
            "bufferView": self.views.len() - 1,
            "componentType": 5126,
            "count": values.len() / width,
            "type": kind,
        });
        if bounds {
            let (mut min, mut max) = (vec![f32::INFINITY; width], vec![f32::NEG_INFINITY; width]);
            for row in values.chunks(width) {
                for (k, v) in row.iter().enumerate() {
                    min[k] = min[k].min(*v);
                    max[k] = max[k].max(*v);
                }
            }
            accessor["min"] = json!(min);
            accessor["max"] = json!(max);
        }
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    /// A POINTS mesh of `points` in one colour; returns the mesh JSON.
    fn points_mesh(&mut self, points: &[&Point3], colour: [u8; 3]) -> Value {
        let xyz: Vec<f32> = points.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
        let rgb: Vec<f32> =
            points.iter().flat_map(|_| colour.map(|c| f32::from(c) / 255.0)).collect();
        let position = self.floats(&xyz, "VEC3", 3, true);
        let colour = self.floats(&rgb, "VEC3", 3, false);
        json!({"primitives": [{"attributes": {"POSITION": position, "COLOR_0": colour}, "mode": 0}]})
    }
}

/// The glTF binary of P's segments (`labels`, ids `0..K`) moving by `motions` onto Q.
pub fn animation_glb(
    p: &[Point3],
    labels: &[u32],
    motions: &[Similarity],
    q: &[Point3],
    params: &AnimationParams,
) -> Vec<u8> {
    let mut buffer = Buffer::default();
    let (mut nodes, mut meshes, mut channels, mut samplers) = (vec![], vec![], vec![], vec![]);
    let frames = params.keyframes.max(2);
    let times: Vec<f32> =
        (0..frames).map(|k| params.seconds * k as f32 / (frames - 1) as f32).collect();
    let time = buffer.floats(&times, "SCALAR", 1, true);
    for (k, motion) in motions.iter().enumerate() {
        let members: Vec<&Point3> =
            p.iter().zip(labels).filter(|(_, &l)| l as usize == k).map(|(x, _)| x).collect();
        if members.is_empty() {
            continue;
        }
        meshes.push(buffer.points_mesh(&members, part_colour(k as u8)));
        nodes.push(json!({"name": format!("segment {k}"), "mesh": meshes.len() - 1}));
        let node = nodes.len() - 1;
        let poses: Vec<Similarity> = (0..frames)
            .map(|f| interpolate_screw(motion, f as Real / (frames - 1) as Real))
            .collect();
        let translations: Vec<f32> = poses
            .iter()
            .flat_map(|m| [m.translation.x, m.translation.y, m.translation.z])
            .collect();
        let rotations: Vec<f32> = poses
            .iter()
            .flat_map(|m| {
                let q = m.quaternion();
                [q.i, q.j, q.k, q.w]
            })
            .collect();
        let scales: Vec<f32> = poses.iter().flat_map(|m| [m.scale; 3]).collect();
        for (path, values, kind, width) in [
            ("translation", translations, "VEC3", 3),
            ("rotation", rotations, "VEC4", 4),
            ("scale", scales, "VEC3", 3),
        ] {
            let output = buffer.floats(&values, kind, width, false);
            samplers.push(json!({"input": time, "output": output, "interpolation": "LINEAR"}));
            channels.push(
                json!({"sampler": samplers.len() - 1, "target": {"node": node, "path": path}}),
            );
        }
    }
    let q_points: Vec<&Point3> = q.iter().collect();
    meshes.push(buffer.points_mesh(&q_points, [90, 90, 90]));
    nodes.push(json!({"name": "Q", "mesh": meshes.len() - 1}));
    buffer.bytes.resize(buffer.bytes.len().next_multiple_of(4), 0);
    let document = json!({
        "asset": {"version": "2.0", "generator": concat!("model ", env!("CARGO_PKG_VERSION"))},
        "scene": 0,
        "scenes": [{"nodes": (0..nodes.len()).collect::<Vec<_>>()}],
        "nodes": nodes,
        "meshes": meshes,
        "buffers": [{"byteLength": buffer.bytes.len()}],
        "bufferViews": buffer.views,
        "accessors": buffer.accessors,
        "animations": [{"name": "P to Q", "channels": channels, "samplers": samplers}],
    });
    let mut text = document.to_string().into_bytes();
    text.resize(text.len().next_multiple_of(4), b' ');
    let total = 12 + 8 + text.len() + 8 + buffer.bytes.len();
    let mut glb = Vec::with_capacity(total);
    glb.extend(b"glTF");
    glb.extend(2u32.to_le_bytes());
    glb.extend((total as u32).to_le_bytes());
    glb.extend((text.len() as u32).to_le_bytes());
    glb.extend(b"JSON");
    glb.extend(text);
    glb.extend((buffer.bytes.len() as u32).to_le_bytes());
    glb.extend(b"BIN\0");
    glb.extend(buffer.bytes);
    glb
}

/// Writes [`animation_glb`] to `path`.
pub fn write_animation(
    path: &Path,
    p: &[Point3],
    labels: &[u32],
    motions: &[Similarity],
    q: &[Point3],
    params: &AnimationParams,
) -> Result<(), PointFileError> {
    let glb = animation_glb(p, labels, motions, q, params);
    Ok(pairs::atomic::replace_bytes(path, &glb)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::synthetic::hinge_pair;

    #[test]
    fn the_glb_is_well_formed_and_ends_at_q() {
        let pair = hinge_pair("t", 4, 0.9);
        let (input, truth) = (pair.input(), pair.truth());
        let labels = pairs::parts::part_segments(&truth.part_p);
        let glb = animation_glb(
            &input.p.points,
            &labels,
            &truth.motions,
            &input.q.points,
            &AnimationParams::default(),
        );
        assert_eq!(&glb[..4], b"glTF");
        let u32_at =
            |i: usize| u32::from_le_bytes(glb[i..i + 4].try_into().expect("4 bytes")) as usize;
        assert_eq!(u32_at(8), glb.len());
        let json_len = u32_at(12);
        assert_eq!(&glb[16..20], b"JSON");
        let doc: Value = serde_json::from_slice(&glb[20..20 + json_len]).expect("valid JSON");
        let bin = &glb[20 + json_len + 8..];
        assert_eq!(doc["buffers"][0]["byteLength"].as_u64(), Some(bin.len() as u64));
        assert_eq!(doc["nodes"].as_array().map(Vec::len), Some(3));
        assert_eq!(doc["animations"][0]["channels"].as_array().map(Vec::len), Some(6));
        // The last translation keyframe of segment 1 is its motion's translation.
        let sampler = &doc["animations"][0]["samplers"][3];
        let view = &doc["bufferViews"][doc["accessors"]
            [sampler["output"].as_u64().expect("index") as usize]["bufferView"]
            .as_u64()
            .expect("index") as usize];
        let start = view["byteOffset"].as_u64().expect("offset") as usize
            + view["byteLength"].as_u64().expect("length") as usize
            - 12;
        let last: Vec<f32> = bin[start..start + 12]
            .chunks(4)
            .map(|b| f32::from_le_bytes(b.try_into().expect("4 bytes")))
            .collect();
        let t = truth.motions[1].translation;
        assert!(
            (last[0] - t.x).abs() < 1e-4
                && (last[1] - t.y).abs() < 1e-4
                && (last[2] - t.z).abs() < 1e-4
        );
    }
}
