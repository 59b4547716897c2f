//! Overlap of an assembly's links, whose every piece is a box (the root's primitive by its
//! bounding box): exact separating-axis tests between posed boxes over a grid of the joints
//! that move two links relative to each other.

use pairs::math::{Isometry3, Matrix3, Point3, Real, Vector3};
use pairs::transform::rotation_about;
use pairs::JointKind;

use super::geometry::Block;
use crate::kinematics::joint_motion;
use crate::objects::{ArticulatedObject, Joint};

/// Deepest overlap allowed on the checked grid of states, as a fraction of the object's
/// size: half of what the category tests allow, for the states between grid points.
pub(super) const OVERLAP: Real = 0.01;

/// A box posed in space.
struct Obb {
    centre: Point3,
    axes: Matrix3,
    half: Vector3,
}

impl Obb {
    /// Half the extent of the box's projection on unit direction `l`.
    fn reach(&self, l: &Vector3) -> Real {
        (0..3).map(|i| self.half[i] * self.axes.column(i).dot(l).abs()).sum()
    }
}

/// A link pose with its rotation as a matrix, to place the link's boxes.
struct Posed<'a> {
    pose: &'a Isometry3,
    axes: Matrix3,
}

impl<'a> Posed<'a> {
    fn new(pose: &'a Isometry3) -> Self {
        Self { pose, axes: *pose.rotation.to_rotation_matrix().matrix() }
    }

    fn place(&self, block: &Block) -> Obb {
        Obb { centre: self.pose * block.centre(), axes: self.axes, half: block.half() }
    }
}

/// How deep two boxes overlap (0 when apart): the least overlap of their projections on the
/// 15 candidate separating axes, which for boxes is the shortest distance that parts them.
fn depth(a: &Obb, b: &Obb) -> Real {
    let d = b.centre - a.centre;
    let faces = (0..3).flat_map(|i| [a.axes.column(i).into_owned(), b.axes.column(i).into_owned()]);
    let edges = (0..9).map(|k| a.axes.column(k / 3).cross(&b.axes.column(k % 3)));
    let mut least = Real::MAX;
    for axis in faces.chain(edges) {
        let norm = axis.norm();
        if norm < 1e-6 {
            continue;
        }
        let l = axis / norm;
        let overlap = a.reach(&l) + b.reach(&l) - d.dot(&l).abs();
        if overlap <= 0.0 {
            return 0.0;
        }
        least = least.min(overlap);
    }
    least
}

/// A ball holding `block` (of link `link`) in every state of the joints from `link` up to
/// its ancestor `above`, in the frame of `above`.
fn swept_ball(
    object: &ArticulatedObject,
    parents: &[Option<usize>],
    block: &Block,
    mut link: usize,
    above: usize,
) -> (Point3, Real) {
    let (mut centre, mut radius) = (block.centre(), block.half().norm());
    while link != above {
        let Some(j) = parents[link] else { break };
        let joint = &object.joints[j];
        let (lo, hi) = joint.limits;
        match joint.kind {
            JointKind::Revolute => {
                let foot = joint.pivot + joint.axis * (centre - joint.pivot).dot(&joint.axis);
                let arm = (centre - foot).norm();
                let half_span = 0.5 * (hi - lo);
                if half_span >= std::f32::consts::FRAC_PI_2 || arm < 1e-6 {
                    centre = foot;
                    radius += arm;
                } else {
                    // The arc's chord midpoint holds the arc within arm * sin(half span).
                    let middle = rotation_about(&joint.pivot, &joint.axis, lo + half_span) * centre;
                    centre = foot + (middle - foot) * half_span.cos();
                    radius += arm * half_span.sin();
                }
            }
            JointKind::Prismatic => {
                centre += joint.axis * 0.5 * (lo + hi);
                radius += 0.5 * (hi - lo);
            }
        }
        link = joint.parent;
    }
    (centre, radius)
}

/// The motions of `joint` tried: `steps` even steps over its limits, and its rest value.
fn grid(joint: &Joint, steps: usize) -> Vec<Isometry3> {
    let (lo, hi) = joint.limits;
    let mut values: Vec<Real> =
        (0..=steps).map(|i| lo + (hi - lo) * i as Real / steps as Real).collect();
    if !values.contains(&joint.rest) {
        values.push(joint.rest);
    }
    values.into_iter().map(|v| joint_motion(joint, v)).collect()
}

