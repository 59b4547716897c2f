//! Object `index` of a dataset: built from its category and seed, and its articulation
//! states.

use pairs::math::Real;

use crate::config::GeneratorConfig;
use crate::generate::GenerateError;
use crate::protocol::draw_state;
use articulated::objects::ArticulatedObject;
use articulated::seed::{rng_for, Rng, Stream};

/// Builds object `index` of a dataset: its category comes in turn from the config.
pub fn build_object(
    config: &GeneratorConfig,
    index: u32,
) -> Result<ArticulatedObject, GenerateError> {
    let categories = config.categories()?;
    let category = categories[index as usize % categories.len()];
    let object = (category.build)(&mut rng_for(config.seed, u64::from(index), Stream::Object));
    object.validate().map_err(|source| GenerateError::Object { object: index, source })?;
    Ok(object)
}

/// The articulation states of object `index` (one value per joint each): the states its
/// pairs are drawn between, which `provenance.articulation_p` and `_q` index.
pub fn object_states(
    config: &GeneratorConfig,
    object: &ArticulatedObject,
    index: u32,
) -> Vec<Vec<Real>> {
    draw_states(config, object, &mut rng_for(config.seed, u64::from(index), Stream::States))
}

/// The object's states, drawn from `rng` (the start of its [`Stream::States`]).
pub(super) fn draw_states(
    config: &GeneratorConfig,
    object: &ArticulatedObject,
    rng: &mut Rng,
) -> Vec<Vec<Real>> {
    (0..config.states_per_object)
        .map(|_| draw_state(object, config.rest_probability, rng))
        .collect()
}

/// Extra draws past the object's `states_per_object` states allowed to find K distinct
/// ones.
const EXTRA_STATES: usize = 64;

/// The states a set draws its views from: the object's states (what pairs'
/// `articulation_p` / `_q` index), continued with the same stream's next draws while fewer
/// than `views` of them are distinct (a simple object may sit at rest in most of its
/// states), so that state `i` is the same state for pairs and sets.
pub fn set_states(
    config: &GeneratorConfig,
    object: &ArticulatedObject,
    index: u32,
    views: usize,
) -> Vec<Vec<Real>> {
    let mut rng = rng_for(config.seed, u64::from(index), Stream::States);
    let mut states: Vec<Vec<Real>> = Vec::new();
    let distinct = |states: &[Vec<Real>]| {
        states.iter().enumerate().filter(|(i, s)| !states[..*i].contains(s)).count()
    };
    while states.len() < config.states_per_object as usize
        || (distinct(&states) < views
            && states.len() < config.states_per_object as usize + EXTRA_STATES)
    {
        states.push(draw_state(object, config.rest_probability, &mut rng));
    }
    states
}
