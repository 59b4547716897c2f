#!/usr/bin/env bash
# Continue a training run on a CUDA machine for a bounded time, from its latest checkpoint,
# and leave a checkpoint for the CPU trainer to resume from (and the other way round:
# checkpoints are burn records, which hold no device; model/TRAINING.md, "The GPU path",
# records the check on an H200).
#
#   model/scripts/train_gpu.sh MINUTES [CONFIG] [CHECKPOINTS] [REPORTS]
#
#   MINUTES      wall-clock minutes of training (the build comes on top)
#   CONFIG       config file or built-in name       [default: model/configs/cpu.toml]
#   CHECKPOINTS  checkpoint folder to resume from   [default: checkpoints/<config name>]
#   REPORTS      folder for log.csv, loss.png and validation.csv
#                                                   [default: reports/training/<config name>]
#
# Environment:
#   MODEL_BIN           a `model` binary already built with `--features cuda` (for a GPU
#                       machine without a Rust toolchain); without it the script builds one
#   CUDARC_CUDA_VERSION the CUDA version to build against when `nvcc` is not on the PATH,
#                       as cudarc spells it (13000 for CUDA 13.0, 12080 for 12.8)
#
# Run from the repository root. Without MODEL_BIN it builds `model` with the `cuda`
# feature: burn's CUDA backend compiles its kernels at run time with NVRTC, so the machine
# needs the NVIDIA driver and NVRTC (`libnvrtc.so.<major>`, from the CUDA toolkit or the
# `nvidia-cuda-nvrtc` Python wheel) on the library path; the build needs only crates.io
# (cubecl-cuda's LLVM compiler, unused with NVRTC, is the workspace's shims/cubecl-llvm).
# It then trains on GPU 0 for MINUTES
# minutes (the step under way is finished, then a checkpoint is written) and prints where
# the checkpoint is. Copy that folder back and run
# `cargo run --release -p model -- train --config CONFIG --checkpoints CHECKPOINTS` to go on
# on the CPU.
set -euo pipefail

minutes="${1:?usage: $0 MINUTES [CONFIG] [CHECKPOINTS] [REPORTS]}"
config="${2:-model/configs/cpu.toml}"
checkpoints="${3:-}"
reports="${4:-}"

if [[ ! -f Cargo.toml || ! -d model ]]; then
    echo "run this from the repository root" >&2
    exit 2
fi
if ! command -v nvidia-smi >/dev/null 2>&1; then
    echo "warning: nvidia-smi not found; the CUDA backend may not find a GPU" >&2
fi

model="${MODEL_BIN:-}"
if [[ -z "$model" ]]; then
    if ! command -v nvcc >/dev/null 2>&1 && [[ -z "${CUDARC_CUDA_VERSION:-}" ]]; then
        echo "nvcc not found: set CUDARC_CUDA_VERSION to the machine's CUDA version" \
            "(13000 for 13.0, 12080 for 12.8)" >&2
        exit 2
    fi
    cargo build --release -p model --features cuda
    model=./target/release/model
fi
args=(train --config "$config" --device cuda --max-minutes "$minutes")
if [[ -n "$checkpoints" ]]; then
    args+=(--checkpoints "$checkpoints")
fi
if [[ -n "$reports" ]]; then
    args+=(--reports "$reports")
fi
"$model" "${args[@]}"