/// Whether two links overlap deeper than `tolerance` anywhere on a grid of the joints
/// between them (the joints on the tree path from one to the other), the grid coarser
/// where more joints combine. Only pairs of boxes whose swept balls meet are tested.
pub(super) fn collides(object: &ArticulatedObject, blocks: &[Vec<Block>], tolerance: Real) -> bool {
    let parents = object.parent_joints();
    let chain = |mut link: usize| {
        let mut links = vec![link];
        while let Some(j) = parents[link] {
            link = object.joints[j].parent;
            links.push(link);
        }
        links
    };
    let chains: Vec<Vec<usize>> = (0..blocks.len()).map(chain).collect();
    (0..blocks.len()).any(|a| {
        (a + 1..blocks.len()).any(|b| {
            let meet = chains[a].iter().copied().find(|l| chains[b].contains(l)).unwrap_or(0);
            let ball = |link: usize, k: &Block| swept_ball(object, &parents, k, link, meet);
            let near: Vec<(usize, usize)> = (0..blocks[a].len())
                .flat_map(|i| (0..blocks[b].len()).map(move |j| (i, j)))
                .filter(|&(i, j)| {
                    let ((ca, ra), (cb, rb)) = (ball(a, &blocks[a][i]), ball(b, &blocks[b][j]));
                    (ca - cb).norm() < ra + rb
                })
                .collect();
            // The joints from `meet` down to each link, top first: a link's pose relative
            // to `meet` is the product of their motions in that order.
            let down = |link: usize| -> Vec<usize> {
                let up = chains[link].iter().take_while(|&&l| l != meet);
                let mut joints: Vec<usize> = up.filter_map(|&l| parents[l]).collect();
                joints.reverse();
                joints
            };
            let (down_a, down_b) = (down(a), down(b));
            let steps = match down_a.len() + down_b.len() {
                1 => 6,
                2 => 4,
                3 => 2,
                _ => 1,
            };
            let grids: Vec<Vec<Isometry3>> =
                down_a.iter().chain(&down_b).map(|&j| grid(&object.joints[j], steps)).collect();
            !near.is_empty()
                && any_combination(&grids, |motions| {
                    let pose = |ms: &[Isometry3]| {
                        ms.iter().fold(Isometry3::identity(), |pose, m| pose * m)
                    };
                    let (pose_a, pose_b) =
                        (pose(&motions[..down_a.len()]), pose(&motions[down_a.len()..]));
                    let (pa, pb) = (Posed::new(&pose_a), Posed::new(&pose_b));
                    near.iter().any(|&(i, j)| {
                        let (x, y) = (pa.place(&blocks[a][i]), pb.place(&blocks[b][j]));
                        let apart = (x.centre - y.centre).norm() >= x.half.norm() + y.half.norm();
                        !apart && depth(&x, &y) > tolerance
                    })
                })
        })
    })
}

/// Whether `test` holds for some choice of one motion from each grid.
fn any_combination(grids: &[Vec<Isometry3>], mut test: impl FnMut(&[Isometry3]) -> bool) -> bool {
    let mut digits = vec![0; grids.len()];
    let mut motions: Vec<Isometry3> = grids.iter().map(|g| g[0]).collect();
    loop {
        if test(&motions) {
            return true;
        }
        // The next combination, counting in mixed radix.
        let Some(k) = (0..grids.len()).find(|&k| digits[k] + 1 < grids[k].len()) else {
            return false;
        };
        digits[k] += 1;
        for i in 0..k {
            digits[i] = 0;
            motions[i] = grids[i][0];
        }
        motions[k] = grids[k][digits[k]];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seed::{rng_for, Stream};
    use parry3d::query;
    use parry3d::shape::Cuboid;
    use rand::Rng as _;

    #[test]
    fn box_depth_is_parrys_penetration_depth() {
        let mut rng = rng_for(7, 0, Stream::Object);
        let mut overlapping = 0;
        for _ in 0..200 {
            let draw = |rng: &mut crate::seed::Rng| {
                let half = Vector3::from_fn(|_, _| rng.random_range(0.1..0.5));
                let centre = Vector3::from_fn(|_, _| rng.random_range(-0.4..0.4));
                let turn = Vector3::from_fn(|_, _| rng.random_range(-1.5..1.5));
                (
                    Block { min: Point3::from(-half), max: Point3::from(half) },
                    Isometry3::new(centre, turn),
                )
            };
            let ((a, pose_a), (b, pose_b)) = (draw(&mut rng), draw(&mut rng));
            let ours = depth(&Posed::new(&pose_a).place(&a), &Posed::new(&pose_b).place(&b));
            let (ca, cb) = (Cuboid::new(a.half()), Cuboid::new(b.half()));
            let contact =
                query::contact(&pose_a, &ca, &pose_b, &cb, 0.0).expect("boxes are convex");
            let theirs = contact.map_or(0.0, |c| (-c.dist).max(0.0));
            assert!((ours - theirs).abs() < 1e-3, "{ours} vs {theirs}");
            overlapping += usize::from(theirs > 0.0);
        }
        assert!(overlapping > 20, "{overlapping}");
    }
}
