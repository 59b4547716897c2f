"""Shared fixtures: small datasets made by the Rust generator, and the Rust reader's view of
them (`pairs/examples/dump_pairs.rs`), so the Python reader is checked against the Rust side.

Cargo runs from the repository root in the dev profile and honours CARGO_TARGET_DIR.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path
from typing import Any, Callable, Dict, List

import pytest

PYTHON_DIR = Path(__file__).resolve().parents[1]
REPO = PYTHON_DIR.parent


def run_cargo(*args: str) -> str:
    """Runs `cargo <args>` at the repository root; fails the test with cargo's output."""
    result = subprocess.run(
        ["cargo", *args], cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    if result.returncode != 0:
        pytest.fail(
            f"cargo {' '.join(args)} exited {result.returncode}\n"
            f"stdout:\n{result.stdout}\nstderr:\n{result.stderr}",
            pytrace=False,
        )
    return result.stdout


def generate(out: Path, kind: str, objects: int, points: int) -> Path:
    args = ["--kind", kind, "-n", str(objects), "-p", str(points), "--seed", "7"]
    run_cargo("run", "-q", "-p", "generator", "--", *args, "--out", str(out))
    return out


@pytest.fixture(scope="session")
def sf2f_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """15 SF2F pairs (3 objects) of 96 points, in a folder named `py-sf2f` (the evaluator
    refuses a folder named after a default dataset, such as `sf2f`)."""
    return generate(tmp_path_factory.mktemp("data") / "py-sf2f", "sf2f", 3, 96)


@pytest.fixture(scope="session")
def sp2p_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """10 SP2P pairs (2 objects) of 64 points, both sides scanned, with images."""
    return generate(tmp_path_factory.mktemp("data") / "py-sp2p", "sp2p", 2, 64)


@pytest.fixture(scope="session")
def xf2p_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """10 XF2P pairs (2 objects, each against a second instance of its category) of 64
    points: no flow, Q scanned."""
    return generate(tmp_path_factory.mktemp("data") / "py-xf2p", "xf2p", 2, 64)


@pytest.fixture(scope="session")
def rust_dump(tmp_path_factory: pytest.TempPathFactory) -> Callable[[Path], List[Dict[str, Any]]]:
    """Every field of every pair of a dataset as the Rust reader sees it."""
    cache: Dict[Path, List[Dict[str, Any]]] = {}

    def dump(dataset: Path) -> List[Dict[str, Any]]:
        if dataset not in cache:
            out = tmp_path_factory.mktemp("dump") / "pairs.json"
            example = ["run", "-q", "-p", "pairs", "--example", "dump_pairs", "--"]
            run_cargo(*example, str(dataset), str(out))
            cache[dataset] = json.loads(out.read_text())
        return cache[dataset]

    return dump


@pytest.fixture
def cargo() -> Callable[..., str]:
    """`cargo(*args)` runs cargo at the repository root and returns its stdout."""
    return run_cargo


@pytest.fixture
def python_env() -> Dict[str, str]:
    """The environment for a Python subprocess that imports the package from this tree."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(PYTHON_DIR), env.get("PYTHONPATH")]))
    return env


@pytest.fixture(scope="session")
def sets_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """3 mixed sets (3 objects) of 4 views of 64 points: view 0 a full shape, views 1-3
    scans with images (`generator --kind sets`)."""
    out = tmp_path_factory.mktemp("data") / "py-sets"
    args = ["--kind", "sets", "--views", "4", "--mode", "mixed", "-n", "3", "-p", "64"]
    run_cargo("run", "-q", "-p", "generator", "--", *args, "--seed", "7", "--out", str(out))
    return out


EXPORT_SEED = 3
"""The seed of the exported objects (`exported`, `kinematics`)."""


@pytest.fixture(scope="session")
def categories() -> List[str]:
    """Every built-in category of every split (`generator --list-categories`)."""
    listing = run_cargo("run", "-q", "-p", "generator", "--", "--list-categories")
    return [line.split()[0] for line in listing.splitlines() if line.strip()]


@pytest.fixture(scope="session")
def exported(tmp_path_factory: pytest.TempPathFactory, categories: List[str]) -> Path:
    """One object of every category, exported (URDF, MJCF, USD, collision hulls)."""
    out = tmp_path_factory.mktemp("objects") / "objects"
    run_cargo(
        "run", "-q", "-p", "generator", "--", "export-objects", "--seed", str(EXPORT_SEED),
        "--categories", ",".join(categories), "-n", str(len(categories)), "--out", str(out),
    )
    return out


@pytest.fixture(scope="session")
def kinematics(categories: List[str]) -> List[Dict[str, Any]]:
    """The generator's forward kinematics of `exported` (`generator/examples/
    kinematics_json.rs`): every link's transform at several joint configurations."""
    text = run_cargo(
        "run", "-q", "-p", "generator", "--example", "kinematics_json", "--",
        "--seed", str(EXPORT_SEED), "--categories", ",".join(categories),
        "-n", str(len(categories)), "--states", "2",
    )
    return json.loads(text)
