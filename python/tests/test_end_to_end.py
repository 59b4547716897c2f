"""A prediction file written from Python, scored by the Rust evaluator; and the example
method of docs/SCORING.md and python/README.md."""

from __future__ import annotations

import csv
import subprocess
import sys
from pathlib import Path
from typing import Callable, Dict, List

import numpy as np
import pytest

from part_induction import PredictionError, PredictionWriter, open_dataset, read_predictions


def rows(path: Path, method: str) -> List[Dict[str, str]]:
    with open(path, newline="") as f:
        return [row for row in csv.DictReader(f) if row["method"] == method]


@pytest.mark.evaluator
def test_the_ground_truth_written_from_python_scores_perfectly(
    sf2f_dir: Path, tmp_path: Path, cargo: Callable[..., str]
) -> None:
    dataset = open_dataset(sf2f_dir)
    predictions = tmp_path / "gt.mcap"
    with PredictionWriter(predictions, "gt-py", dataset, method_version="test") as writer:
        for pair in dataset:
            writer.write(
                pair.id,
                pair.part_p,
                segments_q=pair.part_q,
                flow=pair.flow,
                motions=(pair.motions.rotations, pair.motions.translations, pair.scale),
            )
    reports = tmp_path / "reports"
    score = ["score", "--dataset", str(sf2f_dir), "--predictions", str(predictions)]
    score += ["--name", "gt-py", "--reports", str(reports)]
    cargo("run", "-q", "-p", "evaluator", "--", *score)
    (flow,) = rows(reports / "leaderboard_flow.csv", "gt-py")
    assert flow["flow_source"] == "external"
    assert float(flow["epe"]) == pytest.approx(0.0, abs=1e-6)
    (seg,) = rows(reports / "leaderboard_seg.csv", "gt-py")
    assert float(seg["ri"]) == pytest.approx(1.0, abs=1e-6)
    assert float(seg["iou"]) == pytest.approx(1.0, abs=1e-6)
    for row in (flow, seg):
        if "pairs" in row:
            assert int(row["pairs"]) == len(dataset)
        if "failed" in row:
            assert int(row["failed"]) == 0


@pytest.mark.evaluator
def test_a_cross_instance_set_is_scored_on_segmentation_only(
    xf2p_dir: Path, tmp_path: Path, cargo: Callable[..., str]
) -> None:
    dataset = open_dataset(xf2p_dir)
    predictions = tmp_path / "labels.mcap"
    with PredictionWriter(predictions, "labels-py", dataset, method_version="test") as writer:
        for pair in dataset:
            # A flow is allowed, but there is no true flow to score it against.
            writer.write(pair.id, pair.part_p, segments_q=pair.part_q, flow=np.zeros_like(pair.p))
    reports = tmp_path / "reports"
    score = ["score", "--dataset", str(xf2p_dir), "--predictions", str(predictions)]
    score += ["--name", "labels-py", "--reports", str(reports)]
    cargo("run", "-q", "-p", "evaluator", "--", *score)
    assert rows(reports / "leaderboard_flow.csv", "labels-py") == []
    (seg,) = rows(reports / "leaderboard_seg.csv", "labels-py")
    assert float(seg["ri"]) == pytest.approx(1.0, abs=1e-6)
    assert float(seg["iou"]) == pytest.approx(1.0, abs=1e-6)
    assert float(seg["ri_q"]) == pytest.approx(1.0, abs=1e-6)
    assert int(seg["pairs"]) == len(dataset) and int(seg["failed"]) == 0


@pytest.mark.evaluator
def test_predictions_written_by_the_evaluator_read_back(
    sf2f_dir: Path, tmp_path: Path, cargo: Callable[..., str]
) -> None:
    out = tmp_path / "gt.mcap"
    predict = ["predict", "--method", "gt", "--dataset", str(sf2f_dir), "--out", str(out)]
    cargo("run", "-q", "-p", "evaluator", "--", *predict)
    dataset = open_dataset(sf2f_dir)
    header, predictions = read_predictions(out)
    assert (header["method"], header["dataset"]) == ("gt", dataset.content_hash)
    by_id = {p["id"]: p for p in predictions}
    pairs = list(dataset)
    assert sorted(by_id) == sorted(p.id for p in pairs)
    for pair in pairs:
        prediction = by_id[pair.id]
        np.testing.assert_array_equal(prediction["segments_p"], pair.part_p)
        np.testing.assert_array_equal(prediction["segments_q"], pair.part_q)
        np.testing.assert_array_equal(prediction["flow"], pair.flow)
        motions = prediction["motions"]
        np.testing.assert_array_equal(motions["rotations"], pair.motions.rotations)
        np.testing.assert_array_equal(motions["translations"], pair.motions.translations)
        np.testing.assert_array_equal(motions["scales"], np.float32(pair.scale))


