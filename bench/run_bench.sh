#!/usr/bin/env bash
# One invocation: gpugeom's problems on every usable backend, then the CPU anchors (CGAL,
# SciPy/Qhull) on the same generated points; CSV, a table and plots under --out.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=build OUT=bench_out QUICK=0
while [ $# -gt 0 ]; do
  case "$1" in
    --build) BUILD=$2; shift 2 ;;
    --out) OUT=$2; shift 2 ;;
    --quick) QUICK=1; shift ;;
    *) echo "usage: run_bench.sh [--build DIR] [--out DIR] [--quick]"; exit 2 ;;
  esac
done
mkdir -p "$OUT"
CSV="$OUT/bench.csv"
rm -f "$CSV"
B="$BUILD/bench/gpugeom_bench"
G="$BUILD/tools/gpugeom/gpugeom"
if [ "$QUICK" = 1 ]; then SIZES=100000,1000000; ASIZES=100000; else SIZES=1000000,10000000; ASIZES=1000000; fi
echo "== gpugeom ($("$G" info --device | grep -E '^device' | sed 's/device: *//'))"
"$B" --problem hilbert --dist uniform,grid --sizes $SIZES --csv "$CSV"
"$B" --problem hilbert --dim 2 --dist uniform --sizes $SIZES --csv "$CSV"
"$B" --problem orient3d --dist uniform,sphere,grid --sizes $SIZES --csv "$CSV"
"$B" --problem insphere --dist uniform,sphere,grid --sizes $SIZES --csv "$CSV"
echo "== distance transform"
if [ "$QUICK" = 1 ]; then ESIDES=1024,2048; else ESIDES=2048,4096,8192; fi
"$BUILD/bench/gpugeom_bench_edt" --sides $ESIDES --density 0.001,0.1,0.5 --reps 3 --csv "$CSV"
python3 bench/anchor_edt.py --sides $ESIDES --density 0.1 --tools cupy,scipy,opencv,edt --csv "$CSV" || true
echo "== centroidal Voronoi diagram (time per Lloyd iteration)"
if [ "$QUICK" = 1 ]; then CSIDES=1024; CSITES=1000,100000; else CSIDES=1024,4096,8192; CSITES=1000,100000,1000000; fi
"$BUILD/bench/gpugeom_bench_cvd" --sides $CSIDES --sites $CSITES --iters 5 --csv "$CSV"
echo "== 2D Delaunay (end to end and on the device; CGAL in the same process, then Triangle)"
if [ "$QUICK" = 1 ]; then DSIZES=100000,1000000; else DSIZES=1000000,10000000; fi
"$BUILD/bench/gpugeom_bench_del2d" --dists uniform,thin_circle,circle,grid --sizes $DSIZES --reps 3 --cgal --csv "$CSV"
python3 bench/anchor_del2d.py --gpugeom "$G" --dists uniform,circle,grid --sizes $ASIZES --tools triangle --csv "$CSV" || true
echo "== 3D convex hull (end to end and on the device; CGAL in the same process, then Qhull)"
HD=$(mktemp -d)
"$BUILD/bench/gpugeom_bench_hull3d" --dists ball,uniform,thin_box,thin_sphere,sphere --sizes $DSIZES --reps 3 --cgal $ASIZES --save "$HD" --csv "$CSV"
python3 bench/anchor_hull3d.py --dir "$HD" --max-n $ASIZES --csv "$CSV" || true
rm -rf "$HD"
echo "== anchors (CPU, one core)"
if [ -x "$BUILD/bench/anchor_cgal" ]; then
  "$BUILD/bench/anchor_cgal" --problem delaunay2d --dist uniform --sizes $ASIZES --csv "$CSV"
  "$BUILD/bench/anchor_cgal" --problem delaunay3d --dist uniform --sizes $ASIZES --csv "$CSV"
  "$BUILD/bench/anchor_cgal" --problem hull3d --dist ball --sizes $ASIZES --csv "$CSV"
else
  echo "note: CGAL anchor not built (libcgal-dev missing)"
fi
python3 bench/anchor_scipy.py --gpugeom "$G" --problem delaunay2d --dist uniform --sizes $ASIZES --csv "$CSV" || true
python3 bench/anchor_scipy.py --gpugeom "$G" --problem hull3d --dist ball --sizes $ASIZES --csv "$CSV" || true
python3 bench/plot.py "$CSV" "$OUT/plots" || true
echo "== CSV: $CSV"
column -s, -t < "$CSV" | cut -c1-150
