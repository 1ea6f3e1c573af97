#!/usr/bin/env bash
# Every capability's A/B in one run on the GPU machine (issue 48, part 7: "no capability more
# than 3 % slower"): the benchmark binaries of two or more builds alternated (A, B, A, B, ...)
# on the CUDA executor, so that drift and noise show as the spread between one build's passes.
# Each bench prints its end-to-end and device-resident columns as usual.
# Usage (repository root, .devbin/lib carried): bench/ab_all.sh DIR_A DIR_B [DIR_C ...];
# DIR_*: folders holding gpugeom_bench_{edt,cvd,del2d,cdt2d,hull3d,del3d,dynamic} (a missing
# one is skipped; gpugeom_bench_del3d needs libtbb.so.12 in .devbin/lib). scripts/stage_ab.sh
# stages and packs the builds with their libraries. PASSES (default 2); CAPS="edt del2d ..."
# runs only those capabilities.
set -u
OUT=${OUT:-/tmp/gg_out}
mkdir -p "$OUT"
export LD_LIBRARY_PATH=$PWD/.devbin/lib:${LD_LIBRARY_PATH:-}
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
CAPS=${CAPS:-edt cvd del2d voronoi2d cdt2d hull3d del3d dynamic}
run() {  # $1 capability, $2 dir: the capability's rows (the header once, first pass)
  local d=$2
  case $1 in
    edt)
      [ -x "$d/gpugeom_bench_edt" ] || return 0
      "$d/gpugeom_bench_edt" --backend cuda --sides 4096,16384 --density 0.001,0.1 --reps 5
      "$d/gpugeom_bench_edt" --backend cuda --dim 3 --sides 256,512 --density 0.1 --reps 3 | tail -n +3
      ;;
    cvd)
      [ -x "$d/gpugeom_bench_cvd" ] || return 0
      "$d/gpugeom_bench_cvd" --backend cuda --sides 4096 --sites 1000,100000 --iters 10
      "$d/gpugeom_bench_cvd" --backend cuda --dim 3 --sides 256 --sites 100000 --iters 5 | tail -n +3
      ;;
    del2d)
      [ -x "$d/gpugeom_bench_del2d" ] || return 0
      "$d/gpugeom_bench_del2d" --backend cuda --dists uniform,gaussian,circle,grid --sizes 1e5,1e6,1e7 --reps 7
      ;;
    voronoi2d)
      [ -x "$d/gpugeom_bench_del2d" ] || return 0
      "$d/gpugeom_bench_del2d" --backend cuda --dists uniform,grid --sizes 1e6 --reps 5 --voronoi
      ;;
    cdt2d)
      [ -x "$d/gpugeom_bench_cdt2d" ] || return 0
      "$d/gpugeom_bench_cdt2d" --backend cuda --inputs pslg:1e5,pslg:1e6,pslg:1e7 --reps 5
      ;;
    hull3d)
      [ -x "$d/gpugeom_bench_hull3d" ] || return 0
      "$d/gpugeom_bench_hull3d" --backend cuda --dists ball,sphere,thin_box --sizes 1e6,1e7 --reps 5
      ;;
    del3d)
      [ -x "$d/gpugeom_bench_del3d" ] || return 0
      "$d/gpugeom_bench_del3d" --reps 3 --cgal-max 0 uniform:100000 uniform:1000000 ball:1000000 \
        gaussian:1000000 thin_sphere:1000000 sphere:1000000 grid:1000000
      ;;
    dynamic)
      [ -x "$d/gpugeom_bench_dynamic" ] || return 0
      "$d/gpugeom_bench_dynamic" --backend cuda --reps 5 uniform:1000000:10000 uniform:1000000:100000 --3d \
        uniform:1000000:10000
      ;;
  esac
}
for cap in $CAPS; do
  for pass in $(seq 1 "${PASSES:-2}"); do
    for dir in "$@"; do
      echo "=== $cap: $(basename "$dir") pass $pass"
      run "$cap" "$dir" 2>&1 | grep -v "^# device"
    done
  done 2>&1 | tee -a "$OUT/ab_all.txt"
done
