#!/usr/bin/env bash
# Developer helper for the lent multi-GPU machine: the gpugeom.dask tests with the blocks on the
# GPU, then bench/dask_delaunay.py on 1 and 2 (or more) GPUs, one Dask worker per GPU.
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
timeout 200 python3 -c "
import numpy as np, dask, gpugeom.dask as gd
with dask.config.set(scheduler='sync'):
    for d in (2, 3):
        gd.delaunay(np.random.default_rng(d).random((20000, d)), blocks=4).gather()
print('CuPy kernels compiled')" 2>&1 | tail -3 | tee "$OUT/warmup.txt"
[ "${TEST_S:-150}" = 0 ] || timeout "${TEST_S:-150}" python3 -m pytest -q -p no:cacheprovider -x \
  python/tests/test_dask.py 2>&1 | grep -v "^INFO\|^WARNING" | tail -15 |
  tee "$OUT/tests.txt"
GPUS=${GPUS:-1,2}
# JOBS: "dims n dists" jobs separated by ';'
IFS=';' read -ra jobs <<<"${JOBS:-3 1e7 uniform;2 5e7 uniform;3 1e7 clustered}"
for job in "${jobs[@]}"; do
  set -- $job
  timeout "${BENCH_S:-180}" python3 bench/dask_delaunay.py --gpus "$GPUS" --dims "$1" --n "$2" \
    --dist "$3" --csv "$OUT/dask_delaunay.csv" 2>&1 | grep -v "^INFO\|^WARNING\|UserWarn\|warnings.warn\|next(self" |
    tee -a "$OUT/bench.txt"
done
