//! An articulated object as USD (text, `mobility.usda`) with the UsdPhysics schema, for
//! Isaac Sim and any USD reader, from the same description as the URDF and MJCF.
//!
//! - Stage: `upAxis = "Y"` (the generator's frame), one metre and one kilogram per unit, a
//!   `PhysicsScene` with gravity along -Y.
//! - `/<category>` (the default prim, `PhysicsArticulationRootAPI`) holds one `Xform` per
//!   link, named as in the URDF (`link_i`), side by side, each placed at its link frame's
//!   rest position (a translation; links are never rotated at rest) with
//!   `PhysicsRigidBodyAPI` and `PhysicsMassAPI` (mass, centre of mass, principal moments
//!   and axes from [`crate::inertia`]). Under it, `visual` is the link's mesh, and
//!   `collision/hull_k` its convex hulls (`PhysicsCollisionAPI`,
//!   `PhysicsMeshCollisionAPI` with `convexHull` approximation, purpose `guide`).
//! - `/<category>/joints`: a `PhysicsFixedJoint` from the world to `link_0`
//!   (`base_joint`), then one `PhysicsRevoluteJoint` or `PhysicsPrismaticJoint` per joint.
//!   UsdPhysics joints move about or along their frame's X, Y or Z axis only, so the joint
//!   frame is rotated (`localRot0` = `localRot1`) to take X onto the joint's axis; it sits
//!   on the pivot (`localPos0` in the parent link, `localPos1` = 0 in the child). Limits are
//!   in degrees for revolute joints, object units for prismatic ones.
//! - A prim name must be an identifier: a joint name that is not one is made one (every
//!   other character becomes `_`, a leading digit gets a `_`), and every joint keeps its
//!   own name in `part_induction:name`. UsdPhysics has no coupled joints: a mimic joint
//!   records its leader (`part_induction:mimic:joint`), `multiplier` and `offset` as custom
//!   attributes, and simulates as an independent joint.

use std::fmt::Write as _;

use pairs::math::{Real, UnitQuaternion, Vector3};
use pairs::JointKind;

use crate::physics::LinkPhysics;
use crate::urdf::{base_joint_name, link_name, link_origins, widen};
use articulated::mesh::Mesh;
use articulated::objects::ArticulatedObject;

/// `text` as a USD identifier: characters other than ASCII letters, digits and `_`
/// become `_`, and a leading digit (or an empty name) gets a `_` in front.
pub fn identifier(text: &str) -> String {
    let mut out: String =
        text.chars().map(|c| if c.is_ascii_alphanumeric() || c == '_' { c } else { '_' }).collect();
    if out.chars().next().is_none_or(|c| c.is_ascii_digit()) {
        out.insert(0, '_');
    }
    out
}

/// Joint prim names: each joint's name as an identifier, with `_` added until it is
/// unique among the joints (and different from `base`).
pub fn joint_prim_names(object: &ArticulatedObject) -> Vec<String> {
    let mut taken = vec![identifier(&base_joint_name(object))];
    for joint in &object.joints {
        let mut name = identifier(&joint.name);
        while taken.contains(&name) {
            name.push('_');
        }
        taken.push(name);
    }
    taken
}

/// The rotation taking X onto the unit vector `axis`.
fn x_onto(axis: &Vector3) -> UnitQuaternion {
    UnitQuaternion::rotation_between(&Vector3::x(), axis).unwrap_or_else(|| {
        // `axis` is -X: half a turn about Y.
        UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f32::consts::PI)
    })
}

/// A quaternion as USD writes one, `(w, x, y, z)`.
fn quat(q: &UnitQuaternion) -> String {
    let q = q.quaternion();
    format!("({}, {}, {}, {})", f64::from(q.w), f64::from(q.i), f64::from(q.j), f64::from(q.k))
}

/// Three numbers as a USD tuple.
fn tuple(v: [f64; 3]) -> String {
    format!("({}, {}, {})", v[0], v[1], v[2])
}

/// A string as a USD string literal.
fn string(text: &str) -> String {
    serde_json::to_string(text).expect("a string serialises")
}

