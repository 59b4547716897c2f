//! The built-in objects to render or export (`generator render`, `generator export-objects`,
//! the evaluator's render benchmark), and the articulation states their folders list.

use rayon::prelude::*;

use crate::config::GeneratorConfig;
use crate::generate::{build_object, object_states, GenerateError};
use assets::{Source, SourcedObject};
use simulators::StateDraw;

/// The built-in objects a config selects (objects `0..config.objects`, categories in turn),
/// to render or export.
pub fn built_in_objects(config: &GeneratorConfig) -> Result<Vec<SourcedObject>, GenerateError> {
    (0..config.objects)
        .into_par_iter()
        .map(|i| {
            Ok(SourcedObject {
                object_id: i,
                object: build_object(config, i)?,
                source: Source::BuiltIn { split: config.split.as_str().into() },
                surfaces: Vec::new(),
            })
        })
        .collect()
}

/// The states an exported object folder lists (`states.json`): the dataset protocol's
/// states of each object, so that state `k` is articulation `k` of a dataset made with the
/// same config.
pub fn state_draw(config: &GeneratorConfig) -> StateDraw<'_> {
    StateDraw {
        seed: config.seed,
        rest_probability: config.rest_probability,
        draw: Box::new(|o: &SourcedObject| object_states(config, &o.object, o.object_id)),
    }
}
