//! An articulated object as PartNet-Mobility files: `mobility.urdf`, one OBJ mesh per link
//! (`textured_objs/`), its convex collision hulls (`collision/`) and the `mobility_v2.json`
//! joint annotation.
//!
//! The layout follows PartNet-Mobility (SAPIEN): a `base` link without geometry, welded by a
//! fixed joint to `link_0` (the object's root part); `link_i` is the object's link `i`, its frame
//! on its joint's axis (at the pivot), with no rotation; meshes stay in the object's rest
//! frame and each visual's origin moves them into the link frame, as PartNet-Mobility's
//! meshes do. Joints keep the object's names; a revolute joint turns its child by the
//! right-hand rule about its axis, a prismatic one slides it along the axis, as in the
//! generator.
//!
//! Every number is written so that reading it back gives the generator's value exactly:
//! f32 values are printed as the f64 they widen to, link-frame offsets are differences of
//! such values (exact in f64), and the visual origin undoes its link frame exactly. So
//! `generator --assets` reads an exported object back into the same object (`tests/export.rs`).

use std::fmt::Write as _;

use pairs::math::{Point3, Real};
use pairs::JointKind;
use serde_json::{json, Value};

use crate::inertia::Inertial;
use crate::physics::LinkPhysics;
use articulated::mesh::Mesh;
use articulated::objects::{ArticulatedObject, Joint};

/// The URDF name of the empty link the object hangs from.
pub const BASE_LINK: &str = "base";

/// URDF name of the object's link `index`.
pub fn link_name(index: usize) -> String {
    format!("link_{index}")
}

/// Path of link `index`'s mesh, relative to the object folder.
pub fn mesh_path(index: usize) -> String {
    format!("textured_objs/{}.obj", link_name(index))
}

/// Path of link `index`'s collision hull `hull`, relative to the object folder.
pub fn hull_path(index: usize, hull: usize) -> String {
    format!("collision/{}_hull_{hull}.obj", link_name(index))
}

/// The name of the fixed joint from `base` to `link_0`: `base_joint`, with `_` added until
/// no joint of the object has it.
pub fn base_joint_name(object: &ArticulatedObject) -> String {
    let mut name = String::from("base_joint");
    while object.joints.iter().any(|j| j.name == name) {
        name.push('_');
    }
    name
}

/// A point on each link's frame: the rest-frame pivot of its joint (the origin for the
/// root), where `link_i`'s frame sits.
pub fn link_origins(object: &ArticulatedObject) -> Vec<Point3> {
    let mut origins = vec![Point3::origin(); object.links.len()];
    for joint in &object.joints {
        if let Some(slot) = origins.get_mut(joint.child) {
            *slot = joint.pivot;
        }
    }
    origins
}

