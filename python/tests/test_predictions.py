"""PredictionWriter: round trips through read_predictions, the file layout of
docs/FORMAT.md, and the writer's refusals."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Dict

import cbor2
import numpy as np
import pytest
from mcap.records import Channel, Chunk, Header, Message
from mcap.stream_reader import StreamReader

from part_induction import (
    PredictedJoint,
    PredictionError,
    PredictionWriter,
    open_dataset,
    read_predictions,
)

HASH = "ab" * 32


def rotation_z(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]], np.float32)


def full_prediction(rng: np.random.Generator, n_p: int = 20, n_q: int = 30) -> Dict[str, Any]:
    return {
        "segments_p": rng.integers(0, 3, n_p).astype(np.int64),
        "segments_q": rng.integers(0, 3, n_q).astype(np.uint8),
        "flow": rng.normal(size=(n_p, 3)),
        "motions": (
            np.stack([rotation_z(a) for a in (0.0, 0.5, -1.0)]),
            rng.normal(size=(3, 3)).astype(np.float32),
            np.array([1.0, 1.5, 0.5]),
        ),
        "corr_mask": rng.random(n_p),
        "segment_probs": rng.random((n_p, 3)).astype(np.float32),
        "joints": [
            None,
            PredictedJoint("revolute", [0.0, 0.0, 1.0], [0.1, 0.2, 0.3], 0.5),
            {"kind": "prismatic", "axis": np.array([1.2, 1.6, 0.0]), "pivot": [0, 0, 0],
             "value": -0.25},  # stored normalised
        ],
    }


def test_round_trip(tmp_path: Path) -> None:
    rng = np.random.default_rng(0)
    path = tmp_path / "predictions.mcap"
    written = {f"pair-{i}": full_prediction(rng) for i in range(3)}
    with PredictionWriter(path, "my-method", HASH, method_version="1.2.0") as writer:
        for pair_id, prediction in written.items():
            writer.write(pair_id, **prediction)
        writer.write("only-segments", np.zeros(5, np.int32))
        writer.write_error("failed", "did not converge")
        assert len(writer) == 5
    header, predictions = read_predictions(path)
    assert header == {
        "format": "part-induction-predictions",
        "format_version": 1,
        "method": "my-method",
        "method_version": "1.2.0",
        "dataset": HASH,
    }
    read = list(predictions)
    assert [r["id"] for r in read] == [*written, "only-segments", "failed"]
    for r in read[:3]:
        w = written[r["id"]]
        assert r["segments_p"].dtype == np.uint32
        np.testing.assert_array_equal(r["segments_p"], w["segments_p"])
        np.testing.assert_array_equal(r["segments_q"], w["segments_q"])
        np.testing.assert_array_equal(r["flow"], w["flow"].astype(np.float32))
        assert r["flow"].shape == (20, 3) and r["flow"].dtype == np.float32
        np.testing.assert_array_equal(r["motions"]["rotations"], w["motions"][0])
        np.testing.assert_array_equal(r["motions"]["translations"], w["motions"][1])
        np.testing.assert_array_equal(r["motions"]["scales"], [1.0, 1.5, 0.5])
        np.testing.assert_array_equal(r["corr_mask"], w["corr_mask"].astype(np.float32))
        np.testing.assert_array_equal(r["segment_probs"], w["segment_probs"])
        assert r["joints"][0] is None
        assert r["joints"][1]["kind"] == "revolute" and r["joints"][1]["value"] == 0.5
        np.testing.assert_array_equal(r["joints"][2]["axis"], np.float32([0.6, 0.8, 0.0]))
        assert r["joints"][2]["value"] == -0.25
    assert set(read[3]) == {"id", "segments_p"}
    assert read[4] == {"id": "failed", "error": "did not converge"}
    assert not Path(f"{path}.partial").exists()


def test_the_file_layout_is_the_documented_one(tmp_path: Path) -> None:
    path = tmp_path / "p.mcap"
    with PredictionWriter(path, "m", HASH) as writer:
        writer.write("a", [0, 1], flow=np.zeros((2, 3)))
        writer.write("b", [0, 0])
    with open(path, "rb") as f:
        records = list(StreamReader(f, validate_crcs=True, emit_chunks=True).records)
    assert next(r for r in records if isinstance(r, Header)).profile == ""
    chunks = [r for r in records if isinstance(r, Chunk)]
    assert chunks and all(c.compression == "zstd" for c in chunks)
    with open(path, "rb") as f:
        records = list(StreamReader(f).records)
    channels = {r.id: r for r in records if isinstance(r, Channel)}
    assert {c.topic: (c.message_encoding, c.schema_id, c.metadata) for c in channels.values()} == {
        "/header": ("cbor", 0, {"schema": "part_induction.PredictionHeader",
                                "schema_version": "1"}),
        "/prediction": ("cbor", 0, {"schema": "part_induction.Prediction",
                                    "schema_version": "1"}),
    }
    messages = [r for r in records if isinstance(r, Message)]
    assert [(channels[m.channel_id].topic, m.log_time) for m in messages] == [
        ("/header", 0), ("/prediction", 1), ("/prediction", 2),
    ]
    first = cbor2.loads(messages[1].data)
    assert list(first) == ["id", "segments_p", "flow"]
    assert first["segments_p"] == np.array([0, 1], "<u4").tobytes()


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"segments_p": np.zeros(4, np.float32)}, r"`segments_p` must hold integers"),
        ({"segments_p": np.zeros((4, 1), int)}, r"`segments_p` has shape \(4, 1\)"),
        ({"segments_p": [-1, 0, 0, 0]}, r"`segments_p` has ids outside"),
        ({"segments_q": ["a"]}, r"`segments_q` must hold integers"),
        ({"flow": np.zeros((4, 2))}, r"`flow` has shape \(4, 2\), expected \[4, 3\]"),
        ({"flow": np.zeros((5, 3))}, r"`flow` has shape \(5, 3\)"),
        ({"flow": np.full((4, 3), np.nan)}, r"`flow` has a NaN or infinite value at entry 0"),
        ({"flow": np.array([[0, 0, 0]] * 3 + [[0, np.inf, 0]])}, r"`flow` .* at entry 3"),
        ({"flow": np.full((4, 3), "x")}, r"`flow` must hold floats"),
        ({"flow": np.full((4, 3), 1e39)}, r"`flow` has a NaN or infinite"),  # f32 overflow
        ({"corr_mask": np.full(4, 1.5)}, r"`corr_mask` has values outside \[0, 1\]"),
        ({"segment_probs": np.full((4,), 0.5)}, r"`segment_probs` has shape \(4,\)"),
        ({"motions": (np.eye(3)[None], np.zeros((1, 3)))}, r"`motions` has 1 entries, expected 2"),
        ({"motions": (np.stack([np.eye(3)] * 2), np.zeros((2, 2)))},
         r"`motions.translations` has shape"),
        ({"motions": (np.stack([np.eye(3), 2 * np.eye(3)]), np.zeros((2, 3)))},
         r"`motions` rotation 1 is not a rotation matrix"),
        ({"motions": (np.stack([np.eye(3), -np.eye(3)]), np.zeros((2, 3)))},
         r"`motions` rotation 1 is not a rotation matrix"),
        ({"motions": (np.stack([np.eye(3)] * 2), np.zeros((2, 3)), [1, 0])},
         r"`motions` scales must be positive"),
        ({"motions": np.eye(3)}, r"`motions` must be"),
        ({"joints": [None]}, r"`joints` has 1 entries, expected 2"),
        ({"joints": [None, {"kind": "ball", "axis": [1, 0, 0], "pivot": [0, 0, 0], "value": 1}]},
         r"`joints\[1\].kind` 'ball'"),
        ({"joints": [None, {"kind": "revolute", "axis": [0, 0, 0], "pivot": [0, 0, 0],
                            "value": 1}]}, r"`joints\[1\].axis` is zero"),
        ({"segment_probs": np.zeros((4, 0))}, r"`segment_probs` has no columns"),
        ({"joints": [None, {"kind": "revolute", "axis": [1, 0, 0]}]}, r"`joints\[1\]` lacks"),
        ({"joints": [None, PredictedJoint("revolute", [1, 0, 0], [0, 0, 0], float("nan"))]},
         r"`joints\[1\].value` has a NaN"),
    ],
)
def test_the_writer_refuses(tmp_path: Path, kwargs: Dict[str, Any], message: str) -> None:
    args = {"segments_p": np.array([0, 1, 1, 0])}
    args.update(kwargs)
    path = tmp_path / "p.mcap"
    with PredictionWriter(path, "m", HASH) as writer:
        with pytest.raises(PredictionError, match=rf"pair 'x': {message}"):
            writer.write("x", **args)
        writer.write("y", [0])  # a refusal leaves the writer usable
    _, predictions = read_predictions(path)
    assert [p["id"] for p in predictions] == ["y"]


def test_repeated_ids_and_bad_headers_are_refused(tmp_path: Path) -> None:
    with pytest.raises(PredictionError, match="not a sha256"):
        PredictionWriter(tmp_path / "p.mcap", "m", "abc")
    with pytest.raises(PredictionError, match="method must not be empty"):
        PredictionWriter(tmp_path / "p.mcap", "", HASH)
    with PredictionWriter(tmp_path / "p.mcap", "m", HASH) as writer:
        writer.write("a", [0])
        with pytest.raises(PredictionError, match="pair 'a': already written"):
            writer.write_error("a", "again")
        with pytest.raises(PredictionError, match="non-empty"):
            writer.write_error("b", "")


def test_an_exception_removes_the_partial_file(tmp_path: Path) -> None:
    path = tmp_path / "p.mcap"
    path.write_bytes(b"an older file")
    with pytest.raises(RuntimeError, match="method crashed"):
        with PredictionWriter(path, "m", HASH) as writer:
            writer.write("a", [0])
            assert Path(f"{path}.partial").exists()
            raise RuntimeError("method crashed")
    assert not Path(f"{path}.partial").exists()
    assert path.read_bytes() == b"an older file"
    writer = PredictionWriter(path, "m", HASH)
    writer.write("a", [0])
    assert path.read_bytes() == b"an older file"  # nothing under the real name before close
    writer.close()
    assert read_predictions(path)[0]["method"] == "m"


def test_a_dataset_checks_ids_and_sizes(sf2f_dir: Path, tmp_path: Path) -> None:
    dataset = open_dataset(sf2f_dir)
    pair = next(iter(dataset))
    with PredictionWriter(tmp_path / "p.mcap", "m", dataset) as writer:
        with pytest.raises(PredictionError, match="pair 'nope': not a pair of the dataset"):
            writer.write("nope", [0])
        with pytest.raises(PredictionError, match=r"`segments_p` has shape \(95,\)"):
            writer.write(pair.id, np.zeros(95, int))
        with pytest.raises(PredictionError, match=r"`segments_q` has shape \(3,\)"):
            writer.write(pair.id, np.zeros(96, int), segments_q=np.zeros(3, int))
        # The ground truth as a prediction; a pair's Motions is taken as it is.
        writer.write(pair.id, pair.part_p, segments_q=pair.part_q, motions=pair.motions)
    header, predictions = read_predictions(tmp_path / "p.mcap")
    assert header["dataset"] == dataset.content_hash
    (read,) = predictions
    np.testing.assert_array_equal(read["motions"]["rotations"], pair.motions.rotations)
    assert (read["motions"]["scales"] == pair.scale).all()


def test_reading_refuses_other_files(sf2f_dir: Path, tmp_path: Path) -> None:
    with pytest.raises(PredictionError, match=r"wrong schema: /pair|no /header message"):
        read_predictions(sf2f_dir / "pairs.mcap")
    path = tmp_path / "p.mcap"
    with PredictionWriter(path, "m", HASH) as writer:
        for i in range(200):
            flow = np.random.default_rng(i).random((300, 3))
            writer.write(f"p{i}", np.arange(300) % 7, flow=flow)
    data = path.read_bytes()
    (tmp_path / "cut.mcap").write_bytes(data[: len(data) // 2])
    with pytest.raises(PredictionError, match="not a readable MCAP file after"):
        header, predictions = read_predictions(tmp_path / "cut.mcap")
        list(predictions)
