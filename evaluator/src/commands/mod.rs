//! The evaluator's commands as library calls: the whole evaluation ([`pipeline`]),
//! `evaluator score` / `evaluator predict` on prediction files ([`files`]), one row's
//! predictions ([`predict`]), the binary's
//! arguments and their dispatch ([`entry`]) and the progress bars ([`bars`]).

pub mod bars;
pub mod entry;
pub mod files;
pub mod pipeline;
pub mod predict;
