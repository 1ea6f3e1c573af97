#!/usr/bin/env bash
# Developer helper for the lent multi-GPU machine: the gpugeom.dask tests with the blocks on the
# GPU, then bench/dask_delaunay.py and bench/dask_edt.py on 1 and 2 (or more) GPUs, one Dask
# worker per GPU; the GPU test binaries carried in .devbin (test_*_cuda) first, where there are.
# Expects what scripts/stage_gpu.sh carried (.devbin/py, .devbin/lib) and Dask's wheels in
# .devbin/wheels (pip download "dask[array]" distributed for the machine's Python).
# Results go to $OUT (or ./dask-results): the tests' summary, the bench's lines and CSV.
set -uo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-dask-results}
mkdir -p "$OUT"
[ -d .devbin ] && (cd .devbin && gunzip -f ./*.gz py/gpugeom/*.gz 2>/dev/null || true)
python3 -m pip install -q --no-deps --target /tmp/gg_wheels .devbin/wheels/*.whl >/dev/null 2>&1
export LD_LIBRARY_PATH=$PWD/.devbin/lib:${LD_LIBRARY_PATH:-}
export PYTHONPATH=$PWD/.devbin/py:/tmp/gg_wheels
nvidia-smi --query-gpu=name,memory.total --format=csv,noheader | tee "$OUT/gpus.txt"
python3 -c "import gpugeom, cupy; print(gpugeom.device_info())" | tee -a "$OUT/gpus.txt"
# CuPy compiles its kernels on first use (about a minute; cached on disk after): once, here.
# (WARMUP=0 skips it: the EDT needs no CuPy kernel)
[ "${WARMUP:-1}" = 0 ] || timeout 200 python3 -c "
import numpy as np, dask, gpugeom.dask as gd
with dask.config.set(scheduler='sync'):
    for d in (2, 3):
        gd.delaunay(np.random.default_rng(d).random((20000, d)), blocks=4).gather()
print('CuPy kernels compiled')" 2>&1 | tail -3 | tee "$OUT/warmup.txt"
for t in .devbin/test_*_cuda; do
  [ -x "$t" ] || continue
  "$t" --gtest_brief=1 >"$OUT/$(basename "$t").log" 2>&1
  echo "$(basename "$t"): rc=$? $(grep -E '^\[  (PASSED|FAILED)' "$OUT/$(basename "$t").log" | tr '\n' ' ')" |
    tee -a "$OUT/tests.txt"
  # SANITIZE: a gtest filter to run under compute-sanitizer's memcheck (none: skip)
  if [ -n "${SANITIZE:-}" ]; then
    CS=$(command -v compute-sanitizer || echo /usr/local/cuda/bin/compute-sanitizer)
    GG_UNDER_SANITIZER=1 timeout 300 "$CS" --tool memcheck --leak-check full \
      --error-exitcode 9 "$t" --gtest_brief=1 --gtest_filter="$SANITIZE" >"$OUT/memcheck.log" 2>&1
    echo "memcheck $(basename "$t") $SANITIZE: rc=$? $(grep 'ERROR SUMMARY' "$OUT/memcheck.log" | tail -1)" |
      tee -a "$OUT/tests.txt"
  fi
done
[ "${TEST_S:-150}" = 0 ] || timeout "${TEST_S:-150}" python3 -m pytest -q -p no:cacheprovider -x \
  ${PYTESTS:-python/tests/test_dask.py python/tests/test_dask_edt.py} 2>&1 | grep -v "^INFO\|^WARNING" | tail -15 |
  tee "$OUT/tests.txt"
# CPU_CORES: core counts for laptop-sized runs of CPU workers (e.g. "4 8"): on the first N cores
# (taskset; the workers share them), the single CPU run on all N against 4 workers; CPU_JOBS:
# "dims n dists" jobs separated by ';'; CPU_BPW: blocks per worker
IFS=';' read -ra cpu_jobs <<<"${CPU_JOBS:-2 1e6 uniform;2 4e6 uniform;3 1e6 uniform}"
for c in ${CPU_CORES:-}; do
  for job in "${cpu_jobs[@]}"; do
    set -- $job
    timeout "${BENCH_S:-180}" taskset -c "0-$((c - 1))" python3 bench/dask_delaunay.py --cpu \
      --gpus 4 --blocks-per-worker "${CPU_BPW:-2}" --dims "$1" --n "$2" --dist "$3" --check \
      --tasks --csv "$OUT/dask_delaunay_cpu.csv" 2>&1 |
      grep -v "^INFO\|^WARNING\|UserWarn\|warnings.warn\|next(self\|distributed\." | tee -a "$OUT/bench.txt"
  done
done
GPUS=${GPUS:-1,2}
# JOBS: "dims n dists" jobs separated by ';'; BENCH_ARGS: more arguments (e.g. --tasks)
IFS=';' read -ra jobs <<<"${JOBS:-3 1e7 uniform;2 5e7 uniform;3 1e7 clustered}"
for job in "${jobs[@]}"; do
  [ "$job" = none ] && continue
  set -- $job
  timeout "${BENCH_S:-180}" python3 bench/dask_delaunay.py --gpus "$GPUS" --dims "$1" --n "$2" \
    --dist "$3" --csv "$OUT/dask_delaunay.csv" ${BENCH_ARGS:-} 2>&1 | grep -v "^INFO\|^WARNING\|UserWarn\|warnings.warn\|next(self" |
    tee -a "$OUT/bench.txt"
done
# EDT_N: the edges of the cubes for bench/dask_edt.py (none: skip)
if [ "${EDT_N:-1024,2048}" != none ]; then
  timeout "${EDT_S:-300}" python3 bench/dask_edt.py --gpus "$GPUS" --n "${EDT_N:-1024,2048}" \
    --csv "$OUT/dask_edt.csv" ${EDT_ARGS:-} 2>&1 | grep -v "^INFO\|^WARNING\|UserWarn\|warnings.warn\|distributed\." |
    tee -a "$OUT/bench.txt"
fi
