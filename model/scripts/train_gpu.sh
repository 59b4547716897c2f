#!/usr/bin/env bash
# Continue a training run on a CUDA machine for a bounded time, from its latest checkpoint,
# and leave a checkpoint for the CPU trainer to resume from (and the other way round:
# checkpoints are burn records, which hold no device; not yet run on a GPU machine).
#
#   model/scripts/train_gpu.sh MINUTES [CONFIG] [CHECKPOINTS]
#
#   MINUTES      wall-clock minutes of training (the build comes on top)
#   CONFIG       config file or built-in name       [default: model/configs/cpu.toml]
#   CHECKPOINTS  checkpoint folder to resume from   [default: checkpoints/<config name>]
#
# Run from the repository root. It builds `model` with the `cuda` feature (burn's CUDA
# backend compiles its kernels at run time: a CUDA driver is needed, no toolkit), trains on
# GPU 0 for MINUTES minutes (the step under way is finished, then a checkpoint is written),
# and prints where the checkpoint is. Copy that folder back and run
# `cargo run --release -p model -- train --config CONFIG` to go on on the CPU.
set -euo pipefail

minutes="${1:?usage: $0 MINUTES [CONFIG] [CHECKPOINTS]}"
config="${2:-model/configs/cpu.toml}"
checkpoints="${3:-}"

if [[ ! -f Cargo.toml || ! -d model ]]; then
    echo "run this from the repository root" >&2
    exit 2
fi
if ! command -v nvidia-smi >/dev/null 2>&1; then
    echo "warning: nvidia-smi not found; the CUDA backend may not find a GPU" >&2
fi

cargo build --release -p model --features cuda
args=(train --config "$config" --device cuda --max-minutes "$minutes")
if [[ -n "$checkpoints" ]]; then
    args+=(--checkpoints "$checkpoints")
fi
./target/release/model "${args[@]}"
