//! The procedural category library: one file per category, one line per category here.

mod catalog;

mod book;
mod cabinet;
mod eyeglasses;
mod flip_phone;
mod folding_knife;
mod folding_table;
mod laptop;
mod pliers;
mod printer;
mod scissors;
mod stapler;
mod step_ladder;

pub use catalog::{find, of_split, split_table, Category, Split};

/// Every built-in category of every split, in a fixed order.
pub const CATEGORIES: &[Category] = &[
    // Test categories (laptop is shared with training, as in the paper).
    laptop::CATEGORY,
    cabinet::CATEGORY,
    scissors::CATEGORY,
    pliers::CATEGORY,
    folding_knife::CATEGORY,
    flip_phone::CATEGORY,
    eyeglasses::CATEGORY,
    stapler::CATEGORY,
    // Training categories.
    book::CATEGORY,
    folding_table::CATEGORY,
    step_ladder::CATEGORY,
    // Validation categories.
    printer::CATEGORY,
];
