//! The procedural category library: one file per category, one line per category here.

mod catalog;

mod assembly;
mod book;
mod box_with_lid;
mod cabinet;
mod car;
mod desk_lamp;
mod dishwasher;
mod excavator;
mod eyeglasses;
mod fan;
mod faucet;
mod flip_phone;
mod folding_chair;
mod folding_knife;
mod folding_table;
mod laptop;
mod mailbox;
mod microwave;
mod oven;
mod piano;
mod pliers;
mod printer;
mod refrigerator;
mod robot_arm;
mod safe;
mod scissors;
mod seesaw;
mod sliding_window;
mod stapler;
mod step_ladder;
mod suitcase;
mod swivel_chair;
mod toilet;
mod toolbox;
mod trash_can;
mod usb_stick;
mod wardrobe;
mod washing_machine;
mod windmill;

pub use catalog::{find, of_split, split_table, Category, Split};

/// Every built-in category of every split, in a fixed order.
pub const CATEGORIES: &[Category] = &[
    // Test categories (laptop is shared with training, as in the paper).
    laptop::CATEGORY,
    cabinet::CATEGORY,
    scissors::CATEGORY,
    box_with_lid::CATEGORY,
    car::CATEGORY,
    desk_lamp::CATEGORY,
    eyeglasses::CATEGORY,
    fan::CATEGORY,
    faucet::CATEGORY,
    flip_phone::CATEGORY,
    folding_chair::CATEGORY,
    folding_knife::CATEGORY,
    microwave::CATEGORY,
    oven::CATEGORY,
    pliers::CATEGORY,
    refrigerator::CATEGORY,
    seesaw::CATEGORY,
    sliding_window::CATEGORY,
    stapler::CATEGORY,
    suitcase::CATEGORY,
    swivel_chair::CATEGORY,
    toilet::CATEGORY,
    trash_can::CATEGORY,
    usb_stick::CATEGORY,
    washing_machine::CATEGORY,
    windmill::CATEGORY,
    // Training categories: random articulated assemblies, then everyday objects.
    assembly::CATEGORY,
    book::CATEGORY,
    dishwasher::CATEGORY,
    excavator::CATEGORY,
    folding_table::CATEGORY,
    mailbox::CATEGORY,
    piano::CATEGORY,
    robot_arm::CATEGORY,
    step_ladder::CATEGORY,
    wardrobe::CATEGORY,
    // Validation categories.
    printer::CATEGORY,
    safe::CATEGORY,
    toolbox::CATEGORY,
];
