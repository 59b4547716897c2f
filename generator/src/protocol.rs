//! The paper's test protocol: per object, random articulation states within the joint
//! limits, pairs of two different states, and a random global pose per shape.

use pairs::math::{Isometry3, Real, Vector3};
use rand::seq::SliceRandom;
use rand::Rng as _;

use articulated::objects::ArticulatedObject;
use articulated::seed::Rng;

/// Draws one articulation state: each joint sits at its rest value with probability
/// `rest_probability` (a closed door), else uniformly within its limits; mimic joints then
/// follow their leaders (their own draws are discarded, so the stream stays aligned).
pub fn draw_state(object: &ArticulatedObject, rest_probability: f64, rng: &mut Rng) -> Vec<Real> {
    let mut values: Vec<Real> = object
        .joints
        .iter()
        .map(|j| {
            if rng.random_bool(rest_probability) {
                j.rest
            } else {
                rng.random_range(j.limits.0..=j.limits.1)
            }
        })
        .collect();
    object.follow_mimics(&mut values);
    values
}

/// Every unordered pair of states that differ in at least one joint, shuffled, each
/// randomly oriented (which state is P).
pub fn candidate_pairs(states: &[Vec<Real>], rng: &mut Rng) -> Vec<(usize, usize)> {
    let mut pairs: Vec<(usize, usize)> = (0..states.len())
        .flat_map(|i| (i + 1..states.len()).map(move |j| (i, j)))
        .filter(|&(i, j)| states[i] != states[j])
        .collect();
    pairs.shuffle(rng);
    pairs.into_iter().map(|(i, j)| if rng.random_bool(0.5) { (i, j) } else { (j, i) }).collect()
}

/// A random global pose: a rotation of up to `max_rotation_deg` about a uniform random axis,
/// and a translation of up to `max_translation` (object units) along each coordinate.
pub fn global_pose(max_rotation_deg: Real, max_translation: Real, rng: &mut Rng) -> Isometry3 {
    let axis = loop {
        let v = Vector3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        );
        let n = v.norm();
        if n > 1e-3 && n <= 1.0 {
            break v / n;
        }
    };
    let angle = rng.random_range(0.0..=max_rotation_deg.to_radians());
    let t = if max_translation > 0.0 {
        Vector3::from_fn(|_, _| rng.random_range(-max_translation..=max_translation))
    } else {
        Vector3::zeros()
    };
    Isometry3::new(t, axis * angle)
}

#[cfg(test)]
mod tests {
    use super::*;
    use articulated::categories::CATEGORIES;
    use articulated::seed::{rng_for, Stream};

    #[test]
    fn states_respect_limits_and_pairs_differ() {
        let object = (CATEGORIES[1].build)(&mut rng_for(3, 0, Stream::Object));
        let mut rng = rng_for(3, 0, Stream::States);
        let states: Vec<_> = (0..10).map(|_| draw_state(&object, 0.3, &mut rng)).collect();
        for s in &states {
            for (v, j) in s.iter().zip(&object.joints) {
                assert!(j.limits.0 <= *v && *v <= j.limits.1);
            }
        }
        let pairs = candidate_pairs(&states, &mut rng);
        assert!(pairs.len() >= 5);
        assert!(pairs.iter().all(|&(i, j)| i != j && states[i] != states[j]));
    }

    #[test]
    fn global_pose_stays_within_bounds() {
        let mut rng = rng_for(0, 0, Stream::Pair(0));
        for _ in 0..100 {
            let pose = global_pose(15.0, 0.05, &mut rng);
            assert!(pose.rotation.angle() <= 15f32.to_radians() + 1e-5);
            assert!(pose.translation.vector.amax() <= 0.05);
        }
    }
}
