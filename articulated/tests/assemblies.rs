//! Random assemblies against the exact convex plausibility checks of `articulated::check`
//! (from outside the crate: the object library does not reach up into the checks).

use articulated::check::LinkShapes;
use articulated::kinematics::link_poses;
use articulated::objects::assembly::{random_assembly, AssemblyParams};
use articulated::seed::{rng_for, Stream};
use pairs::math::Real;

#[test]
fn assemblies_pass_the_exact_convex_checks_at_their_limits() {
    let params = AssemblyParams::default();
    for seed in 0..40 {
        let object = random_assembly(&mut rng_for(seed, 0, Stream::Object), &params);
        let shapes = LinkShapes::new(&object);
        let size = shapes.size();
        let lows: Vec<Real> = object.joints.iter().map(|j| j.limits.0).collect();
        let highs: Vec<Real> = object.joints.iter().map(|j| j.limits.1).collect();
        for state in [lows, highs] {
            let poses = link_poses(&object, &state);
            let gaps = shapes.joint_gaps(&object, &poses, 0.01 * size);
            assert!(gaps.iter().all(Option::is_none), "{gaps:?} at {state:?}");
            let hit = shapes.deepest_penetration(&poses, 0.02 * size);
            assert_eq!(hit, None, "seed {seed} at {state:?}");
        }
    }
}