/// A `Mesh` prim's geometry attributes (indented by `pad`).
fn mesh_attributes(
    out: &mut String,
    pad: &str,
    vertices: &[pairs::math::Point3],
    triangles: &[[u32; 3]],
) {
    let counts = vec!["3"; triangles.len()].join(", ");
    let indices: Vec<String> = triangles.iter().flatten().map(u32::to_string).collect();
    let points: Vec<String> = vertices.iter().map(|p| tuple(widen([p.x, p.y, p.z]))).collect();
    let _ = writeln!(out, "{pad}int[] faceVertexCounts = [{counts}]");
    let _ = writeln!(out, "{pad}int[] faceVertexIndices = [{}]", indices.join(", "));
    let _ = writeln!(out, "{pad}point3f[] points = [{}]", points.join(", "));
    let _ = writeln!(out, r#"{pad}uniform token subdivisionScheme = "none""#);
}

/// A translation op (indented by `pad`).
fn translate(out: &mut String, pad: &str, v: [f64; 3]) {
    let _ = writeln!(out, "{pad}double3 xformOp:translate = {}", tuple(v));
    let _ = writeln!(out, r#"{pad}uniform token[] xformOpOrder = ["xformOp:translate"]"#);
}

/// The text of `mobility.usda`.
pub fn usda_text(object: &ArticulatedObject, physics: &[LinkPhysics]) -> String {
    let origins = link_origins(object);
    let root = identifier(&object.category);
    let mut out = String::new();
    let _ = writeln!(out, "#usda 1.0");
    let _ = writeln!(out, "(");
    let _ = writeln!(out, "    defaultPrim = {}", string(&root));
    let _ = writeln!(out, "    doc = \"part_induction generator: one articulated object\"");
    let _ = writeln!(out, "    kilogramsPerUnit = 1");
    let _ = writeln!(out, "    metersPerUnit = 1");
    let _ = writeln!(out, "    upAxis = \"Y\"");
    let _ = writeln!(out, ")");
    let _ = writeln!(out);
    let _ = writeln!(out, "def Xform {} (", string(&root));
    let _ = writeln!(out, "    prepend apiSchemas = [\"PhysicsArticulationRootAPI\"]");
    let _ = writeln!(out, ")");
    let _ = writeln!(out, "{{");
    let _ =
        writeln!(out, "    custom string part_induction:category = {}", string(&object.category));
    let _ = writeln!(out, "    def PhysicsScene \"physics_scene\"");
    let _ = writeln!(out, "    {{");
    let _ = writeln!(out, "        vector3f physics:gravityDirection = (0, -1, 0)");
    let _ = writeln!(out, "        float physics:gravityMagnitude = 9.81");
    let _ = writeln!(out, "    }}");
    for (i, link) in object.links.iter().enumerate() {
        write_link(&mut out, i, &link.name, &link.mesh, &origins[i], physics.get(i));
    }
    let names = joint_prim_names(object);
    let _ = writeln!(out, "    def Scope \"joints\"");
    let _ = writeln!(out, "    {{");
    let _ = writeln!(out, "        def PhysicsFixedJoint {}", string(&names[0]));
    let _ = writeln!(out, "        {{");
    let _ = writeln!(
        out,
        "            custom string part_induction:name = {}",
        string(&base_joint_name(object))
    );
    let _ = writeln!(out, "            rel physics:body1 = </{root}/{}>", link_name(0));
    let _ = writeln!(out, "        }}");
    for (j, joint) in object.joints.iter().enumerate() {
        let kind = match joint.kind {
            JointKind::Revolute => "PhysicsRevoluteJoint",
            JointKind::Prismatic => "PhysicsPrismaticJoint",
        };
        let (lo, hi) = (f64::from(joint.limits.0), f64::from(joint.limits.1));
        let (lo, hi) = match joint.kind {
            JointKind::Revolute => (lo.to_degrees(), hi.to_degrees()),
            JointKind::Prismatic => (lo, hi),
        };
        let offset: [f64; 3] = std::array::from_fn(|k| {
            f64::from(origins[joint.child][k]) - f64::from(origins[joint.parent][k])
        });
        let rotation = quat(&x_onto(&joint.axis));
        let pad = "            ";
        let _ = writeln!(out, "        def {kind} {}", string(&names[j + 1]));
        let _ = writeln!(out, "        {{");
        let _ = writeln!(out, "{pad}custom string part_induction:name = {}", string(&joint.name));
        let _ = writeln!(out, "{pad}rel physics:body0 = </{root}/{}>", link_name(joint.parent));
        let _ = writeln!(out, "{pad}rel physics:body1 = </{root}/{}>", link_name(joint.child));
        let _ = writeln!(out, "{pad}uniform token physics:axis = \"X\"");
        let _ = writeln!(out, "{pad}point3f physics:localPos0 = {}", tuple(offset));
        let _ = writeln!(out, "{pad}quatf physics:localRot0 = {rotation}");
        let _ = writeln!(out, "{pad}point3f physics:localPos1 = (0, 0, 0)");
        let _ = writeln!(out, "{pad}quatf physics:localRot1 = {rotation}");
        let _ = writeln!(out, "{pad}float physics:lowerLimit = {lo}");
        let _ = writeln!(out, "{pad}float physics:upperLimit = {hi}");
        if let Some(m) = object.mimics.iter().find(|m| m.joint == j) {
            let _ = writeln!(
                out,
                "{pad}custom rel part_induction:mimic:joint = </{root}/joints/{}>",
                names[m.leader + 1]
            );
            let _ = writeln!(
                out,
                "{pad}custom float part_induction:mimic:multiplier = {}",
                f64::from(m.multiplier)
            );
            let _ = writeln!(
                out,
                "{pad}custom float part_induction:mimic:offset = {}",
                f64::from(m.offset)
            );
        }
        let _ = writeln!(out, "        }}");
    }
    let _ = writeln!(out, "    }}");
    let _ = writeln!(out, "}}");
    out
}

/// Link `i`'s `Xform`: its rigid body, mass, visual mesh and collision hulls.
fn write_link(
    out: &mut String,
    i: usize,
    name: &str,
    mesh: &Mesh,
    origin: &pairs::math::Point3,
    physics: Option<&LinkPhysics>,
) {
    let at = widen([origin.x, origin.y, origin.z]);
    let back = at.map(|c| 0.0 - c);
    let _ = writeln!(out, "    def Xform \"{}\" (", link_name(i));
    let _ =
        writeln!(out, "        prepend apiSchemas = [\"PhysicsRigidBodyAPI\", \"PhysicsMassAPI\"]");
    let _ = writeln!(out, "    )");
    let _ = writeln!(out, "    {{");
    let pad = "        ";
    let _ = writeln!(out, "{pad}custom string part_induction:name = {}", string(name));
    translate(out, pad, at);
    if let Some(p) = physics {
        let m = &p.inertial;
        let com: [f64; 3] = std::array::from_fn(|k| f64::from(m.com[k]) - at[k]);
        let _ = writeln!(out, "{pad}float physics:mass = {}", m.mass as Real);
        let _ = writeln!(out, "{pad}point3f physics:centerOfMass = {}", tuple(com));
        let _ = writeln!(out, "{pad}float3 physics:diagonalInertia = {}", tuple(m.principal));
        let _ = writeln!(out, "{pad}quatf physics:principalAxes = {}", quat(&m.principal_frame));
    }
    let _ = writeln!(out, "{pad}def Mesh \"visual\"");
    let _ = writeln!(out, "{pad}{{");
    let inner = "            ";
    translate(out, inner, back);
    mesh_attributes(out, inner, &mesh.vertices, &mesh.triangles);
    let _ = writeln!(out, "{pad}}}");
    if let Some(p) = physics {
        let _ = writeln!(out, "{pad}def Xform \"collision\"");
        let _ = writeln!(out, "{pad}{{");
        translate(out, inner, back);
        for (k, hull) in p.collision.hulls.iter().enumerate() {
            let _ = writeln!(out, "{inner}def Mesh \"hull_{k}\" (");
            let _ = writeln!(
                out,
                "{inner}    prepend apiSchemas = [\"PhysicsCollisionAPI\", \"PhysicsMeshCollisionAPI\"]"
            );
            let _ = writeln!(out, "{inner})");
            let _ = writeln!(out, "{inner}{{");
            let deeper = "                ";
            let _ = writeln!(out, "{deeper}uniform token physics:approximation = \"convexHull\"");
            let _ = writeln!(out, "{deeper}uniform token purpose = \"guide\"");
            mesh_attributes(out, deeper, &hull.vertices, &hull.triangles);
            let _ = writeln!(out, "{inner}}}");
        }
        let _ = writeln!(out, "{pad}}}");
    }
    let _ = writeln!(out, "    }}");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_become_identifiers() {
        assert_eq!(identifier("door 1"), "door_1");
        assert_eq!(identifier("2nd-lid"), "_2nd_lid");
        assert_eq!(identifier(""), "_");
        assert_eq!(identifier("hinge_a"), "hinge_a");
    }

    #[test]
    fn the_joint_frame_takes_x_onto_the_axis() {
        for axis in [Vector3::x(), -Vector3::x(), Vector3::y(), Vector3::new(0.6, 0.0, -0.8)] {
            let moved = x_onto(&axis) * Vector3::x();
            assert!((moved - axis).norm() < 1e-6, "{axis:?} -> {moved:?}");
        }
    }
}
