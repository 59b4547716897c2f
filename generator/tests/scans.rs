//! Scanned pairs (SF2P, SP2P): depth images back-project onto the posed meshes with the
//! stored cameras, labels name the part that was hit, the correspondence mask agrees with
//! an independent check, and the output repeats byte for byte whatever the thread count.

use std::collections::BTreeMap;
use std::path::Path;

use articulated::objects::ArticulatedObject;
use generator::config::{GeneratorConfig, ScanConfig};
use generator::generate::{build_object, generate_dataset, object_pairs, GeneratedPair};
use generator::shard::merge_shards;
use image::ImageReader;
use pairs::dataset::{Dataset, Shard};
use pairs::math::{Isometry3, Point3, Real};
use pairs::{PairKind, Scan};
use parry3d::query::PointQuery;
use parry3d::shape::TriMesh;

fn config(kind: PairKind, scan: ScanConfig) -> GeneratorConfig {
    GeneratorConfig {
        kind,
        objects: 6,
        pairs_per_object: 2,
        points: 512,
        seed: 21,
        scan: Some(scan),
        ..Default::default()
    }
}

/// The posed surface of each part, mapped by `frame`.
fn part_meshes(
    object: &ArticulatedObject,
    g: &GeneratedPair,
    poses: &[Isometry3],
    frame: impl Fn(Point3) -> Point3,
) -> Vec<TriMesh> {
    (0..g.parts.count())
        .map(|part| {
            let (mut vertices, mut indices) = (Vec::new(), Vec::new());
            for (link, l) in object.links.iter().enumerate() {
                if usize::from(g.parts.of_link[link]) == part {
                    let offset = vertices.len() as u32;
                    vertices.extend(l.mesh.vertices.iter().map(|v| frame(poses[link] * v)));
                    indices.extend(l.mesh.triangles.iter().map(|t| t.map(|i| i + offset)));
                }
            }
            TriMesh::new(vertices, indices).expect("a part has triangles")
        })
        .collect()
}

fn decode(png: &[u8]) -> image::DynamicImage {
    ImageReader::new(std::io::Cursor::new(png))
        .with_guessed_format()
        .expect("format")
        .decode()
        .expect("a valid PNG")
}

/// Back-projects every pixel of a noise-free scan's depth PNG and checks that it lies on
/// the surface of the part its label PNG names; returns the number of pixels checked.
fn check_back_projection(
    object: &ArticulatedObject,
    g: &GeneratedPair,
    scan: &Scan,
    poses: &[Isometry3],
    pngs: &pairs::scan::ScanImages<Vec<u8>>,
) -> usize {
    let meshes = part_meshes(object, g, poses, |p| p);
    let depth = decode(&pngs.depth).into_luma16();
    let labels = decode(&pngs.labels).into_luma8();
    assert_eq!((depth.width(), depth.height()), (scan.intrinsics.width, scan.intrinsics.height));
    let diagonal: Real = meshes
        .iter()
        .map(|m| m.local_aabb())
        .reduce(|a, b| parry3d::bounding_volume::BoundingVolume::merged(&a, &b))
        .map(|aabb| aabb.extents().norm())
        .expect("parts");
    let mut checked = 0;
    for (u, v, d) in depth.enumerate_pixels() {
        let label = labels.get_pixel(u, v)[0];
        if d[0] == 0 {
            assert_eq!(label, 0, "{}: a noise-free scan drops no surface pixel", g.pair.id());
            continue;
        }
        assert!(label > 0, "{}: pixel ({u}, {v}) has depth but no label", g.pair.id());
        let point = scan.back_project(u as Real, v as Real, Real::from(d[0]) * scan.depth_scale);
        let distance = meshes[usize::from(label - 1)].distance_to_local_point(&point, false);
        assert!(
            distance < 1e-4 * diagonal,
            "{}: pixel ({u}, {v}) lands {} diagonals from part {}",
            g.pair.id(),
            distance / diagonal,
            label - 1
        );
        checked += 1;
    }
    checked
}

#[test]
fn noise_free_depth_back_projects_onto_the_labelled_part() {
    for kind in [PairKind::Sf2p, PairKind::Sp2p] {
        let config = config(kind, ScanConfig::noise_free());
        let mut checked = 0;
        for index in 0..config.objects {
            let object = build_object(&config, index).expect("object");
            for g in object_pairs(&config, index).expect("pairs") {
                let scans = g.pair.scans();
                assert_eq!(scans.p.is_some(), kind == PairKind::Sp2p);
                let (scan, pngs) = (scans.q.as_ref().expect("Q is scanned"), &g.images.q);
                let pngs = pngs.as_ref().expect("Q's images");
                checked += check_back_projection(&object, &g, scan, &g.poses_q, pngs);
                if let (Some(scan), Some(pngs)) = (&scans.p, &g.images.p) {
                    checked += check_back_projection(&object, &g, scan, &g.poses_p, pngs);
                }
            }
        }
        assert!(checked > 10_000, "{kind:?}: only {checked} pixels checked");
    }
}

#[test]
fn noise_free_scanned_points_move_onto_q_surface() {
    let config = config(PairKind::Sp2p, ScanConfig::noise_free());
    for index in 0..config.objects {
        let object = build_object(&config, index).expect("object");
        for g in object_pairs(&config, index).expect("pairs") {
            let (input, truth) = (g.pair.input(), g.pair.truth());
            let norm = input.q.normalisation;
            let meshes = part_meshes(&object, &g, &g.poses_q, |p| norm.apply(&p));
            for (i, p) in input.p.points.iter().enumerate() {
                let part = usize::from(truth.part_p[i]);
                let moved = truth.motions[part].apply(p);
                let d = meshes[part].distance_to_local_point(&moved, false);
                assert!(d < 1e-4, "{}: point {i} lands {d} from Q's part {part}", input.id);
            }
        }
    }
}

