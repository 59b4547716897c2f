"""A trivial method on the benchmark: one segment for every point, nearest-neighbour flow.

    python examples/one_segment_nn.py datasets/sf2f predictions.mcap
    cargo run --release -p evaluator -- score --dataset sf2f \
        --predictions predictions.mcap --name one-segment-nn

This writes one prediction per pair. Scored, its EPE should match the built-in `nn` row (the
same flow) and its RI and IoU the `one-part` row (one segment for everything).
"""

import sys

import numpy as np

from part_induction import PredictionWriter, open_dataset


def nearest_neighbour_flow(p: np.ndarray, q: np.ndarray, chunk: int = 256) -> np.ndarray:
    """float32 [N_p, 3]: from each point of P (float32 [N_p, 3]) to its nearest point of Q
    (float32 [N_q, 3]), both taken as they are in their normalised frames."""
    flow = np.empty_like(p)
    for start in range(0, len(p), chunk):
        block = p[start : start + chunk]
        distances = ((block[:, None, :] - q[None, :, :]) ** 2).sum(-1)  # [chunk, N_q]
        flow[start : start + chunk] = q[distances.argmin(1)] - block
    return flow


def main(dataset_dir: str, out: str) -> None:
    dataset = open_dataset(dataset_dir)
    with PredictionWriter(out, method="one-segment-nn", dataset=dataset) as writer:
        for pair in dataset.inputs():  # P and Q only, no ground truth
            writer.write(
                pair.id,
                segments_p=np.zeros(len(pair.p), np.uint32),
                segments_q=np.zeros(len(pair.q), np.uint32),
                flow=nearest_neighbour_flow(pair.p, pair.q),
            )
    print(f"wrote {len(writer)} predictions to {out}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: one_segment_nn.py <dataset folder> <predictions.mcap>")
    main(sys.argv[1], sys.argv[2])
