#!/usr/bin/env bash
# A/B timing on the lent GPU machine: the benchmark binaries of two or more builds side by side
# in one run, alternated (A, B, A, B) so drift and noise show as the spread between the two
# passes of one build. Usage (repository root, .devbin/ carried): bench/ab_runs.sh DIR_A DIR_B
# [DIR_C ...]; DIR_*: folders holding gpugeom_bench_del2d, gpugeom_bench_hull3d and optionally
# gpugeom_bench_del3d and gpugeom_bench_edt.
set -u
OUT=${OUT:-/tmp/gg_out}
mkdir -p "$OUT"
export LD_LIBRARY_PATH=$PWD/.devbin/lib:${LD_LIBRARY_PATH:-}
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
one() {  # $1 label, $2 dir
  echo "=== $1 ($2)"
  "$2/gpugeom_bench_del2d" --backend cuda --dists uniform,grid --sizes ${AB_DEL2D:-1e6,1e7} --reps 5 |
    grep -E "^(uniform|grid)"
  "$2/gpugeom_bench_hull3d" --backend cuda --dists ball,sphere --sizes ${AB_HULL:-1e6,1e7} --reps 5 |
    grep -E "^(ball|sphere)"
  if [ -x "$2/gpugeom_bench_del3d" ]; then
    "$2/gpugeom_bench_del3d" --reps 3 ${AB_DEL3D:-uniform:1000000 sphere:1000000} |
      grep -E "^(uniform|sphere|ball|gaussian|thin_sphere)"
  fi
  [ -x "$2/gpugeom_bench_edt" ] || return 0  # EDT left out of this comparison
  "$2/gpugeom_bench_edt" --backend cuda --sides ${AB_EDT:-4096,8192} --density 0.1 --reps 5 |
    grep -E "^edt "
}
for pass in 1 2; do
  for dir in "$@"; do one "$(basename "$dir") pass $pass" "$dir" 2>&1 | tee -a "$OUT/ab.txt"; done
done
