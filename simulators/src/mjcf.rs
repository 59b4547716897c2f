//! An articulated object as MJCF for MuJoCo: `mobility.xml` beside `mobility.urdf`, from the
//! same description and the same mesh files.
//!
//! - One `<body>` per link, named as in the URDF (`link_i`), nested along the kinematic
//!   tree; `link_0` hangs from the world without a joint (a fixed base, as `base_joint` is
//!   in the URDF). Each body's frame is the URDF link frame: on its joint's pivot, axes
//!   those of the object.
//! - Joints keep the object's names, types (`hinge` for revolute, `slide` for prismatic),
//!   axes and limits (radians, `angle="radian"`); a mimic joint is an `<equality><joint>`
//!   constraint `follower = offset + multiplier * leader`.
//! - Visual geoms (`class="visual"`, group 2) use `textured_objs/link_i.obj` and never
//!   collide; collision geoms (`class="collision"`, group 3) are the link's convex hulls
//!   (`collision/link_i_hull_k.obj`). Each body's `<inertial>` is the link's mass
//!   properties ([`crate::inertia`]).
//! - A joint's two links never collide with each other (`<contact><exclude>`), as in
//!   URDF loaders; any other two links do.
//! - The object frame is Y-up, as the generator's: gravity is `0 -9.81 0`.

use std::fmt::Write as _;

use pairs::JointKind;

use crate::physics::LinkPhysics;
use crate::urdf::{escape, hull_path, link_name, link_origins, mesh_path, triple, widen};
use articulated::objects::ArticulatedObject;

/// Gravity, object frame (Y-up), metres per second squared.
pub const GRAVITY: [f64; 3] = [0.0, -9.81, 0.0];

