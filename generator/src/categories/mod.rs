//! The procedural category library: one file per category, one line per category here.

mod catalog;

mod box_with_lid;
mod cabinet;
mod laptop;
mod mailbox;
mod piano;
mod scissors;
mod suitcase;
mod toilet;
mod toolbox;
mod trash_can;
mod usb_stick;

pub use catalog::{find, of_split, split_table, Category, Split};

/// Every built-in category of every split, in a fixed order.
pub const CATEGORIES: &[Category] = &[
    // Test categories (laptop is shared with training, as in the paper).
    laptop::CATEGORY,
    cabinet::CATEGORY,
    scissors::CATEGORY,
    box_with_lid::CATEGORY,
    trash_can::CATEGORY,
    toilet::CATEGORY,
    suitcase::CATEGORY,
    usb_stick::CATEGORY,
    // Training categories.
    piano::CATEGORY,
    mailbox::CATEGORY,
    // Validation categories.
    toolbox::CATEGORY,
];
