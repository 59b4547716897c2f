use super::*;
use crate::synthetic;

#[test]
fn modes_name_their_views() {
    assert_eq!(
        SetMode::of(&[ViewKind::Full, ViewKind::Scan, ViewKind::Scan]),
        Some(SetMode::Mixed)
    );
    assert_eq!(SetMode::of(&[ViewKind::Scan, ViewKind::Full]), None);
    assert_eq!("MIXED".parse::<SetMode>(), Ok(SetMode::Mixed));
    assert!("both".parse::<SetMode>().unwrap_err().contains("full, scan, mixed"));
}

#[test]
fn a_hinge_set_slices_into_its_pairs() {
    let angles = [0.0, 0.4, 0.4, -0.3];
    let set = synthetic::hinge_set("h", 4, &angles);
    assert_eq!((set.len(), set.mode(), set.truth().num_parts()), (4, SetMode::Full, 2));
    // Views 1 and 2 hold the same state: their pair has one part and no joint.
    let still = set.pair(1, 2).expect("a pair");
    assert_eq!(still.truth().num_parts(), 1);
    assert!(still.truth().joints.is_empty());
    for (i, j) in [(0, 1), (1, 3), (3, 0), (2, 1)] {
        let pair = set.pair(i, j).expect("a pair");
        let (input, truth) = (pair.input(), pair.truth());
        assert_eq!(pair.id(), format!("h-{i}-{j}"));
        // Every view holds the same samples in the same order: the flow carries each
        // point of P onto its own sample in Q, which is its correspondence.
        let flow = truth.flow.as_ref().expect("a flow");
        for (k, (p, f)) in input.p.points.iter().zip(flow).enumerate() {
            assert!((p + f - input.q.points[k]).norm() < 1e-5, "({i}, {j}) point {k}");
            assert_eq!(truth.corr_index[k], k as i32);
        }
        let moving = angles[i] != angles[j];
        assert_eq!(truth.num_parts(), if moving { 2 } else { 1 });
        if moving {
            assert!(
                (truth.joints[0].value_q - truth.joints[0].value_p - (angles[j] - angles[i])).abs()
                    < 1e-6
            );
        }
    }
}

#[test]
fn bad_sets_are_refused_by_field() {
    let set = synthetic::hinge_set("h", 3, &[0.0, 0.5, 1.0]);
    let err = set.pair(0, 3).unwrap_err().to_string();
    assert!(err.contains("view 3") && err.contains("3 views"), "{err}");
    assert!(set.pair(1, 1).is_err());
    let (input, truth, prov, scans) = set.clone().into_parts();
    let mut broken = truth.clone();
    broken.pair_parts[0][1] = vec![1, 0];
    let err = Set::new(input.clone(), broken, prov.clone(), scans.clone()).unwrap_err();
    assert!(err.to_string().contains("pair_parts"), "{err}");
    // Parts 0 and 1 turn apart between views 0 and 1: they cannot be one part there.
    let mut broken = truth.clone();
    broken.pair_parts[0][1] = vec![0, 0];
    let err = Set::new(input.clone(), broken, prov.clone(), scans.clone()).unwrap_err();
    assert!(err.to_string().contains("move apart"), "{err}");
    let mut broken = truth.clone();
    broken.motions[2][1].scale *= 2.0;
    let err = Set::new(input.clone(), broken, prov.clone(), scans.clone()).unwrap_err();
    assert!(err.to_string().contains("motions"), "{err}");
    let mut broken = truth.clone();
    broken.parts[2].pop();
    let err = Set::new(input.clone(), broken, prov.clone(), scans.clone()).unwrap_err();
    assert!(err.to_string().contains("parts"), "{err}");
    let mut broken = truth;
    broken.flows[1][0].x += 0.5;
    let err = Set::new(input, broken, prov, scans).unwrap_err().to_string();
    assert!(err.contains("flow") || err.contains("flows"), "{err}");
}
