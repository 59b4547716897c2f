//! Writing renders to disk: our own layout ([`native`]), or the folder trees PARIS
//! ([`paris`]), DigitalTwinArt ([`dta`]) and ArtGS ([`artgs`]) read. Every layout is written into a
//! staging folder and swapped into place when complete (an interrupted render never
//! changes what was there), views in parallel, objects one after another.

pub mod artgs;
pub mod dta;
mod files;
pub mod gt;
mod kind;
pub mod native;
pub mod paris;
mod write;

pub(crate) use files::{u16_bytes, write_bytes, write_json, write_png};
pub use kind::Layout;
pub(crate) use write::{each_view, two_states};
pub use write::{write_render, Rendered};

/// Version of the native layout, in `render.json`.
pub const RENDER_FORMAT_VERSION: u32 = 2;
