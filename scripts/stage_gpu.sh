#!/usr/bin/env bash
# Developer helper: copy the CUDA build's test and bench binaries, and the shared libraries they
# need beyond a bare CUDA image, into .devbin/ (git-ignored) to carry to the lent GPU machine.
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build-cuda}
rm -rf .devbin && mkdir -p .devbin/lib
# PYBUILD: a build of the Python package for the GPU machine's interpreter (3.12 there, e.g.
# cmake -B build-py312 -DPython_EXECUTABLE=python3.12 -DGPUGEOM_STATIC_CUDART=ON
# -DGPUGEOM_PYTHON_STUBS=OFF): copied to .devbin/py/gpugeom, stripped. ONLY_PY=1: nothing else.
if [ -n "${PYBUILD:-}" ]; then
  mkdir -p .devbin/py && cp -r "$PYBUILD/python/gpugeom" .devbin/py/
  strip --strip-unneeded .devbin/py/gpugeom/_core*.so
  ldd .devbin/py/gpugeom/_core*.so | awk '/=> \//{print $3}' | grep -E 'libgomp|libpng|libz\.' |
    xargs -r -I{} cp -L {} .devbin/lib/
fi
if [ "${ONLY_PY:-0}" = 1 ]; then du -sh .devbin; exit 0; fi
cp "$B"/tests/test_*_cuda "$B"/bench/gpugeom_bench "$B"/bench/gpugeom_bench_edt "$B"/bench/gpugeom_bench_cvd "$B"/bench/gpugeom_bench_del2d "$B"/bench/gpugeom_bench_cdt2d "$B"/bench/gpugeom_bench_hull3d "$B"/bench/gpugeom_bench_del3d "$B"/bench/gpugeom_bench_dynamic "$B"/tools/gpugeom/gpugeom .devbin/
[ -x "$B/bench/anchor_cgal" ] && cp "$B/bench/anchor_cgal" .devbin/
# The carry limit is 64 MiB (every binary together is about 200 MB): EXCLUDE="gpugeom_bench_cvd
# gpugeom" leaves out what a run needs not; ONLY="delaunay3d del3d" keeps only the binaries whose
# names contain one of the words (e.g. one capability's test and bench).
for x in ${EXCLUDE:-}; do rm -f ".devbin/$x"; done
if [ -n "${ONLY:-}" ]; then
  for f in .devbin/*; do
    [ -f "$f" ] || continue
    case "$f" in *.cmake) continue ;; esac
    keep=0
    for w in $ONLY; do case "$(basename "$f")" in *"$w"*) keep=1 ;; esac; done
    [ $keep = 1 ] || rm -f "$f"
  done
fi
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
