//! The procedural category library: one file per category, one line per category here.

mod catalog;

mod assembly;
mod cabinet;
mod laptop;
mod scissors;

pub use catalog::{find, of_split, split_table, Category, Split};

/// Every built-in category of every split, in a fixed order.
pub const CATEGORIES: &[Category] = &[
    // Test categories (laptop is shared with training, as in the paper).
    laptop::CATEGORY,
    cabinet::CATEGORY,
    scissors::CATEGORY,
    // Training categories.
    assembly::CATEGORY,
    // Validation categories.
];
