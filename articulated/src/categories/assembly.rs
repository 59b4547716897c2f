//! Assembly: a random tree of primitives (a box, round prism or bevelled block with boxes
//! grown on its faces) of which 2 to 6 segments hinge, twist or slide out of a sleeve: the
//! paper's category-free training data.

use super::catalog::{Category, TRAIN};
use crate::objects::assembly::{random_assembly, AssemblyParams};
use crate::objects::ArticulatedObject;
use crate::seed::Rng;

/// The assembly category.
pub const CATEGORY: Category = Category {
    name: "assembly",
    description: "random tree of primitives; 2 to 6 segments hinge or twist about their contact or slide out of a sleeve (1 : 3)",
    splits: TRAIN,
    build,
};

fn build(rng: &mut Rng) -> ArticulatedObject {
    random_assembly(rng, &AssemblyParams::default())
}
