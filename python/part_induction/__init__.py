"""Read part-induction datasets and write prediction files for the benchmark, from Python.

The formats are docs/FORMAT.md. :func:`open_dataset` streams a dataset's pairs as numpy
arrays, :func:`open_set_dataset` the sets of K views of a set dataset (each set's pairs
with :meth:`Set.pair`), :class:`PredictionWriter` writes a method's predictions for
``evaluator score``, and ``part_induction.torch`` (which needs PyTorch; importing this package does not import it)
wraps a dataset for a ``DataLoader``. ``part_induction.renders`` reads a render's ground truth
(``generator render``) and writes joints-only predictions for it.
"""

from .dataset import (
    Dataset,
    DatasetError,
    Joint,
    Motions,
    Pair,
    PairInput,
    collate_numpy,
    open_dataset,
)
from .sets import Set, SetDataset, SetJoint, SetView, collate_sets_numpy, open_set_dataset
from .renders import (
    RenderError,
    joint_from_trans,
    read_ground_truth,
    write_joint_predictions,
)
from .predictions import (
    PredictedJoint,
    PredictionError,
    PredictionWriter,
    read_predictions,
)

__all__ = [
    "RenderError",
    "joint_from_trans",
    "read_ground_truth",
    "write_joint_predictions",
    "Dataset",
    "DatasetError",
    "Joint",
    "Motions",
    "Pair",
    "PairInput",
    "Set",
    "SetDataset",
    "SetJoint",
    "SetView",
    "PredictedJoint",
    "PredictionError",
    "PredictionWriter",
    "collate_numpy",
    "open_dataset",
    "open_set_dataset",
    "collate_sets_numpy",
    "read_predictions",
]
