//! The procedural category library: one file per category, one line per category here.

mod cabinet;
mod laptop;
mod scissors;

use crate::objects::ArticulatedObject;
use crate::seed::Rng;

/// A procedural category: a name and a builder of random instances.
#[derive(Debug, Clone, Copy)]
pub struct Category {
    /// Name used in configs, manifests and provenance.
    pub name: &'static str,
    /// One sentence on what the objects look like and how they move.
    pub description: &'static str,
    /// Builds one random instance; the same generator state gives the same object.
    pub build: fn(&mut Rng) -> ArticulatedObject,
}

/// Every built-in category, in a fixed order.
pub const CATEGORIES: &[Category] = &[laptop::CATEGORY, cabinet::CATEGORY, scissors::CATEGORY];

/// The built-in category called `name`.
pub fn find(name: &str) -> Option<&'static Category> {
    CATEGORIES.iter().find(|c| c.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seed::{rng_for, Stream};

    #[test]
    fn every_category_builds_valid_varied_objects() {
        for category in CATEGORIES {
            let a = (category.build)(&mut rng_for(0, 0, Stream::Object));
            let b = (category.build)(&mut rng_for(0, 1, Stream::Object));
            a.validate().unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(a.category, category.name);
            assert!(!a.joints.is_empty(), "{} has no joint", category.name);
            assert_ne!(
                a.links[0].mesh, b.links[0].mesh,
                "{} proportions do not vary",
                category.name
            );
            assert_eq!(a, (category.build)(&mut rng_for(0, 0, Stream::Object)));
        }
    }
}
