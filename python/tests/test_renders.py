"""Joints-only predictions for a render, written from Python and scored by
``evaluator score`` into joints_renders.csv in every convention."""

from __future__ import annotations

import csv
import json
from pathlib import Path
from typing import Callable, Dict, List

import pytest

from part_induction import RenderError, joint_from_trans, read_ground_truth, write_joint_predictions


@pytest.fixture(scope="module")
def paris_render(tmp_path_factory: pytest.TempPathFactory) -> Path:
    from conftest import run_cargo

    out = tmp_path_factory.mktemp("render") / "py-paris"
    args = ["render", "--layout", "paris", "-n", "3", "--views", "4", "--width", "64", "--height", "48"]
    run_cargo("run", "-q", "-p", "generator", "--", *args, "--out", str(out))
    return out


def board(reports: Path, method: str) -> Dict[str, Dict[str, str]]:
    with open(reports / "joints_renders.csv") as f:
        return {r["variant"]: r for r in csv.DictReader(f) if r["method"] == method}


def score(cargo: Callable[..., str], render: Path, predictions: Path, reports: Path) -> None:
    args = ["score", "--dataset", str(render), "--predictions", str(predictions), "--reports", str(reports)]
    cargo("run", "-q", "-p", "evaluator", "--", *args)


def test_paris_ground_truth_read_from_its_own_files_scores_perfectly(
    paris_render: Path, tmp_path: Path, cargo: Callable[..., str]
) -> None:
    truth = read_ground_truth(paris_render)
    assert truth["layout"] == "paris" and len(truth["objects"]) == 3
    # What a PARIS user has: the trans.json of each object (PARIS's own ground-truth format).
    objects: Dict[str, List[dict]] = {}
    for o in truth["objects"]:
        trans = json.loads((paris_render / "data" / o["folder"] / "textured_objs" / "trans.json").read_text())
        objects[o["folder"]] = [joint_from_trans(trans["trans_info"])]
    predictions = write_joint_predictions(tmp_path / "joints.json", "trans-py", objects, render=paris_render)
    reports = tmp_path / "reports"
    score(cargo, paris_render, predictions, reports)
    rows = board(reports, "trans-py")
    assert set(rows) == {"ours", "paris", "dta", "artgs"}
    for variant, row in rows.items():
        assert row["joints"] == "3" and row["matched"] == "3", variant
        assert float(row["type_accuracy"]) == 1.0
        assert float(row["axis_angle_deg"]) < 1e-3, (variant, row)
        for column in ("axis_distance", "state_revolute_deg", "state_prismatic"):
            assert row[column] == "" or float(row[column]) < 1e-3, (variant, column, row)


def test_the_conventions_differ_on_a_parallel_offset_axis(
    paris_render: Path, tmp_path: Path, cargo: Callable[..., str]
) -> None:
    truth = read_ground_truth(paris_render)
    revolute = [o for o in truth["objects"] if o["joints"][0]["type"] == "revolute"]
    assert revolute, "a test object with a hinge"
    o = revolute[0]
    j = o["joints"][0]
    # The true axis moved 0.1 world units sideways (perpendicular to it), same direction.
    axis = j["axis"]
    side = [axis[1], -axis[0], 0.0] if abs(axis[2]) < 0.9 else [0.0, axis[2], -axis[1]]
    norm = sum(x * x for x in side) ** 0.5
    pivot = [p + 0.1 * s / norm for p, s in zip(j["pivot"], side)]
    guess = {"type": "revolute", "axis": axis, "pivot": pivot, "state": j["state"]}
    predictions = write_joint_predictions(tmp_path / "offset.json", "offset-py", {o["folder"]: [guess]})
    reports = tmp_path / "reports"
    score(cargo, paris_render, predictions, reports)
    rows = board(reports, "offset-py")
    assert rows["ours"]["joints"] == "3" and rows["ours"]["matched"] == "1"
    assert float(rows["paris"]["axis_distance"]) == 0.0, "PARIS: parallel axes are 0 apart"
    assert abs(float(rows["dta"]["axis_distance"]) - 1.0) < 1e-3, "DigitalTwinArt: 0.1 x 10"
    assert abs(float(rows["ours"]["axis_distance"]) - 0.1 / o["diagonal"]) < 1e-4


def test_bad_joints_are_refused_before_writing(tmp_path: Path, paris_render: Path) -> None:
    with pytest.raises(RenderError, match="zero"):
        write_joint_predictions(tmp_path / "j.json", "m", {"x": [{"type": "revolute", "axis": [0, 0, 0], "pivot": [0, 0, 0], "state": 1.0}]})
    with pytest.raises(RenderError, match="not in the render"):
        write_joint_predictions(tmp_path / "j.json", "m", {"nope": []}, render=paris_render)
    with pytest.raises(RenderError, match="finite"):
        write_joint_predictions(tmp_path / "j.json", "m", {"x": [{"type": "prismatic", "axis": [1, 0, 0], "pivot": [0, 0, 0], "state": float("nan")}]})
    assert not (tmp_path / "j.json").exists()
