"""Objects exported by `generator export-objects`, checked by a URDF reader we did not write
(yourdfpy): one object of every category (train, validation and test) loads without
warnings; its joints' types, limits and axes are the generator's; each link's world transform and posed mesh bounds at several joint
configurations match the generator's own forward kinematics (`generator/examples/
kinematics_json.rs`) to 1e-5; and for pairs made from the exported objects
(`generator --assets`), posing the URDF at each pair's recorded joint values and global
poses, then normalising as recorded, reproduces every part's ground-truth motion to 1e-4.
"""

from __future__ import annotations

import json
import logging
import warnings
from pathlib import Path
from typing import Any, Dict, List

import numpy as np
import pytest
import trimesh  # the `test` extra installs trimesh and yourdfpy
import yourdfpy

from conftest import EXPORT_SEED, run_cargo
from part_induction import open_dataset


SEED = EXPORT_SEED


def load(urdf: Path) -> "yourdfpy.URDF":
    return yourdfpy.URDF.load(str(urdf), build_scene_graph=True, load_meshes=True)


def actuated(robot: "yourdfpy.URDF", values: Dict[str, float]) -> Dict[str, float]:
    return {name: values[name] for name in robot.actuated_joint_names}


def test_every_category_exports_and_loads_without_warnings(
    exported: Path,
    kinematics: List[Dict[str, Any]],
    categories: List[str],
    caplog: pytest.LogCaptureFixture,
) -> None:
    index = json.loads((exported / "objects.json").read_text())
    assert [o["folder"] for o in index] == [o["folder"] for o in kinematics]
    assert [o["category"] for o in index] == categories, "one object of every category"
    assert len(categories) >= 39
    for entry in index:
        folder = exported / entry["folder"]
        caplog.clear()
        with caplog.at_level(logging.WARNING), warnings.catch_warnings():
            warnings.simplefilter("error")
            robot = load(folder / "mobility.urdf")
            assert robot.validate(), entry["folder"]
        assert not caplog.records, f"{entry['folder']}: {[r.getMessage() for r in caplog.records]}"
        meta = json.loads((folder / "meta.json").read_text())
        assert meta["category"] == entry["category"] == robot.robot.name
        mobility = json.loads((folder / "mobility_v2.json").read_text())
        assert len(mobility) == len(meta["links"]) == entry["links"]


def test_joints_and_forward_kinematics_match_the_generator(
    exported: Path, kinematics: List[Dict[str, Any]]
) -> None:
    for obj in kinematics:
        robot = load(exported / obj["folder"] / "mobility.urdf")
        for joint in obj["joints"]:
            mine = robot.joint_map[joint["name"]]
            assert mine.type == joint["type"], joint["name"]
            assert mine.parent == joint["parent"] and mine.child == joint["child"]
            np.testing.assert_allclose(mine.axis, joint["axis"], atol=1e-7)
            np.testing.assert_allclose(
                [mine.limit.lower, mine.limit.upper], [joint["lower"], joint["upper"]], atol=1e-7
            )
        for state in obj["states"]:
            robot.update_cfg(actuated(robot, state["values"]))
            for link, expected in state["links"].items():
                transform = robot.get_transform(frame_to=link, frame_from="base")
                np.testing.assert_allclose(
                    transform, expected["transform"], atol=1e-5, err_msg=f"{obj['folder']} {link}"
                )
                visual = robot.link_map[link].visuals[0]
                mesh = trimesh.load(
                    str(exported / obj["folder"] / visual.geometry.mesh.filename),
                    force="mesh", process=False,
                )
                posed = trimesh.transform_points(mesh.vertices, transform @ visual.origin)
                bounds = np.stack([posed.min(axis=0), posed.max(axis=0)])
                np.testing.assert_allclose(
                    bounds, expected["bounds"], atol=1e-5, err_msg=f"{obj['folder']} {link}"
                )


def pose_matrix(pose: Dict[str, Any]) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = np.asarray(pose["rotation"], dtype=np.float64).reshape(3, 3)
    m[:3, 3] = pose["translation"]
    return m


