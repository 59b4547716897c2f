"""A trivial set method (K observations of one object, the MultiBodySync setting): each view
is split in two by 2-means on its points, started from its lowest and highest point, and the
lower cluster is part 0 in every view, so one id names the same region in all K views.

    cargo run --release -p evaluator -- --all            # makes datasets/sets-scan
    python examples/lower_upper_sets.py datasets/sets-scan set-predictions.mcap
    cargo run --release -p evaluator -- score --dataset sets-scan \\
        --predictions set-predictions.mcap --name lower-upper

`PredictionWriter.write_set` writes a set's K label arrays as the records of the pairs
(view 0, view k); `evaluator score` lifts them to the set unchanged and puts the row on the
set board (`reports/leaderboard_sets.csv`) with multi-scan and per-scan mIoU and RI.
"""

import sys

import numpy as np

from part_induction import PredictionWriter, open_set_dataset


def lower_upper(points: np.ndarray, iterations: int = 10) -> np.ndarray:
    """uint32 [N]: 0 for the points nearer the lower of two 2-means centres (started from the
    lowest and the highest point along y), 1 for the others."""
    centres = np.stack([points[points[:, 1].argmin()], points[points[:, 1].argmax()]])
    labels = np.zeros(len(points), np.uint32)
    for _ in range(iterations):
        distances = ((points[:, None, :] - centres[None, :, :]) ** 2).sum(-1)  # [N, 2]
        labels = distances.argmin(1).astype(np.uint32)
        for c in range(2):
            if (labels == c).any():
                centres[c] = points[labels == c].mean(0)
    if centres[0, 1] > centres[1, 1]:
        labels = 1 - labels
    return labels


def main(dataset_dir: str, out: str) -> None:
    dataset = open_set_dataset(dataset_dir)
    with PredictionWriter(out, method="lower-upper", dataset=dataset) as writer:
        for s in dataset:
            writer.write_set(s.id, [lower_upper(points) for points in s.points()])
    print(f"wrote {len(writer)} pair records ({len(dataset)} sets) to {out}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: lower_upper_sets.py <set dataset folder> <predictions.mcap>")
    main(sys.argv[1], sys.argv[2])
