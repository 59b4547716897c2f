//! Generation speed. Targets on 2 cores: a paper-size SF2F set (175 objects, 875 pairs,
//! N = 512) written to disk in under 5 s, SF2P in under 15 s and SP2P in under 30 s
//! (images included); ray casting at least 2 million rays per second; the training stream
//! delivering at least 1,000 full pairs per second.

use articulated::kinematics::link_poses;
use articulated::seed::{rng_for, Stream};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use generator::config::GeneratorConfig;
use generator::generate::{build_object, generate_dataset, object_pairs};
use generator::stream::TrainingStream;
use pairs::PairKind;
use scanner::camera::Camera;
use scanner::config::ScanConfig;
use scanner::render::render;
use scanner::scene::PosedScene;

/// Pairs drawn from the training stream per iteration.
const STREAM_PAIRS: u64 = 2000;

fn bench(c: &mut Criterion) {
    let config = GeneratorConfig::default();
    c.bench_function("object_pairs (5 pairs, N=512)", |b| {
        b.iter(|| object_pairs(&config, 1).expect("pairs"))
    });
    ray_casting(c);
    let mut group = c.benchmark_group("dataset");
    group.sample_size(10);
    for kind in [PairKind::Sf2f, PairKind::Sf2p, PairKind::Sp2p] {
        let config = GeneratorConfig::of_kind(kind);
        group.bench_function(format!("paper-size {} (875 pairs, N=512)", kind.as_str()), |b| {
            b.iter(|| {
                let dir = tempfile::tempdir().expect("tempdir");
                generate_dataset(&config, dir.path(), false, None, |_| {}).expect("dataset")
            })
        });
    }
    group.throughput(Throughput::Elements(STREAM_PAIRS));
    group.bench_function("training stream (N=512, pairs/s)", |b| {
        b.iter(|| {
            let stream = TrainingStream::new(GeneratorConfig::training()).expect("stream");
            stream.take(STREAM_PAIRS as usize).try_fold(0, |n, p| p.map(|_| n + 1)).expect("pairs")
        })
    });
    group.finish();
}

/// Rays per second: 320 x 240 images of the first test objects at rest, counting the rays
/// the renderer casts (the pixels of the object's bounding-box window).
fn ray_casting(c: &mut Criterion) {
    let config = GeneratorConfig::default();
    let scan = ScanConfig::default();
    let scenes: Vec<(PosedScene, Camera)> = (0..8)
        .map(|i| {
            let object = build_object(&config, i).expect("object");
            let rest: Vec<f32> = object.joints.iter().map(|j| j.rest).collect();
            let scene = PosedScene::new(&object, &link_poses(&object, &rest)).expect("scene");
            let mut rng = rng_for(0, u64::from(i), Stream::Scan(0, 0));
            let camera = Camera::draw(&scan, &scene.centre(), scene.diagonal(), &mut rng);
            (scene, camera)
        })
        .collect();
    let rays: u64 = scenes.iter().map(|(s, c)| cast_rays(s, c)).sum();
    let mut group = c.benchmark_group("scan");
    group.throughput(Throughput::Elements(rays));
    group.bench_function("ray casting (8 scans, 320x240)", |b| {
        b.iter(|| scenes.iter().map(|(s, c)| render(s, c).hits()).sum::<usize>())
    });
    group.finish();
}

/// Rays `render` casts for one image: the pixels of the object's bounding-box window.
fn cast_rays(scene: &PosedScene, camera: &Camera) -> u64 {
    let (u, v) = scanner::render::pixel_window(scene, camera);
    u64::from(u.end - u.start) * u64::from(v.end - v.start)
}

criterion_group!(benches, bench);
criterion_main!(benches);
