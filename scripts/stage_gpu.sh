#!/usr/bin/env bash
# Developer helper: copy the CUDA build's test and bench binaries, and the shared libraries they
# need beyond a bare CUDA image, into .devbin/ (git-ignored) to carry to the lent GPU machine.
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build-cuda}
rm -rf .devbin && mkdir -p .devbin/lib
cp "$B"/tests/test_*_cuda "$B"/bench/gpugeom_bench "$B"/bench/gpugeom_bench_edt "$B"/bench/gpugeom_bench_cvd "$B"/bench/gpugeom_bench_del2d "$B"/bench/gpugeom_bench_hull3d "$B"/bench/gpugeom_bench_del3d "$B"/tools/gpugeom/gpugeom .devbin/
[ -x "$B/bench/anchor_cgal" ] && cp "$B/bench/anchor_cgal" .devbin/
# The carry limit is 64 MiB: EXCLUDE="gpugeom_bench_cvd gpugeom" leaves out what a run needs not.
for x in ${EXCLUDE:-}; do rm -f ".devbin/$x"; done
for f in .devbin/*; do
  [ -f "$f" ] || continue
  ldd "$f" | awk '/=> \//{print $3}' | grep -E 'libcudart|libgomp|libpng|libgmp|libmpfr|libz\.|libtbb' | xargs -r -I{} cp -L {} .devbin/lib/
done
# A CTest file, so that the GPU machine can run 'ctest --test-dir .devbin -L gpu'.
{
  for t in .devbin/test_*_cuda; do
    n=$(basename "$t")
    echo "add_test($n \"\${CMAKE_CURRENT_LIST_DIR}/$n\")"
    echo "set_tests_properties($n PROPERTIES LABELS gpu SKIP_RETURN_CODE 77)"
  done
} >.devbin/CTestTestfile.cmake
du -sh .devbin
