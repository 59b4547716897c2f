//! The `generator` binary's commands as library calls: the arguments ([`args`]), their
//! dispatch ([`run()`]: datasets, the gallery, the category list), the exports and shard
//! merge with the progress bars and report every command shares (`objects`), and the
//! renders (`render`). `src/bin/generator/main.rs` parses [`Args`] and calls [`run()`];
//! like a binary's, these return [`anyhow::Result`] with context naming the file and flag.

pub mod args;
pub(crate) mod objects;
pub(crate) mod render;
mod run;

pub use args::Args;
pub use run::run;
