#!/usr/bin/env bash
# Quick start 1: install what is needed, build (CUDA when nvcc is present), run the demo job:
# generate a million points, summarise them, show the device, draw a stipple of a photograph
# (matplotlib's sample portrait of Grace Hopper), triangulate a terrain's contour lines (the
# Jacksboro fault DEM shipped with matplotlib; also with the lines as constraints) and a million
# points exactly, tetrahedralise
# a point cloud in a ball for ParaView, run the Python package's examples (installed with pip from
# this build), run the benchmarks small.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
BUILD=${BUILD_DIR:-build}
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DGPUGEOM_CUDA=${GPUGEOM_CUDA:-AUTO} \
  -DGPUGEOM_TESTS=OFF
# What the demo runs (no tests): the CLI, the Python package, the benchmark drivers and anchors.
cmake --build "$BUILD"
GPUGEOM_TESTS=OFF bash scripts/install_python.sh "$BUILD"
G="$BUILD/tools/gpugeom/gpugeom"
OUT=${DEMO_OUT:-$BUILD/demo}
mkdir -p "$OUT"
"$G" info --device
"$G" --verbose gen uniform3d -n 1000000 -o "$OUT/p.ply"
"$G" info "$OUT/p.ply"
"$G" gen thin_circle2d -n 100000 -o "$OUT/ring.npy"
"$G" info "$OUT/ring.npy"
python3 -c "import sys, numpy as n, matplotlib.image as m, matplotlib.cbook as c; \
a = m.imread(c.get_sample_data('grace_hopper.jpg', asfileobj=False)).astype(float); \
n.save(sys.argv[1], ((a[..., 0] * .299 + a[..., 1] * .587 + a[..., 2] * .114) / 255).astype(n.float32))" "$OUT/hopper.npy"
"$G" stipple "$OUT/hopper.npy" -n 20000 -o "$OUT/hopper_stipple.svg" --png "$OUT/hopper_stipple.png"
python3 bench/terrain_contours.py -n 1e4 --levels 6 -o "$OUT/contours.npy" --segments "$OUT/contour_edges.npy"
"$G" delaunay2d "$OUT/contours.npy" -o "$OUT/terrain_tin.ply" --check --draw "$OUT/terrain_tin.png"
# the contour lines as breaklines: every contour edge an edge of the terrain model
"$G" --verbose cdt2d "$OUT/contours.npy" --segments "$OUT/contour_edges.npy" -o "$OUT/terrain_cdt.vtu" \
  --check --draw "$OUT/terrain_cdt.png"
"$G" gen uniform2d -n 1000000 -o "$OUT/plane.npy"
"$G" --verbose delaunay2d "$OUT/plane.npy" -o "$OUT/plane_tri.npy" --check
"$G" gen ball3d -n 100000 -o "$OUT/ball.npy"
"$G" --verbose delaunay3d "$OUT/ball.npy" -o "$OUT/ball_tets.vtu" --check
echo "== the Python package's examples (pictures in $OUT)"
for ex in terrain_voronoi terrain_breaklines edt_labels stipple_photo hull_scan; do
  python3 python/examples/$ex.py -o "$OUT/py_$ex.png"
done
bash bench/run_bench.sh --quick --build "$BUILD" --out "$OUT/bench"