/// Median distance from a point of `points` to its nearest other point.
fn spacing(points: &[Point3]) -> Real {
    let mut nearest: Vec<Real> = points
        .iter()
        .enumerate()
        .map(|(i, a)| {
            points
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .map(|(_, b)| (a - b).norm())
                .fold(Real::MAX, Real::min)
        })
        .collect();
    nearest.sort_by(Real::total_cmp);
    nearest[nearest.len() / 2]
}

/// Agreement of the mask with proximity: a matched point of P has a Q point of its part
/// within 1.5 of Q's point spacings of its moved position, an unmatched one has none.
/// Points whose 8 nearest neighbours in P (moved) include one of the other mask lie at a
/// visibility boundary (a silhouette, or the two sides of a thin plate) and are not counted.
fn mask_agreement(g: &GeneratedPair) -> (usize, usize) {
    let (input, truth) = (g.pair.input(), g.pair.truth());
    let q = &input.q.points;
    let radius = 1.5 * spacing(q);
    let moved: Vec<Point3> = input
        .p
        .points
        .iter()
        .zip(&truth.part_p)
        .map(|(p, &k)| truth.motions[usize::from(k)].apply(p))
        .collect();
    let (mut agree, mut counted) = (0, 0);
    for (i, m) in moved.iter().enumerate() {
        let mask = truth.corr_mask[i];
        let mut neighbours: Vec<(Real, bool)> = moved
            .iter()
            .zip(&truth.corr_mask)
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, (o, &matched))| ((o - m).norm(), matched))
            .collect();
        neighbours.sort_by(|a, b| a.0.total_cmp(&b.0));
        if neighbours.iter().take(8).any(|&(_, matched)| matched != mask) {
            continue;
        }
        let near_q = q
            .iter()
            .zip(&truth.part_q)
            .any(|(x, &k)| k == truth.part_p[i] && (x - m).norm() < radius);
        counted += 1;
        agree += usize::from(mask == near_q);
    }
    (agree, counted)
}

#[test]
fn the_correspondence_mask_agrees_with_proximity_on_95_percent_of_points() {
    // Noise-free scans: dropout and flying pixels unmatch points that proximity cannot tell
    // apart. Dense clouds, so that "near" can mean less than the thickness of a thin plate.
    for kind in [PairKind::Sf2p, PairKind::Sp2p] {
        let config =
            GeneratorConfig { objects: 3, points: 2048, ..config(kind, ScanConfig::noise_free()) };
        let (mut agree, mut counted, mut unmatched) = (0, 0, 0);
        for index in 0..config.objects {
            for g in object_pairs(&config, index).expect("pairs") {
                let (a, c) = mask_agreement(&g);
                (agree, counted) = (agree + a, counted + c);
                unmatched += g.pair.truth().corr_mask.iter().filter(|&&m| !m).count();
            }
        }
        let rate = agree as f64 / counted as f64;
        assert!(rate >= 0.95, "{kind:?}: the mask agrees with proximity on {rate:.3} of points");
        let total = config.objects * config.pairs_per_object * config.points;
        assert!(
            counted > total as usize / 4,
            "{kind:?}: only {counted} points away from boundaries"
        );
        assert!(unmatched > 0, "{kind:?}: a scan hides part of P");
    }
}

/// Every file under `dir`, by path relative to it.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).expect("read dir") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let rel = path.strip_prefix(dir).expect("inside").to_string_lossy().into_owned();
                out.insert(rel, std::fs::read(&path).expect("read"));
            }
        }
    }
    out
}

#[test]
fn scanned_datasets_repeat_byte_for_byte_and_merge_from_shards() {
    let config = GeneratorConfig {
        objects: 4,
        points: 128,
        min_part_points: 5,
        ..config(PairKind::Sp2p, ScanConfig::default())
    };
    let root = tempfile::tempdir().expect("tempdir");
    let run = |threads: usize, name: &str, shard: Option<Shard>| {
        let dir = root.path().join(name);
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
        pool.install(|| generate_dataset(&config, &dir, false, shard, |_| {})).expect("generate");
        dir
    };
    let (one, two) = (run(1, "one", None), run(2, "two", None));
    let (a, b) = (files(&one), files(&two));
    assert_eq!(a.keys().collect::<Vec<_>>(), b.keys().collect::<Vec<_>>());
    assert!(a == b, "files differ between 1 and 2 threads");
    let images = a.keys().filter(|k| k.starts_with("images/")).count();
    assert_eq!(images, 4 * 2 * 2 * 3, "three images per scan, two scans per pair");
    let dataset = Dataset::open(&one).expect("open");
    dataset.verify().expect("checksums cover the images");
    assert!(dataset.manifest().files.len() > images);
    let shards = [
        run(2, "s1", Some(Shard { index: 1, count: 2 })),
        run(1, "s0", Some(Shard { index: 0, count: 2 })),
    ];
    let merged = root.path().join("merged");
    merge_shards(&shards, &merged, false, |_| {}).expect("merge");
    assert!(files(&merged) == a, "merged shards differ from the single run");
}
