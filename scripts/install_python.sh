#!/usr/bin/env bash
# Installs the Python package (pip install .) from the CMake build tree the quick-start commands
# just built, so nothing is compiled twice: scikit-build-core reuses BUILD (its configuration is
# the same as the one this repository's scripts use) and installs the extension and the package
# into the running Python. A user who has not built anything runs plain `pip install .`.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
PY=${PYTHON:-python3}
export CMAKE_GENERATOR=Ninja  # as the scripts configure BUILD
TESTS=${GPUGEOM_TESTS:-ON}
BENCH=${GPUGEOM_BENCH:-ON}
"$PY" -m pip install -q --no-build-isolation --no-deps \
  -C build-dir="$BUILD" \
  -C cmake.define.GPUGEOM_TESTS="$TESTS" -C cmake.define.GPUGEOM_BENCH="$BENCH" \
  -C cmake.define.GPUGEOM_CLI=ON -C cmake.define.GPUGEOM_STATIC_CUDART=OFF \
  -C cmake.define.GPUGEOM_CUDA="${GPUGEOM_CUDA:-AUTO}" .
"$PY" -c "import gpugeom; print('gpugeom', gpugeom.__version__, 'installed; CUDA build:', gpugeom.built_with_cuda())"
