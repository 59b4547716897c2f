"""`generator export --format yi-mat|mbs-npz`: the exported files read back the way the
paper authors' code (`scipy.io.loadmat`) and MultiBodySync (`numpy.load(allow_pickle=True)`)
read them, and checked field by field against the dataset as `part_induction` reads it."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path
from typing import Callable, List

import numpy as np
import pytest
from scipy.io import loadmat  # the `test` extra installs scipy

from part_induction import Pair, open_dataset

REPO = Path(__file__).resolve().parents[2]
DATASETS = ["sf2f_dir", "sp2p_dir"]
ATOL = 1e-6


def export_args(fmt: str, dataset: Path, out: Path, *extra: str) -> List[str]:
    return ["run", "-q", "-p", "generator", "--", "export", "--format", fmt,
            "--dataset", str(dataset), "--out", str(out), *extra]  # fmt: skip


def to_common(pair: Pair, q_normalised: np.ndarray) -> np.ndarray:
    """Q's normalised frame to P's (MultiBodySync's common frame), in float64."""
    q = np.asarray(q_normalised, np.float64)
    centre_p = np.asarray(pair.p_centre, np.float64)
    centre_q = np.asarray(pair.q_centre, np.float64)
    return (q * float(pair.q_scale) + centre_q - centre_p) / float(pair.p_scale)


@pytest.mark.parametrize("name", DATASETS)
def test_yi_mat_holds_every_field(
    name: str, request: pytest.FixtureRequest, cargo: Callable[..., str], tmp_path: Path
) -> None:
    folder: Path = request.getfixturevalue(name)
    out = tmp_path / "mat"
    cargo(*export_args("yi-mat", folder, out))
    pairs = list(open_dataset(folder))
    k, n, m = len(pairs), len(pairs[0].p), len(pairs[0].q)
    assert k >= 2
    assert sorted(p.name for p in out.iterdir()) == ["flow.mat", "ids.txt", "pairs.mat"]
    assert (out / "ids.txt").read_text().splitlines() == [p.id for p in pairs]

    data = loadmat(str(out / "pairs.mat"))
    shapes = {"pc1": (k, n, 3), "pc2": (k, m, 3), "pc2_partial": (k, m, 3),
              "flow12": (k, n, 3), "seg1": (k, n), "seg2": (k, m), "momasks": (k, n),
              "vismask": (k, n)}  # fmt: skip
    for key, shape in shapes.items():
        assert data[key].shape == shape, key
        integer = key in ("seg1", "seg2", "momasks")
        assert data[key].dtype == (np.int32 if integer else np.float32), key
    for i, pair in enumerate(pairs):
        np.testing.assert_allclose(data["pc1"][i], pair.p, rtol=0, atol=ATOL, err_msg=pair.id)
        np.testing.assert_allclose(data["pc2"][i], pair.q, rtol=0, atol=ATOL, err_msg=pair.id)
        np.testing.assert_allclose(data["pc2_partial"][i], pair.q, rtol=0, atol=ATOL)
        np.testing.assert_allclose(data["flow12"][i], pair.flow, rtol=0, atol=ATOL)
        np.testing.assert_array_equal(data["seg1"][i], pair.part_p.astype(np.int32) + 1)
        np.testing.assert_array_equal(data["seg2"][i], pair.part_q.astype(np.int32) + 1)
        np.testing.assert_array_equal(data["momasks"][i], pair.part_p)
        np.testing.assert_array_equal(data["vismask"][i], pair.corr_mask.astype(np.float32))
    # The authors' evaluation takes seg1 - 1 as 0-based part ids.
    assert (data["seg1"] - 1).min() == 0

    flow = loadmat(str(out / "flow.mat"))
    assert {key for key in flow if not key.startswith("__")} == {
        "pc1", "pc2", "pc2_partial", "vismask"
    }
    np.testing.assert_array_equal(flow["pc1"], data["pc1"])
    np.testing.assert_array_equal(flow["pc2"], data["pc1"] + data["flow12"])
    np.testing.assert_array_equal(flow["pc2_partial"], data["pc2"])
    np.testing.assert_array_equal(flow["vismask"], data["vismask"])
    # Their FlowDataset's flow.
    np.testing.assert_allclose(flow["pc2"] - flow["pc1"], data["flow12"], rtol=0, atol=ATOL)


@pytest.mark.parametrize("name", DATASETS)
def test_mbs_npz_holds_views_segments_and_motions(
    name: str, request: pytest.FixtureRequest, cargo: Callable[..., str], tmp_path: Path
) -> None:
    folder: Path = request.getfixturevalue(name)
    out = tmp_path / "mbs"
    cargo(*export_args("mbs-npz", folder, out))
    dataset = open_dataset(folder)
    pairs = list(dataset)
    k = len(pairs)

    meta = json.loads((out / "meta.json").read_text())
    assert list(meta) == ["train", "val", "test"]
    split = {"train": "train", "validation": "val", "test": "test"}[
        dataset.manifest["config"]["split"]
    ]
    for key, ids in meta.items():
        assert ids == (list(range(k)) if key == split else []), key
    assert (out / "ids.txt").read_text().splitlines() == [p.id for p in pairs]
    assert sorted(p.name for p in (out / "data").iterdir()) == [f"{i:06d}.npz" for i in range(k)]

    for i, pair in enumerate(pairs):
        datum = np.load(out / "data" / f"{i:06d}.npz", allow_pickle=True)
        assert sorted(datum.files) == ["pc", "segm", "trans"]
        pc, segm, trans = datum["pc"], datum["segm"], datum["trans"].item()
        n = len(pair.p)
        assert pc.dtype == np.float32 and pc.shape == (2, n, 3)
        assert segm.dtype == np.int64 and segm.shape == (2, n)
        np.testing.assert_allclose(pc[0], pair.p, rtol=0, atol=ATOL, err_msg=pair.id)
        np.testing.assert_allclose(pc[1], to_common(pair, pair.q), rtol=0, atol=ATOL)
        np.testing.assert_array_equal(segm[0], pair.part_p.astype(np.int64) + 1)
        np.testing.assert_array_equal(segm[1], pair.part_q.astype(np.int64) + 1)

        assert isinstance(trans, dict)
        assert list(trans) == ["cam", *range(1, pair.num_parts + 1)]
        for key, views in trans.items():
            assert isinstance(views, list) and len(views) == 2, key
            for matrix in views:
                assert matrix.dtype == np.float64 and matrix.shape == (4, 4), key
                np.testing.assert_array_equal(matrix[3], [0.0, 0.0, 0.0, 1.0])
                r = matrix[:3, :3]
                # pyquaternion.Quaternion(matrix=R)'s test, which MultiBodySync relies on.
                assert np.allclose(r @ r.T, np.eye(3), rtol=1e-5, atol=1e-8), (pair.id, key)
                assert np.linalg.det(r) > 0, (pair.id, key)
        np.testing.assert_array_equal(trans["cam"][0], np.eye(4))
        np.testing.assert_array_equal(trans["cam"][1], np.eye(4))

        # MultiBodySync's compute_flow, on view 0's points of each part, reproduces the
        # ground truth: P moved by its flow, mapped into the common frame.
        cam0, cam1 = trans["cam"]
        moved = to_common(pair, pair.p.astype(np.float64) + pair.flow)
        for part in range(1, pair.num_parts + 1):
            mask = segm[0] == part
            base, dest = trans[part]
            mapping = np.linalg.inv(cam1) @ dest @ np.linalg.inv(base) @ cam0
            points = pc[0][mask].astype(np.float64)
            flowed = points @ mapping[:3, :3].T + mapping[:3, 3]
            np.testing.assert_allclose(flowed, moved[mask], rtol=0, atol=1e-5, err_msg=pair.id)


@pytest.mark.parametrize("fmt", ["yi-mat", "mbs-npz"])
def test_a_non_empty_folder_is_refused_and_left_unchanged(
    fmt: str, sf2f_dir: Path, cargo: Callable[..., str], tmp_path: Path
) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    result = subprocess.run(
        ["cargo", *export_args(fmt, sf2f_dir, out)],
        cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    assert result.returncode != 0
    assert "not empty" in result.stderr and "--force" in result.stderr, result.stderr
    assert [p.name for p in out.iterdir()] == ["keep.txt"]
    assert (out / "keep.txt").read_text() == "mine"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"], "no staging folder is left"
    # With --force the folder holds the export and nothing else.
    cargo(*export_args(fmt, sf2f_dir, out, "--force"))
    assert not (out / "keep.txt").exists()
    assert (out / "ids.txt").is_file()


def test_exports_are_deterministic(
    sf2f_dir: Path, cargo: Callable[..., str], tmp_path: Path
) -> None:
    for fmt in ("yi-mat", "mbs-npz"):
        one, two = tmp_path / f"{fmt}-1", tmp_path / f"{fmt}-2"
        cargo(*export_args(fmt, sf2f_dir, one))
        cargo(*export_args(fmt, sf2f_dir, two))
        files = sorted(p.relative_to(one) for p in one.rglob("*") if p.is_file())
        assert files == sorted(p.relative_to(two) for p in two.rglob("*") if p.is_file())
        for rel in files:
            assert (one / rel).read_bytes() == (two / rel).read_bytes(), rel


def test_mbs_npz_of_a_set_holds_all_k_views(
    sets_dir: Path, cargo: Callable[..., str], tmp_path: Path
) -> None:
    """A set dataset exports K views per file, as MultiBodySync's SAPIEN files hold them:
    one labelling for all views, and its compute_flow from view 0 to every view k
    reproduces the set's ground truth."""
    from part_induction import open_set_dataset

    out = tmp_path / "mbs-sets"
    cargo(*export_args("mbs-npz", sets_dir, out))
    sets = list(open_set_dataset(sets_dir))
    assert (out / "ids.txt").read_text().splitlines() == [s.id for s in sets]
    for i, item in enumerate(sets):
        datum = np.load(out / "data" / f"{i:06d}.npz", allow_pickle=True)
        pc, segm, trans = datum["pc"], datum["segm"], datum["trans"].item()
        k, n = len(item), len(item.views[0].points)
        assert pc.shape == (k, n, 3) and pc.dtype == np.float32
        assert segm.shape == (k, n) and segm.dtype == np.int64
        assert list(trans) == ["cam", *range(1, item.num_parts + 1)]
        assert all(len(views) == k for views in trans.values())
        v0 = item.views[0]
        for v, view in enumerate(item.views):
            np.testing.assert_array_equal(segm[v], view.parts.astype(np.int64) + 1)
            common = (view.points.astype(np.float64) * view.scale + view.centre - v0.centre)
            np.testing.assert_allclose(pc[v], common / v0.scale, rtol=0, atol=ATOL)
            # View 0 moved by the set's flow into view v's state, in the common frame.
            moved = v0.points.astype(np.float64) + view.flow
            moved = (moved * view.scale + view.centre - v0.centre) / v0.scale
            for part in range(1, item.num_parts + 1):
                mask = segm[0] == part
                mapping = (np.linalg.inv(trans["cam"][v]) @ trans[part][v]
                           @ np.linalg.inv(trans[part][0]) @ trans["cam"][0])
                points = pc[0][mask].astype(np.float64)
                flowed = points @ mapping[:3, :3].T + mapping[:3, 3]
                np.testing.assert_allclose(flowed, moved[mask], rtol=0, atol=1e-5,
                                           err_msg=f"{item.id} view {v} part {part}")


def test_yi_mat_refuses_a_set_dataset(
    sets_dir: Path, cargo: Callable[..., str], tmp_path: Path
) -> None:
    result = subprocess.run(
        ["cargo", *export_args("yi-mat", sets_dir, tmp_path / "mat")], cwd=REPO,
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )
    assert result.returncode != 0 and "mbs-npz" in result.stderr
