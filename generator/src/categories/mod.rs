//! The procedural category library: one file per category, one line per category here.

mod catalog;

mod cabinet;
mod desk_lamp;
mod excavator;
mod fan;
mod faucet;
mod folding_chair;
mod laptop;
mod robot_arm;
mod scissors;
mod seesaw;
mod swivel_chair;
mod windmill;

pub use catalog::{find, of_split, split_table, Category, Split};

/// Every built-in category of every split, in a fixed order.
pub const CATEGORIES: &[Category] = &[
    // Test categories (laptop is shared with training, as in the paper).
    laptop::CATEGORY,
    cabinet::CATEGORY,
    scissors::CATEGORY,
    swivel_chair::CATEGORY,
    folding_chair::CATEGORY,
    desk_lamp::CATEGORY,
    faucet::CATEGORY,
    seesaw::CATEGORY,
    windmill::CATEGORY,
    fan::CATEGORY,
    // Training categories.
    robot_arm::CATEGORY,
    excavator::CATEGORY,
    // Validation categories.
];
