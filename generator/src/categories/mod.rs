//! The procedural category library: one file per category, one line per category here.

mod catalog;

mod cabinet;
mod car;
mod dishwasher;
mod laptop;
mod microwave;
mod oven;
mod refrigerator;
mod safe;
mod scissors;
mod sliding_window;
mod wardrobe;
mod washing_machine;

pub use catalog::{find, of_split, split_table, Category, Split};

/// Every built-in category of every split, in a fixed order.
pub const CATEGORIES: &[Category] = &[
    // Test categories (laptop is shared with training, as in the paper).
    laptop::CATEGORY,
    cabinet::CATEGORY,
    scissors::CATEGORY,
    refrigerator::CATEGORY,
    microwave::CATEGORY,
    oven::CATEGORY,
    washing_machine::CATEGORY,
    sliding_window::CATEGORY,
    car::CATEGORY,
    // Training categories.
    wardrobe::CATEGORY,
    dishwasher::CATEGORY,
    // Validation categories.
    safe::CATEGORY,
];
