//! The segmentation module (the paper's 4.3): [`hypotheses`] proposes a rigid motion per
//! point of P from the flow, [`support`] scores each hypothesis's support over P, and
//! [`rpen`], the recurrent part proposal network, picks one segment per step from them.

pub mod hypotheses;
pub mod rpen;
pub mod support;
