//! Forward kinematics: link poses from joint values.

use pairs::math::{Isometry3, Real, Translation3};
use pairs::transform::rotation_about;
use pairs::JointKind;

use crate::objects::{ArticulatedObject, Joint};

/// The motion a joint applies to its child at `value`, in the parent's frame.
pub fn joint_motion(joint: &Joint, value: Real) -> Isometry3 {
    match joint.kind {
        JointKind::Revolute => rotation_about(&joint.pivot, &joint.axis, value),
        JointKind::Prismatic => {
            Isometry3::from_parts(Translation3::from(joint.axis * value), Default::default())
        }
    }
}

/// Pose of every link (rest frame to posed frame) for one value per joint.
///
/// Relies on the model's rule that a joint's parent comes before its child.
pub fn link_poses(object: &ArticulatedObject, values: &[Real]) -> Vec<Isometry3> {
    let mut poses = vec![Isometry3::identity(); object.links.len()];
    for (joint, &value) in object.joints.iter().zip(values) {
        poses[joint.child] = poses[joint.parent] * joint_motion(joint, value);
    }
    poses
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;
    use crate::objects::Link;
    use pairs::math::{Point3, Vector3};

    #[test]
    fn chained_joints_compose() {
        let cube = || Mesh::cuboid(Point3::origin(), Point3::new(1.0, 1.0, 1.0));
        let link = |name: &str| Link { name: name.into(), mesh: cube() };
        let mut obj = ArticulatedObject::new("test", link("base"));
        let slide = Joint {
            name: String::new(),
            kind: JointKind::Prismatic,
            parent: 0,
            child: 0,
            pivot: Point3::origin(),
            axis: Vector3::x(),
            limits: (0.0, 1.0),
            rest: 0.0,
        };
        let arm = obj.attach(0, link("slider"), slide);
        let hinge = Joint {
            name: String::new(),
            kind: JointKind::Revolute,
            axis: Vector3::z(),
            limits: (0.0, 2.0),
            ..obj.joints[0].clone()
        };
        let tip = obj.attach(arm, link("tip"), hinge);
        obj.validate().expect("valid tree");
        let poses = link_poses(&obj, &[0.5, std::f32::consts::FRAC_PI_2]);
        let p = poses[tip] * Point3::new(1.0, 0.0, 0.0);
        assert!((p - Point3::new(0.5, 1.0, 0.0)).norm() < 1e-6);
    }
}
