//! An object's pairs, per the paper's protocol: its states, the candidate pairs between
//! them, each side observed and labelled; for cross-instance sets, Q observes a second
//! instance of the category.

use pairs::math::Isometry3;
use pairs::scan::PairImages;
use pairs::{Pair, PairKind};
use rand::Rng as _;

use crate::config::GeneratorConfig;
use crate::generate::object::draw_states;
use crate::generate::pair::{make_pair, Partner, Scene, State};
use crate::generate::{build_object, GenerateError};
use crate::label::{same_structure, Parts};
use crate::protocol::candidate_pairs;
use articulated::objects::ArticulatedObject;
use articulated::sampling::SurfaceSampler;
use articulated::seed::{rng_for, Stream};

/// Second instances tried per object of a cross-instance set before the object is left
/// out: each is built from its own seed and kept when it has the same links and joints by
/// name and gives the pairs wanted.
pub const PARTNER_ATTEMPTS: u32 = 16;

/// A generated pair with the scene it was made from, for checks against the meshes.
#[derive(Debug, Clone)]
pub struct GeneratedPair {
    /// The pair.
    pub pair: Pair,
    /// Link poses of P's shape (rest frame to P's object frame, global pose included).
    pub poses_p: Vec<Isometry3>,
    /// Link poses of Q's shape.
    pub poses_q: Vec<Isometry3>,
    /// Which links form which part.
    pub parts: Parts,
    /// PNG images of the scanned sides (empty for full shapes, or when not asked for).
    pub images: PairImages,
}

/// All pairs of object `index`, per the paper's protocol, with the images of their scans.
pub fn object_pairs(
    config: &GeneratorConfig,
    index: u32,
) -> Result<Vec<GeneratedPair>, GenerateError> {
    object_pairs_with(config, index, Variant { index: 0, kind: config.kind, images: true })
}

/// Which rendition of an object's pairs to make: the training stream makes several scanned
/// variants of the same shapes, each from its own viewpoints, without images.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Variant {
    /// 0 for a dataset's own pairs; 1, 2, ... for extra scanned renditions.
    pub index: u32,
    /// Kind of the pairs.
    pub kind: PairKind,
    /// Whether to encode the scans' PNG images.
    pub images: bool,
}

/// The pairs of object `index` in one [`Variant`]. A cross-instance object without a
/// second instance to match is an error ([`GenerateError::NoPartner`]); datasets leave such
/// objects out instead ([`dataset_object_pairs`]).
pub fn object_pairs_with(
    config: &GeneratorConfig,
    index: u32,
    variant: Variant,
) -> Result<Vec<GeneratedPair>, GenerateError> {
    let object = build_object(config, index)?;
    if !variant.kind.cross_instance() {
        return pairs_of_object(config, &object, index, variant);
    }
    cross_pairs_of_object(config, &object, index, variant)?.ok_or_else(|| {
        GenerateError::NoPartner { object: index, category: object.category.clone() }
    })
}

/// The pairs object `index` contributes to a dataset: `None` when it is a cross-instance
/// object left out (no second instance of its category matched it part for part).
pub fn dataset_object_pairs(
    config: &GeneratorConfig,
    index: u32,
) -> Result<Option<Vec<GeneratedPair>>, GenerateError> {
    match object_pairs(config, index) {
        Err(GenerateError::NoPartner { .. }) => Ok(None),
        other => other.map(Some),
    }
}

/// The pairs of an already built `object` as object `index` of a dataset (user assets
/// come here with their object built by `assets`).
pub fn pairs_of_object(
    config: &GeneratorConfig,
    object: &ArticulatedObject,
    index: u32,
    variant: Variant,
) -> Result<Vec<GeneratedPair>, GenerateError> {
    pairs_with(config, object, None, index, variant)
}

/// The cross-instance pairs of `object` as object `index`: P observes it, Q the first of
/// [`PARTNER_ATTEMPTS`] second instances (object `index` of the config under a seed drawn
/// from [`Stream::Partner`]) that has the same links and joints by name and gives the
/// pairs wanted; `None` when none does.
pub fn cross_pairs_of_object(
    config: &GeneratorConfig,
    object: &ArticulatedObject,
    index: u32,
    variant: Variant,
) -> Result<Option<Vec<GeneratedPair>>, GenerateError> {
    for attempt in 0..PARTNER_ATTEMPTS {
        let seed = rng_for(config.seed, u64::from(index), Stream::Partner(attempt)).random();
        let other = build_object(&GeneratorConfig { seed, ..config.clone() }, index)?;
        if !same_structure(object, &other) {
            continue;
        }
        let sampler = SurfaceSampler::new(&other);
        let partner = Partner { object: &other, sampler: &sampler, seed };
        match pairs_with(config, object, Some(partner), index, variant) {
            Err(GenerateError::TooFewPairs { .. }) => continue,
            other => return other.map(Some),
        }
    }
    Ok(None)
}

/// The pairs of `object`, with Q observing `partner` in a cross-instance set. Q's states
/// are the partner's own (drawn from its seed's [`Stream::States`]), so that
/// `articulation_q` indexes them as `articulation_p` indexes P's.
fn pairs_with(
    config: &GeneratorConfig,
    object: &ArticulatedObject,
    partner: Option<Partner>,
    index: u32,
    variant: Variant,
) -> Result<Vec<GeneratedPair>, GenerateError> {
    let sampler = SurfaceSampler::new(object);
    let mut rng = rng_for(config.seed, u64::from(index), Stream::States);
    let states = draw_states(config, object, &mut rng);
    let partner_states = partner.map(|o| {
        draw_states(config, o.object, &mut rng_for(o.seed, u64::from(index), Stream::States))
    });
    let states_q = partner_states.as_deref().unwrap_or(&states);
    let wanted = config.pairs_per_object as usize;
    let mut pairs = Vec::with_capacity(wanted);
    let scene = Scene { config, object, sampler: &sampler, index, variant, partner };
    for (candidate, (i, j)) in candidate_pairs(&states, &mut rng).into_iter().enumerate() {
        if pairs.len() == wanted {
            break;
        }
        let candidate = candidate as u32;
        let mut rng = rng_for(config.seed, u64::from(index), Stream::Pair(candidate));
        let (p, q) =
            (State { index: i, values: &states[i] }, State { index: j, values: &states_q[j] });
        if let Some(pair) = make_pair(&scene, (pairs.len(), candidate), p, q, &mut rng)? {
            pairs.push(pair);
        }
    }
    if pairs.len() < wanted {
        return Err(GenerateError::TooFewPairs {
            object: index,
            category: object.category.clone(),
            found: pairs.len(),
            wanted,
            min: config.min_part_points,
        });
    }
    Ok(pairs)
}
