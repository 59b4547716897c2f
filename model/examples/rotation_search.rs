//! The 48-rotation search with the shipped weights on pairs whose Q is P under a random
//! global rotation: prints, per pair, the angle between the chosen rotation and the true
//! one, against the search's resolution (the set's covering radius, 67°).
//!
//! `cargo run --release -p model --example rotation_search -- 20`

use std::path::Path;

use model::inference::rotation_search::COVERING_RADIUS_DEG;
use model::train::validation::validation_pairs;
use model::weights;
use pairs::math::{Point3, UnitQuaternion};
use pairs::transform::rotation_error_deg;
use pairs::Cloud;
use rand::{Rng, SeedableRng};

fn main() -> anyhow::Result<()> {
    let count: u32 = std::env::args().nth(1).map_or(Ok(20), |a| a.parse())?;
    let weights = Path::new(env!("CARGO_MANIFEST_DIR")).join("weights/cpu");
    let net = weights::load(&weights)?.net;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
    let mut within = 0;
    let mut errors = Vec::new();
    for pair in validation_pairs(512, count, false)? {
        let (u1, u2, u3): (f32, f32, f32) = (rng.random(), rng.random(), rng.random());
        let tau = std::f32::consts::TAU;
        let truth = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
            (1.0 - u1).sqrt() * (tau * u2).sin(),
            (1.0 - u1).sqrt() * (tau * u2).cos(),
            u1.sqrt() * (tau * u3).sin(),
            u1.sqrt() * (tau * u3).cos(),
        ))
        .to_rotation_matrix()
        .into_inner();
        let mut input = pair.input().clone();
        let turned: Vec<Point3> =
            input.p.points.iter().map(|x| Point3::from(truth * x.coords)).collect();
        input.q = Cloud::normalise(&turned).expect("a turned cloud is not degenerate");
        let search = net.search_rotation(&input)?;
        let error = rotation_error_deg(&search.rotation, &truth);
        within += usize::from(error <= COVERING_RADIUS_DEG);
        errors.push(error);
        println!("{}: chosen rotation {error:.1}° from the truth", pair.id());
    }
    errors.sort_by(f32::total_cmp);
    println!(
        "{within} of {} within the {COVERING_RADIUS_DEG}° resolution; median error {:.1}°",
        errors.len(),
        errors[errors.len() / 2]
    );
    Ok(())
}
