//! Foxglove `foxglove.PointCloud` messages (JSON encoding) that show each pair coloured by part.

use base64::Engine;
use serde_json::json;

use crate::math::{Point3, Real};
use crate::parts::PartId;

/// Topic of P's visualisation.
pub const VIZ_P_TOPIC: &str = "/viz/p";
/// Topic of Q's visualisation.
pub const VIZ_Q_TOPIC: &str = "/viz/q";
/// Schema name Foxglove recognises.
pub const POINT_CLOUD_SCHEMA: &str = "foxglove.PointCloud";
/// Frame both clouds are drawn in.
pub const VIZ_FRAME: &str = "pair";
/// P is drawn at `-VIZ_OFFSET` along x and Q at `+VIZ_OFFSET`, so that both are visible at once.
pub const VIZ_OFFSET: Real = 0.6;

/// JSON schema of `foxglove.PointCloud`, as the `jsonschema` encoding requires.
pub const POINT_CLOUD_JSON_SCHEMA: &str = r#"{
  "title": "foxglove.PointCloud",
  "description": "A collection of N-dimensional points",
  "type": "object",
  "properties": {
    "timestamp": {"type": "object", "title": "time", "properties": {
      "sec": {"type": "integer", "minimum": 0},
      "nsec": {"type": "integer", "minimum": 0, "maximum": 999999999}}},
    "frame_id": {"type": "string"},
    "pose": {"title": "foxglove.Pose", "type": "object", "properties": {
      "position": {"title": "foxglove.Vector3", "type": "object", "properties": {
        "x": {"type": "number"}, "y": {"type": "number"}, "z": {"type": "number"}}},
      "orientation": {"title": "foxglove.Quaternion", "type": "object", "properties": {
        "x": {"type": "number"}, "y": {"type": "number"}, "z": {"type": "number"},
        "w": {"type": "number"}}}}},
    "point_stride": {"type": "integer", "minimum": 0},
    "fields": {"type": "array", "items": {"title": "foxglove.PackedElementField",
      "type": "object", "properties": {
        "name": {"type": "string"},
        "offset": {"type": "integer", "minimum": 0},
        "type": {"title": "foxglove.NumericType", "oneOf": [
          {"title": "UNKNOWN", "const": 0}, {"title": "UINT8", "const": 1},
          {"title": "INT8", "const": 2}, {"title": "UINT16", "const": 3},
          {"title": "INT16", "const": 4}, {"title": "UINT32", "const": 5},
          {"title": "INT32", "const": 6}, {"title": "FLOAT32", "const": 7},
          {"title": "FLOAT64", "const": 8}]}}}},
    "data": {"type": "string", "contentEncoding": "base64"}
  }
}"#;

/// Schema name Foxglove recognises for PNG or JPEG images.
pub const COMPRESSED_IMAGE_SCHEMA: &str = "foxglove.CompressedImage";

/// JSON schema of `foxglove.CompressedImage`.
pub const COMPRESSED_IMAGE_JSON_SCHEMA: &str = r#"{
  "title": "foxglove.CompressedImage",
  "description": "A compressed image",
  "type": "object",
  "properties": {
    "timestamp": {"type": "object", "title": "time", "properties": {
      "sec": {"type": "integer", "minimum": 0},
      "nsec": {"type": "integer", "minimum": 0, "maximum": 999999999}}},
    "frame_id": {"type": "string"},
    "data": {"type": "string", "contentEncoding": "base64"},
    "format": {"type": "string"}
  }
}"#;

/// Topic of one image of one side: `/viz/<side>/<kind>` (e.g. `/viz/q/depth`).
pub fn image_topic(side: &str, kind: &str) -> String {
    format!("/viz/{side}/{kind}")
}

/// The JSON bytes of a `foxglove.CompressedImage` holding `png`, stamped at `sec` seconds.
pub fn image_message(png: &[u8], sec: u64) -> Vec<u8> {
    let message = json!({
        "timestamp": {"sec": sec, "nsec": 0},
        "frame_id": VIZ_FRAME,
        "data": base64::engine::general_purpose::STANDARD.encode(png),
        "format": "png",
    });
    serde_json::to_vec(&message).expect("a JSON value always serialises")
}

/// Bytes per point: x, y, z as f32 then red, green, blue, alpha as u8.
const STRIDE: usize = 16;
const FLOAT32: u8 = 7;
const UINT8: u8 = 1;

/// Colour of a part: a fixed qualitative palette, repeated past its end.
pub fn part_colour(part: PartId) -> [u8; 3] {
    const PALETTE: [[u8; 3]; 10] = [
        [160, 160, 160],
        [228, 26, 28],
        [55, 126, 184],
        [77, 175, 74],
        [152, 78, 163],
        [255, 127, 0],
        [200, 200, 40],
        [166, 86, 40],
        [247, 129, 191],
        [0, 190, 190],
    ];
    PALETTE[usize::from(part) % PALETTE.len()]
}

/// The JSON bytes of a `foxglove.PointCloud` of `points` coloured by `parts`, stamped at
/// `sec` seconds and drawn at `offset_x` along x.
pub fn point_cloud_message(
    points: &[Point3],
    parts: &[PartId],
    sec: u64,
    offset_x: Real,
) -> Vec<u8> {
    let mut data = Vec::with_capacity(points.len() * STRIDE);
    for (p, &part) in points.iter().zip(parts) {
        for c in p.coords.iter() {
            data.extend_from_slice(&c.to_le_bytes());
        }
        data.extend_from_slice(&part_colour(part));
        data.push(255);
    }
    let field =
        |name: &str, offset: usize, kind: u8| json!({"name": name, "offset": offset, "type": kind});
    let message = json!({
        "timestamp": {"sec": sec, "nsec": 0},
        "frame_id": VIZ_FRAME,
        "pose": {
            "position": {"x": offset_x, "y": 0.0, "z": 0.0},
            "orientation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0}
        },
        "point_stride": STRIDE,
        "fields": [
            field("x", 0, FLOAT32), field("y", 4, FLOAT32), field("z", 8, FLOAT32),
            field("red", 12, UINT8), field("green", 13, UINT8), field("blue", 14, UINT8),
            field("alpha", 15, UINT8)
        ],
        "data": base64::engine::general_purpose::STANDARD.encode(&data),
    });
    serde_json::to_vec(&message).expect("a JSON value always serialises")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn message_packs_points_and_colours() {
        let msg = point_cloud_message(&[Point3::new(1.0, 2.0, 3.0)], &[1], 7, 0.5);
        let v: serde_json::Value = serde_json::from_slice(&msg).expect("valid JSON");
        let data = base64::engine::general_purpose::STANDARD
            .decode(v["data"].as_str().expect("data is a string"))
            .expect("valid base64");
        assert_eq!(data.len(), STRIDE);
        assert_eq!(f32::from_le_bytes(data[4..8].try_into().expect("4 bytes")), 2.0);
        assert_eq!(&data[12..16], &[228, 26, 28, 255]);
        assert_eq!(v["timestamp"]["sec"], 7);
        let schema: serde_json::Value =
            serde_json::from_str(POINT_CLOUD_JSON_SCHEMA).expect("schema is JSON");
        assert_eq!(schema["title"], POINT_CLOUD_SCHEMA);
    }
}
