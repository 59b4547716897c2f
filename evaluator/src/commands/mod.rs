//! The evaluator's commands as library calls: the whole evaluation ([`pipeline`]) and
//! `evaluator score` / `evaluator predict` on prediction files ([`files`]).

pub mod files;
pub mod pipeline;