def test_the_example_method_writes_one_prediction_per_pair(
    sf2f_dir: Path, tmp_path: Path, python_env: Dict[str, str]
) -> None:
    out = tmp_path / "predictions.mcap"
    example = Path(__file__).resolve().parents[1] / "examples" / "one_segment_nn.py"
    command = [sys.executable, str(example), str(sf2f_dir), str(out)]
    result = subprocess.run(command, env=python_env, stdout=subprocess.PIPE, text=True)
    assert result.returncode == 0
    assert result.stdout.strip() == f"wrote 15 predictions to {out}"
    dataset = open_dataset(sf2f_dir)
    header, predictions = read_predictions(out)
    assert header["method"] == "one-segment-nn"
    assert header["dataset"] == dataset.content_hash
    by_id = {p["id"]: p for p in predictions}
    pairs = list(dataset)
    assert sorted(by_id) == sorted(p.id for p in pairs)
    for pair in pairs:
        prediction = by_id[pair.id]
        assert (prediction["segments_p"] == 0).all() and len(prediction["segments_p"]) == 96
        assert (prediction["segments_q"] == 0).all() and len(prediction["segments_q"]) == 96
        moved = pair.p + prediction["flow"]
        # Every moved point is a point of Q, and the nearest one.
        distances = ((pair.p[:, None] - pair.q[None]) ** 2).sum(-1)
        np.testing.assert_allclose(moved, pair.q[distances.argmin(1)], atol=1e-6)


def _miou(predicted: np.ndarray, truth: np.ndarray) -> float:
    """MultiBodySync's segmentation mIoU (``IoULoss`` in huangjh-pub/multibody-sync's
    ``loss.py``, transcribed from torch to numpy for one set): the labels of all views pooled
    (``segm.reshape(n_batch, -1)``), one-hot predictions with at least as many columns as
    true parts (their ``s``; empty columns added here score IoU 0), a Hungarian matching
    maximising IoU (``linear_sum_assignment(..., maximize=True)``), and the mean IoU of the
    matched true parts, each ``inter / (union + 1e-8)``."""
    from scipy.optimize import linear_sum_assignment

    _, gt = np.unique(truth, return_inverse=True)  # their ids start from 0, contiguous
    _, pd = np.unique(predicted, return_inverse=True)
    n_gt = gt.max() + 1
    s = max(pd.max() + 1, n_gt)
    gt_onehot = np.eye(s)[gt]  # (N, s)
    pd_onehot = np.eye(s)[pd]
    matching = np.einsum("ng,np->gp", gt_onehot, pd_onehot)
    union = gt_onehot.sum(0)[:, None] + pd_onehot.sum(0)[None, :] - matching
    score = matching / (union + 1e-8)
    rows_, cols = linear_sum_assignment(score[:n_gt], maximize=True)
    inter = (gt_onehot[:, rows_] * pd_onehot[:, cols]).sum(0)
    union = gt_onehot[:, rows_].sum(0) + pd_onehot[:, cols].sum(0) - inter
    return float((inter / (union + 1e-8)).mean())


@pytest.mark.evaluator
def test_a_set_method_from_python_is_scored_onto_the_set_board(
    sets_dir: Path, tmp_path: Path, cargo: Callable[..., str], python_env: Dict[str, str]
) -> None:
    from part_induction import open_set_dataset

    dataset = open_set_dataset(sets_dir)
    sets = list(dataset)
    # The set parts, one id per part in every view (renamed): perfect by every score.
    truth = tmp_path / "truth.mcap"
    with PredictionWriter(truth, "set-truth-py", dataset) as writer:
        for s in sets:
            writer.write_set(s.id, [5 - v.parts.astype(np.int64) for v in s.views])
        with pytest.raises(PredictionError, match="2 label arrays for 4 views"):
            writer.write_set(sets[0].id, [np.zeros(1)] * 2)
    # The example set method, run as a user runs it.
    example = Path(__file__).resolve().parents[1] / "examples" / "lower_upper_sets.py"
    out = tmp_path / "lower-upper.mcap"
    command = [sys.executable, str(example), str(sets_dir), str(out)]
    result = subprocess.run(command, env=python_env, stdout=subprocess.PIPE, text=True)
    assert result.returncode == 0
    wrote = f"wrote {3 * len(sets)} pair records ({len(sets)} sets) to {out}"
    assert result.stdout.strip() == wrote
    reports = tmp_path / "reports"
    for path, name in ((truth, "set-truth-py"), (out, "lower-upper")):
        score = ["score", "--dataset", str(sets_dir), "--predictions", str(path)]
        score += ["--name", name, "--reports", str(reports)]
        cargo("run", "-q", "-p", "evaluator", "--", *score)
    (perfect,) = rows(reports / "leaderboard_sets.csv", "set-truth-py")
    assert perfect["flow_source"] == "external" and perfect["failed"] == "0"
    for column in ("multi_scan_miou", "per_scan_miou", "multi_scan_ri", "per_scan_ri"):
        assert perfect[column] == "1.0000", column
    # The example's scores, recomputed here from its labels with MultiBodySync's own metric.
    import importlib.util

    spec = importlib.util.spec_from_file_location("lower_upper_sets", example)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    multi, per = [], []
    for s in sets:
        labels = [module.lower_upper(v.points) for v in s.views]
        multi.append(_miou(np.concatenate(labels), np.concatenate([v.parts for v in s.views])))
        per.append(np.mean([_miou(l, v.parts) for l, v in zip(labels, s.views)]))
    (row,) = rows(reports / "leaderboard_sets.csv", "lower-upper")
    assert int(row["sets"]) == len(sets) and row["failed"] == "0"
    assert float(row["multi_scan_miou"]) == pytest.approx(np.mean(multi), abs=5e-5)
    assert float(row["per_scan_miou"]) == pytest.approx(np.mean(per), abs=5e-5)
