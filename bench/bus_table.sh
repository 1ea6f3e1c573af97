#!/usr/bin/env bash
# The "results at bus speed" table (issue 18): every capability end to end (host arrays in and
# out), with its input already on the device (on_dev), and the bus floor of its bytes, with CuPy's
# EDT and Delaunay (host in / host out, and on the device) in the same run. Runs on the lent GPU
# machine from the repository root with .devbin/ carried (scripts/stage_gpu.sh); logs to $OUT.
set -u
export LD_LIBRARY_PATH=$PWD/.devbin/lib:${LD_LIBRARY_PATH:-}
OUT=${OUT:-/tmp/gg_out}
mkdir -p "$OUT"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee "$OUT/gpu.txt"
B=.devbin
{
  echo "== EDT float32 distances from a uint8 grid, 10 % sites"
  $B/gpugeom_bench_edt --backend cuda --sides 4096,8192 --density 0.1 --reps 3 --dist-only
  $B/gpugeom_bench_edt --backend cuda --dim 3 --sides 512 --density 0.1 --reps 3 --dist-only | tail -n +3
  python3 bench/anchor_edt.py --sides 4096,8192 --density 0.1 --tools cupy,cupy_host --reps 3
  python3 bench/anchor_edt.py --dim 3 --sides 512 --density 0.1 --tools cupy,cupy_host --reps 3
  echo "== 2D Delaunay, uniform"
  $B/gpugeom_bench_del2d --backend cuda --dists uniform --sizes 1e6,1e7 --reps 3 --voronoi
  $B/gpugeom_bench_del2d --backend cuda --dists uniform --sizes ${HUGE:-1e8} --reps 1 | tail -n +3
  python3 bench/anchor_del2d.py --gpugeom $B/gpugeom --dists uniform --sizes 1e6,1e7 --tools cupy,cupy_host
  echo "== 3D convex hull"
  $B/gpugeom_bench_hull3d --backend cuda --dists ball,sphere --sizes 1e6,1e7 --reps 3
  echo "== 3D Delaunay"
  $B/gpugeom_bench_del3d --reps 3 --cgal-max 0 uniform:1000000 sphere:1000000
  echo "== CVD (10 Lloyd iterations)"
  $B/gpugeom_bench_cvd --backend cuda --sides 4096 --sites 100000 --iters 10
  $B/gpugeom_bench_cvd --backend cuda --dim 3 --sides 256 --sites 100000 --iters 10 | tail -n +2
} 2>&1 | tee "$OUT/bus_table.txt"