def normaliser(centre: np.ndarray, scale: float) -> np.ndarray:
    m = np.eye(4) / scale
    m[3, 3] = 1.0
    m[:3, 3] = -np.asarray(centre, dtype=np.float64) / scale
    return m


@pytest.mark.parametrize("kind", ["sf2f", "sp2p"])
def test_recorded_configurations_and_poses_reproduce_every_motion(
    exported: Path, categories: List[str], tmp_path: Path, kind: str
) -> None:
    dataset = tmp_path / f"from-urdf-{kind}"
    run_cargo(
        "run", "-q", "-p", "generator", "--", "--assets", str(exported), "--kind", kind,
        "--seed", str(SEED), "-p", "128", "--min-part-points", "4", "--out", str(dataset),
    )
    folders = sorted(p.name for p in exported.iterdir() if p.is_dir())
    robots: Dict[int, Any] = {}
    checked = 0
    for pair in open_dataset(dataset):
        prov = pair.provenance
        object_id = prov["object_id"]
        if object_id not in robots:
            robots[object_id] = load(exported / folders[object_id] / "mobility.urdf")
        robot = robots[object_id]
        links = [name for name in robot.link_map if name != "base"]

        def world(values: Dict[str, float], pose: Dict[str, Any]) -> Dict[str, np.ndarray]:
            assert set(values) == set(robot.joint_names) - {"base_joint"}, "every joint by name"
            robot.update_cfg(actuated(robot, values))
            g = pose_matrix(pose)
            return {link: g @ robot.get_transform(frame_to=link, frame_from="base") for link in links}

        world_p = world(prov["joints_p"], prov["pose_p"])
        world_q = world(prov["joints_q"], prov["pose_q"])
        n_p = normaliser(pair.p_centre, pair.p_scale)
        n_q = normaliser(pair.q_centre, pair.q_scale)
        motions = []
        for rotation, translation in zip(pair.motions.rotations, pair.motions.translations):
            t = np.eye(4)
            t[:3, :3] = pair.motions.scale * rotation.astype(np.float64)
            t[:3, 3] = translation
            motions.append(t)
        matched = set()
        for link in links:
            moved = n_q @ world_q[link] @ np.linalg.inv(world_p[link]) @ np.linalg.inv(n_p)
            errors = [np.abs(moved - t).max() for t in motions]
            k = int(np.argmin(errors))
            assert errors[k] < 1e-4, f"{pair.id} {link}: nearest motion off by {errors[k]}"
            matched.add(k)
        assert matched == set(range(len(motions))), f"{pair.id}: every part has a link"
        checked += 1
    assert checked == len(categories) * 5


def test_the_cli_round_trip_gives_the_built_in_pairs(
    exported: Path, categories: List[str], tmp_path: Path
) -> None:
    """`generator --assets <exported>` and the built-in objects, same seed and settings:
    the same pairs, field for field (provenance included)."""
    common = ["--seed", str(SEED), "-p", "96", "--min-part-points", "4"]
    from_urdf, built_in = tmp_path / "from-urdf", tmp_path / "built-in"
    run_cargo("run", "-q", "-p", "generator", "--", "--assets", str(exported), *common,
              "--out", str(from_urdf))  # fmt: skip
    run_cargo("run", "-q", "-p", "generator", "--", "--categories", ",".join(categories),
              "-n", str(len(categories)), *common, "--out", str(built_in))  # fmt: skip
    a, b = list(open_dataset(from_urdf)), list(open_dataset(built_in))
    assert len(a) == len(b) == 5 * len(categories)
    for x, y in zip(a, b):
        assert x.id == y.id and x.provenance == y.provenance
        for field in ["p", "q", "part_p", "part_q", "flow", "corr_mask", "corr_index"]:
            np.testing.assert_array_equal(getattr(x, field), getattr(y, field), err_msg=x.id)
    assert (from_urdf / "pairs.mcap").read_bytes() == (built_in / "pairs.mcap").read_bytes()
