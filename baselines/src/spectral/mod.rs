//! Spectral clustering of a flow's rigidity affinities (the paper's SC baseline).

pub mod affinity;
pub mod embedding;
pub mod kmeans;
pub mod segmenter;

pub use affinity::{affinity_flow, estimate_pair_scale, transport_normals};
pub use embedding::{embed_spectral, Embedding};
pub use kmeans::cluster_kmeans;
pub use segmenter::{segment_spectral, Spectral, SpectralError, SpectralParams};