/// The text of `mobility.urdf`; `physics` holds each link's collision hulls and mass
/// properties ([`crate::physics::object_physics`]).
pub fn urdf_text(object: &ArticulatedObject, physics: &[LinkPhysics]) -> String {
    let origins = link_origins(object);
    let mut out = String::new();
    let _ = writeln!(out, r#"<?xml version="1.0"?>"#);
    let _ = writeln!(out, r#"<robot name="{}">"#, escape(&object.category));
    // The base carries a token inertial: simulators warn about (and PyBullet invents a unit
    // mass for) a link without one; a fixed base ignores it.
    let _ = writeln!(
        out,
        r#"  <link name="{BASE_LINK}"><inertial><origin xyz="0 0 0" rpy="0 0 0"/><mass value="0.001"/><inertia ixx="1e-9" ixy="0" ixz="0" iyy="1e-9" iyz="0" izz="1e-9"/></inertial></link>"#
    );
    for (i, at) in origins.iter().enumerate() {
        let _ = writeln!(out, r#"  <link name="{}">"#, link_name(i));
        let back = at.coords.map(|c| 0.0 - f64::from(c));
        let origin = format!(r#"<origin xyz="{}" rpy="0 0 0"/>"#, triple(back.into()));
        let geometry = format!(r#"<geometry><mesh filename="{}"/></geometry>"#, mesh_path(i));
        let _ = writeln!(out, "    <visual>{origin}{geometry}</visual>");
        let Some(physics) = physics.get(i) else {
            let _ = writeln!(out, "  </link>");
            continue;
        };
        for k in 0..physics.collision.hulls.len() {
            let geometry =
                format!(r#"<geometry><mesh filename="{}"/></geometry>"#, hull_path(i, k));
            let _ = writeln!(out, "    <collision>{origin}{geometry}</collision>");
        }
        let _ = write!(out, "{}", inertial(&physics.inertial, at));
        let _ = writeln!(out, "  </link>");
    }
    let base_joint = base_joint_name(object);
    let _ = writeln!(out, r#"  <joint name="{}" type="fixed">"#, escape(&base_joint));
    let _ = writeln!(out, r#"    <parent link="{BASE_LINK}"/><child link="{}"/>"#, link_name(0));
    let _ = writeln!(out, r#"    <origin xyz="0 0 0" rpy="0 0 0"/>"#);
    let _ = writeln!(out, "  </joint>");
    let leader_of = |j: usize| object.mimics.iter().find(|m| m.joint == j);
    for (j, joint) in object.joints.iter().enumerate() {
        let kind = match joint.kind {
            JointKind::Revolute => "revolute",
            JointKind::Prismatic => "prismatic",
        };
        let _ = writeln!(out, r#"  <joint name="{}" type="{kind}">"#, escape(&joint.name));
        let _ = writeln!(
            out,
            r#"    <parent link="{}"/><child link="{}"/>"#,
            link_name(joint.parent),
            link_name(joint.child)
        );
        let offset: [f64; 3] = std::array::from_fn(|k| {
            f64::from(origins[joint.child][k]) - f64::from(origins[joint.parent][k])
        });
        let _ = writeln!(out, r#"    <origin xyz="{}" rpy="0 0 0"/>"#, triple(offset));
        let _ = writeln!(out, r#"    <axis xyz="{}"/>"#, triple(widen(joint.axis.into())));
        let (lo, hi) = joint.limits;
        let _ = writeln!(
            out,
            r#"    <limit lower="{}" upper="{}" effort="1000" velocity="10"/>"#,
            f64::from(lo),
            f64::from(hi)
        );
        if let Some(m) = leader_of(j) {
            let _ = writeln!(
                out,
                r#"    <mimic joint="{}" multiplier="{}" offset="{}"/>"#,
                escape(&object.joints[m.leader].name),
                f64::from(m.multiplier),
                f64::from(m.offset)
            );
        }
        let _ = writeln!(out, "  </joint>");
    }
    let _ = writeln!(out, "</robot>");
    out
}

/// The `<inertial>` of a link with mass properties `m`, in the link frame whose origin is
/// `origin`.
fn inertial(m: &Inertial, origin: &Point3) -> String {
    let com: [f64; 3] = std::array::from_fn(|k| f64::from(m.com[k]) - f64::from(origin[k]));
    let t = m.tensor();
    format!(
        "    <inertial><origin xyz=\"{}\" rpy=\"0 0 0\"/><mass value=\"{}\"/>\
         <inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/></inertial>\n",
        triple(com),
        m.mass,
        t[0][0],
        t[0][1],
        t[0][2],
        t[1][1],
        t[1][2],
        t[2][2],
    )
}

/// The text of one link's OBJ file: its rest-frame vertices (printed so that an f32
/// reader gets them back exactly) and triangles.
pub fn obj_text(mesh: &Mesh, name: &str) -> String {
    let mut out = String::with_capacity(mesh.vertices.len() * 32 + mesh.triangles.len() * 16);
    let _ = writeln!(out, "# part_induction generator: one link, object rest frame");
    let _ = writeln!(out, "o {}", name.replace(char::is_whitespace, "_"));
    for v in &mesh.vertices {
        let _ = writeln!(out, "v {} {} {}", v.x, v.y, v.z);
    }
    for t in &mesh.triangles {
        let _ = writeln!(out, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    out
}

/// PartNet-Mobility's `mobility_v2.json`: one entry per link (`id` i is `link_i`), its
/// parent link, `joint` (`heavy` for the root, `hinge` for revolute, `slider` for
/// prismatic), the link's name, and the joint's axis (origin and direction, rest frame)
/// with its limits (`hinge`: degrees; `slider`: object units). A mimic joint's coupling,
/// which PartNet-Mobility does not annotate, is under `mimic`.
pub fn mobility_json(object: &ArticulatedObject) -> Value {
    let parents = object.parent_joints();
    let entries: Vec<Value> = object
        .links
        .iter()
        .enumerate()
        .map(|(i, link)| {
            let parts = json!([{ "id": i, "name": link.name, "children": [] }]);
            let Some(j) = parents[i] else {
                return json!({
                    "id": i, "parent": -1, "joint": "heavy", "name": link.name,
                    "parts": parts, "jointData": {},
                });
            };
            let joint = &object.joints[j];
            let mut entry = json!({
                "id": i,
                "parent": joint.parent,
                "joint": if joint.kind == JointKind::Revolute { "hinge" } else { "slider" },
                "name": link.name,
                "joint_name": joint.name,
                "parts": parts,
                "jointData": joint_data(joint),
            });
            if let Some(m) = object.mimics.iter().find(|m| m.joint == j) {
                entry["mimic"] = json!({
                    "joint": object.joints[m.leader].name,
                    "multiplier": m.multiplier,
                    "offset": m.offset,
                });
            }
            entry
        })
        .collect();
    Value::Array(entries)
}

/// `jointData` of a PartNet-Mobility entry.
fn joint_data(joint: &Joint) -> Value {
    let axis = json!({ "origin": widen(joint.pivot.coords.into()), "direction": widen(joint.axis.into()) });
    let (lo, hi) = (f64::from(joint.limits.0), f64::from(joint.limits.1));
    match joint.kind {
        JointKind::Revolute => json!({
            "axis": axis,
            "limit": { "a": lo.to_degrees(), "b": hi.to_degrees(), "noLimit": false },
        }),
        JointKind::Prismatic => json!({
            "axis": axis,
            "limit": {
                "a": lo, "b": hi, "noLimit": false,
                "rotates": false, "noRotationLimit": false, "rotationLimit": 0,
            },
        }),
    }
}

pub(crate) fn widen(v: [Real; 3]) -> [f64; 3] {
    v.map(f64::from)
}

/// Three numbers separated by spaces, each printed so that parsing gives it back exactly.
pub(crate) fn triple(v: [f64; 3]) -> String {
    format!("{} {} {}", v[0], v[1], v[2])
}

/// `text` with the five XML special characters escaped, for attribute values.
pub(crate) fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn special_characters_are_escaped() {
        assert_eq!(escape(r#"a&b<"c">'"#), "a&amp;b&lt;&quot;c&quot;&gt;&apos;");
    }

    #[test]
    fn printed_numbers_parse_back_exactly() {
        for x in [0.1f32, -1.0e-7, 3.4e38, 1.0 / 3.0, -0.0] {
            let text = format!("{}", f64::from(x));
            let back: f64 = text.parse().expect("a number");
            assert_eq!(back as f32, x, "{text}");
        }
        for x in [0.1f32, -1.0e-7, 1.0 / 3.0, 12345.678] {
            let back: f32 = format!("{x}").parse().expect("a number");
            assert_eq!(back, x);
        }
    }
}
