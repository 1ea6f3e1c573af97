#!/usr/bin/env bash
# Quick start 2: install what is needed, build everything, run the whole test suite.
# The gpu label runs too: where no CUDA device is usable its tests report "skipped".
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
BUILD=${BUILD_DIR:-build}
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DGPUGEOM_CUDA=${GPUGEOM_CUDA:-AUTO}
cmake --build "$BUILD"
# The Python package, installed from this build (nothing compiled again): pip install .
bash scripts/install_python.sh "$BUILD"
cd "$BUILD"
ctest --output-on-failure -L "cpu|gpu"
