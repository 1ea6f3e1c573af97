#!/usr/bin/env bash
# Builds the documentation site into build/docs/html (open build/docs/html/index.html), with
# warnings as errors: the user guide, the gallery (python/examples/ run at small sizes on the CPU
# executor, their pictures made now), the Python reference from the installed package's
# docstrings, the C++ reference from the headers (Doxygen's XML through Breathe), the command-line
# reference from the tool's --help, and the benchmark plots from docs/bench_*.csv.
# A missing description, a broken example or a dangling reference fails the build.
#
# It needs the package installed and the tool built: scripts/test.sh does both (and then calls
# this); on its own it builds them first into BUILD_DIR (default build), as test.sh would.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD_DIR:-build}
PY=${PYTHON:-python3}
DOCS_DEPS=${DOCS_DEPS:-1} bash scripts/install_deps.sh
if ! "$PY" -c "import gpugeom" >/dev/null 2>&1 || [ ! -x "$BUILD/tools/gpugeom/gpugeom" ]; then
  cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DGPUGEOM_CUDA=${GPUGEOM_CUDA:-AUTO}
  cmake --build "$BUILD"
  bash scripts/install_python.sh "$BUILD"
fi
OUT=build/docs
rm -rf "$OUT/doxygen" docs/_generated docs/auto_examples
mkdir -p "$OUT/doxygen"
# Doxygen: the XML only; its own warnings (a malformed comment) fail the build too.
(cat docs/Doxyfile; echo "OUTPUT_DIRECTORY=$OUT/doxygen"; echo "WARN_LOGFILE=$OUT/doxygen/warnings.txt") | doxygen -
if [ -s "$OUT/doxygen/warnings.txt" ]; then
  cat "$OUT/doxygen/warnings.txt"
  echo "[docs] Doxygen warned about the headers' comments (above)" >&2
  exit 1
fi
t0=$(date +%s)
GPUGEOM_CLI="$PWD/$BUILD/tools/gpugeom/gpugeom" GPUGEOM_DOXYGEN_XML="$PWD/$OUT/doxygen/xml" \
  GPUGEOM_BACKEND=cpu "$PY" -m sphinx -W --keep-going -q -b html -d "$OUT/doctrees" docs "$OUT/html"
echo "[docs] built in $(( $(date +%s) - t0 )) s: open $OUT/html/index.html"
