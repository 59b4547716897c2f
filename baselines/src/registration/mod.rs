//! Flow by registration of P onto Q: nearest neighbours, rigid ICP, embedded deformation
//! (ED) and non-rigid registration with part clustering (NRR), on a shared deformation
//! graph and closest-point correspondences.

pub mod correspondence;
pub mod embedded;
pub mod graph;
pub mod nearest;
pub mod nonrigid;
pub mod rigid;
pub mod solve;

pub use correspondence::{match_closest, mean_closest_distance, Matches};
pub use embedded::{register_embedded_deformation, EdError, EdParams, EmbeddedDeformation};
pub use graph::{build_graph, DeformationGraph, NodeTransform};
pub use nearest::{flow_nearest, NearestError, NearestFlow};
pub use nonrigid::{register_nonrigid_graph, Nrr, NrrError, NrrParams, NrrResult};
pub use rigid::{register_rigid_icp, IcpError, IcpFlow, IcpParams};
pub use solve::{rotation_procrustes, NormalEquations};
