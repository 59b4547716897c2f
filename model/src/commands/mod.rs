//! The `model` binary's commands, one file each: the arguments (`clap`) beside the body,
//! so `src/main.rs` only parses and dispatches and any caller (a test, a script, another
//! binary) runs a command as a library call. Like a binary's, the bodies return
//! [`anyhow::Result`] with context naming the file and the flag; the library's own modules
//! below them return typed errors.
//!
//! - [`train`]: train stage by stage, or resume (`model train`).
//! - [`validate`]: score a weights folder on the validation pairs, or two of them paired
//!   with a bootstrap interval (`model validate`).
//! - [`diagnose`]: the oracle-substitution table ([`crate::diagnose`], `model diagnose`).
//! - [`procedures`]: the iterative procedure's variants side by side
//!   ([`crate::procedures`], `model procedures`).
//! - [`average`]: the parameter-wise mean of weights folders (`model average`).
//! - [`infer`]: the inference procedure on a user's two files or a dataset pair, described
//!   and written as coloured PLYs or an animated glTF (`model infer`, `model animate`).

pub mod average;
pub mod diagnose;
pub mod infer;
pub mod procedures;
mod shared;
pub mod train;
pub mod validate;
