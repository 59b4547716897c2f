//! The default config is the paper's protocol: 175 objects of the held-out test categories,
//! balanced, giving exactly 875 pairs.

use std::collections::BTreeMap;

use articulated::categories::{of_split, Split};
use generator::config::GeneratorConfig;
use generator::generate::object_pairs;
use rayon::prelude::*;

#[test]
fn the_default_protocol_gives_875_pairs_of_175_balanced_test_objects() {
    let config = GeneratorConfig::default();
    assert_eq!(config.split, Split::Test);
    let per_object: Vec<usize> = (0..config.objects)
        .into_par_iter()
        .map(|i| object_pairs(&config, i).map(|pairs| pairs.len()))
        .collect::<Result<_, _>>()
        .expect("every object gives its pairs");
    assert_eq!(per_object.len(), 175);
    assert_eq!(per_object.iter().sum::<usize>(), 875);
    let mut objects: BTreeMap<String, u32> = BTreeMap::new();
    for i in 0..config.objects {
        let object = generator::generate::build_object(&config, i).expect("object");
        *objects.entry(object.category).or_default() += 1;
    }
    let test: Vec<&str> = of_split(Split::Test).iter().map(|c| c.name).collect();
    assert_eq!(objects.keys().map(String::as_str).collect::<Vec<_>>(), {
        let mut sorted = test.clone();
        sorted.sort_unstable();
        sorted
    });
    let (least, most) = (objects.values().min(), objects.values().max());
    assert!(most.zip(least).is_some_and(|(m, l)| m - l <= 1), "unbalanced: {objects:?}");
}
