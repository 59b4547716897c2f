//! Hand-crafted point descriptors and matching in descriptor space.

pub mod fpfh;

pub use fpfh::{
    describe_fpfh, flow_fpfh, match_descriptors, match_fpfh, FpfhError, FpfhFlow, FpfhParams,
    FPFH_BINS,
};