/// The text of `mobility.xml`.
pub fn mjcf_text(object: &ArticulatedObject, physics: &[LinkPhysics]) -> String {
    let origins = link_origins(object);
    let parents = object.parent_joints();
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); object.links.len()];
    for joint in &object.joints {
        if let Some(c) = children.get_mut(joint.parent) {
            c.push(joint.child);
        }
    }
    let mut out = String::new();
    let _ = writeln!(out, r#"<mujoco model="{}">"#, escape(&object.category));
    let _ =
        writeln!(out, r#"  <compiler angle="radian" autolimits="true" balanceinertia="true"/>"#);
    let _ = writeln!(out, r#"  <option gravity="{}"/>"#, triple(GRAVITY));
    let _ = writeln!(out, "  <default>");
    // Stiff joint limits (a time constant of two default steps, MuJoCo's smallest stable
    // one): the default soft limit lets a heavy link sink a few degrees past its limit.
    let _ = writeln!(out, r#"    <joint solreflimit="0.004 1" solimplimit="0.95 0.99 0.001"/>"#);
    let _ = writeln!(
        out,
        r#"    <default class="visual"><geom type="mesh" contype="0" conaffinity="0" group="2"/></default>"#
    );
    let _ =
        writeln!(out, r#"    <default class="collision"><geom type="mesh" group="3"/></default>"#);
    let _ = writeln!(out, "  </default>");
    let _ = writeln!(out, "  <asset>");
    for i in 0..object.links.len() {
        // A visual mesh need not enclose a volume (an asset's open surface): "shell"
        // inertia asks only for area, and the mesh's own inertia is never used (every body
        // has an explicit <inertial>).
        let _ = writeln!(
            out,
            r#"    <mesh name="{}" file="{}" inertia="shell"/>"#,
            link_name(i),
            mesh_path(i)
        );
        for k in 0..physics.get(i).map_or(0, |p| p.collision.hulls.len()) {
            let _ = writeln!(
                out,
                r#"    <mesh name="{}_hull_{k}" file="{}"/>"#,
                link_name(i),
                hull_path(i, k)
            );
        }
    }
    let _ = writeln!(out, "  </asset>");
    let _ = writeln!(out, "  <worldbody>");
    // Depth-first over the tree from link 0, closing each body after its children.
    let mut stack: Vec<(usize, usize, bool)> = vec![(0, 0, false)];
    while let Some((i, depth, closing)) = stack.pop() {
        let pad = " ".repeat(4 + 2 * depth);
        if closing {
            let _ = writeln!(out, "{pad}</body>");
            continue;
        }
        let parent = parents[i].map(|j| object.joints[j].parent);
        let pos: [f64; 3] = std::array::from_fn(|k| {
            f64::from(origins[i][k]) - parent.map_or(0.0, |p| f64::from(origins[p][k]))
        });
        let _ = writeln!(out, r#"{pad}<body name="{}" pos="{}">"#, link_name(i), triple(pos));
        if let Some(p) = physics.get(i) {
            let m = &p.inertial;
            let com: [f64; 3] =
                std::array::from_fn(|k| f64::from(m.com[k]) - f64::from(origins[i][k]));
            let q = m.principal_frame.quaternion();
            let _ = writeln!(
                out,
                r#"{pad}  <inertial pos="{}" quat="{} {} {} {}" mass="{}" diaginertia="{}"/>"#,
                triple(com),
                f64::from(q.w),
                f64::from(q.i),
                f64::from(q.j),
                f64::from(q.k),
                m.mass,
                triple(m.principal)
            );
        }
        if let Some(j) = parents[i] {
            let joint = &object.joints[j];
            let kind = match joint.kind {
                JointKind::Revolute => "hinge",
                JointKind::Prismatic => "slide",
            };
            let _ = writeln!(
                out,
                r#"{pad}  <joint name="{}" type="{kind}" pos="0 0 0" axis="{}" range="{} {}"/>"#,
                escape(&joint.name),
                triple(widen(joint.axis.into())),
                f64::from(joint.limits.0),
                f64::from(joint.limits.1)
            );
        }
        let back: [f64; 3] = std::array::from_fn(|k| 0.0 - f64::from(origins[i][k]));
        let _ = writeln!(
            out,
            r#"{pad}  <geom name="{}_visual" class="visual" mesh="{}" pos="{}"/>"#,
            link_name(i),
            link_name(i),
            triple(back)
        );
        for k in 0..physics.get(i).map_or(0, |p| p.collision.hulls.len()) {
            let _ = writeln!(
                out,
                r#"{pad}  <geom name="{0}_hull_{k}" class="collision" mesh="{0}_hull_{k}" pos="{1}"/>"#,
                link_name(i),
                triple(back)
            );
        }
        stack.push((i, depth, true));
        for &c in children[i].iter().rev() {
            stack.push((c, depth + 1, false));
        }
    }
    let _ = writeln!(out, "  </worldbody>");
    // A joint's two links touch at the joint (a hinge's knuckles, a drawer's runners); as
    // URDF loaders do, they never collide with each other. (MuJoCo would filter a body and
    // its parent itself, but not when the parent is welded to the world, as link_0 is.)
    if !object.joints.is_empty() {
        let _ = writeln!(out, "  <contact>");
        for joint in &object.joints {
            let _ = writeln!(
                out,
                r#"    <exclude body1="{}" body2="{}"/>"#,
                link_name(joint.parent),
                link_name(joint.child)
            );
        }
        let _ = writeln!(out, "  </contact>");
    }
    if !object.mimics.is_empty() {
        let _ = writeln!(out, "  <equality>");
        for m in &object.mimics {
            let _ = writeln!(
                out,
                r#"    <joint joint1="{}" joint2="{}" polycoef="{} {} 0 0 0"/>"#,
                escape(&object.joints[m.joint].name),
                escape(&object.joints[m.leader].name),
                f64::from(m.offset),
                f64::from(m.multiplier)
            );
        }
        let _ = writeln!(out, "  </equality>");
    }
    let _ = writeln!(out, "</mujoco>");
    out
}
