use super::*;

#[test]
fn built_in_configs_parse_and_validate() {
    for (name, _) in BUILT_IN {
        let c = TrainConfig::built_in(name);
        assert_eq!(c.name, name);
    }
}

#[test]
fn every_config_file_parses_and_validates() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("configs");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).expect("the configs folder") {
        let path = entry.expect("an entry").path();
        if path.extension().is_some_and(|e| e == "toml") {
            let c = TrainConfig::load(path.to_str().expect("a UTF-8 path")).expect("valid");
            assert_eq!(path.file_stem().and_then(|s| s.to_str()), Some(c.name.as_str()));
            count += 1;
        }
    }
    assert!(count >= 4, "{count} configs in {}", dir.display());
}

#[test]
fn every_config_reads_back_equal_from_its_toml() {
    // What a weights folder's config.toml holds: every built-in and every shipped config,
    // ablations included, written by `to_toml` and read back.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("configs");
    let mut configs: Vec<TrainConfig> =
        BUILT_IN.iter().map(|(name, _)| TrainConfig::built_in(name)).collect();
    for dir in [root.clone(), root.join("ablations")] {
        for entry in std::fs::read_dir(&dir).expect("a configs folder") {
            let path = entry.expect("an entry").path();
            if path.extension().is_some_and(|e| e == "toml") {
                configs.push(TrainConfig::load(&path.to_string_lossy()).expect("valid"));
            }
        }
    }
    assert!(configs.len() > 20, "{} configs", configs.len());
    for c in configs {
        let text = c.to_toml().unwrap_or_else(|e| panic!("{}: {e}", c.name));
        let back = TrainConfig::from_toml(&text, &c.name).expect("reads back");
        assert_eq!(back, c, "{}:\n{text}", c.name);
    }
}

#[test]
fn errors_name_the_field() {
    let mut text = BUILT_IN[2].1.replace("batch = ", "batch = 0 #");
    let err = TrainConfig::from_toml(&text, "t").expect_err("batch 0").to_string();
    assert!(err.contains("batch"), "{err}");
    text = BUILT_IN[2].1.replace("seg_points = ", "seg_points = 100000 #");
    let err = TrainConfig::from_toml(&text, "t").expect_err("seg > corr").to_string();
    assert!(err.contains("network.seg_points"), "{err}");
    let err = TrainConfig::from_toml("name = 3", "t").expect_err("bad toml").to_string();
    assert!(err.contains("name"), "{err}");
}

#[test]
fn schedule_decays_to_a_floor_and_stages_follow_each_other() {
    let c = TrainConfig {
        learning_rate: 1e-4,
        decay: 0.5,
        decay_every_pairs: 10,
        min_learning_rate: 3e-5,
        stage1_pairs: 5,
        stage2_pairs: 5,
        ..TrainConfig::built_in("tiny")
    };
    assert_eq!(c.learning_rate_at(9), 1e-4);
    assert_eq!(c.learning_rate_at(10), 5e-5);
    assert_eq!(c.learning_rate_at(1000), 3e-5);
    assert_eq!((c.stage_at(4), c.stage_at(5), c.stage_at(10)), (1, 2, 3));
}

#[test]
fn cosine_warms_up_then_falls_to_the_floor_in_every_stage() {
    let c = TrainConfig {
        schedule: Schedule::Cosine,
        warmup_pairs: 10,
        learning_rate: 1e-3,
        min_learning_rate: 1e-5,
        stage1_pairs: 110,
        stage2_pairs: 30,
        stage3_pairs: 210,
        ..TrainConfig::built_in("tiny")
    };
    let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
    // Warm-up: 1/10, ..., 10/10 of the peak over the first 10 pairs of each stage.
    assert!(close(c.learning_rate_at(0), 1e-4));
    assert!(close(c.learning_rate_at(9), 1e-3));
    assert!(close(c.learning_rate_at(10), 1e-3));
    // Half-way through the cosine part (pair 10 + 50): midway between peak and floor.
    assert!(close(c.learning_rate_at(60), 0.5 * (1e-3 + 1e-5)));
    // Stage 2 starts over: warm-up again.
    assert!(close(c.learning_rate_at(110), 1e-4));
    // The rate never rises within the cosine part and ends near the floor.
    let rates: Vec<f64> = (150..350).map(|p| c.learning_rate_at(p)).collect();
    assert!(rates.windows(2).all(|w| w[1] <= w[0]));
    assert!(rates[rates.len() - 1] < 1.1e-5 && rates[rates.len() - 1] >= 1e-5);
}

#[test]
fn replicas_must_divide_the_batch() {
    let text = BUILT_IN[2].1.replace("batch = 8", "batch = 8\nreplicas = 3");
    let err = TrainConfig::from_toml(&text, "t").expect_err("3 does not divide 8").to_string();
    assert!(err.contains("replicas"), "{err}");
}
