#!/usr/bin/env bash
# The CPU executor's scaling table (issue 53): 3D Delaunay, 2D Delaunay and the 3D hull at SIZE
# points on 1, 2, 4, ... threads up to the host's cores, with the anchors in the same run: CGAL on
# one core at every count (its spread says how steady the host was), CGAL's parallel 3D Delaunay
# on the same thread count (TBB limited to OMP_NUM_THREADS by the bench), and once, where Python
# has them, Triangle and SciPy's Qhull (2D) and Qhull (the hull), one core each. Prints one table
# (ms, end to end from host arrays); every bench's own rows stay in OUT_DIR.
# Usage: bench/cpu_scaling.sh BIN_DIR [SIZE] [OUT_DIR]
#   BIN_DIR: gpugeom_bench_del3d, gpugeom_bench_del2d, gpugeom_bench_hull3d and (for the Python
#   anchors' points) the gpugeom CLI. SIZE: 1e6 by default.
set -euo pipefail
BIN=$1 N=${2:-1e6} O=${3:-$(mktemp -d)}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$O/hull_points"
CORES=$(nproc)
THREADS="" T=1
while [ "$T" -lt "$CORES" ]; do THREADS="$THREADS $T" T=$((T * 2)); done
THREADS="$THREADS $CORES"
echo "# host: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $CORES cores; $N points"
for t in $THREADS; do
  export OMP_NUM_THREADS=$t
  "$BIN/gpugeom_bench_del3d" --reps 1 --cgal-max "$N" "uniform:$N" >"$O/del3d_$t.txt"
  "$BIN/gpugeom_bench_del2d" --backend cpu --dists uniform --sizes "$N" --reps 1 --cgal \
    >"$O/del2d_$t.txt"
  "$BIN/gpugeom_bench_hull3d" --backend cpu --dists ball,sphere --sizes "$N" --reps 1 \
    --cgal "$N" --save "$O/hull_points" >"$O/hull3d_$t.txt"
done
unset OMP_NUM_THREADS
# The one-core anchors from Python, on the same points (where the packages are installed).
if [ -x "$BIN/gpugeom" ]; then
  python3 "$HERE/anchor_del2d.py" --gpugeom "$BIN/gpugeom" --dists uniform --sizes "$N" \
    --tools triangle,scipy-qhull >"$O/anchor_del2d.txt" 2>&1 || true
fi
python3 "$HERE/anchor_hull3d.py" --dir "$O/hull_points" --reps 1 >"$O/anchor_hull3d.txt" 2>&1 || true

row() { awk -v d="$1" -v c="$2" '$1 == d && $3 == "cpu" { print $c; exit }' "$3"; }
printf "%-8s %10s %10s %10s %10s %10s %10s\n" threads 3D CGAL-par 2D hull-ball hull-sph CGAL-3D-1
for t in $THREADS; do
  printf "%-8s %10s %10s %10s %10s %10s %10s\n" "$t" \
    "$(row uniform 4 "$O/del3d_$t.txt")" "$(row uniform 15 "$O/del3d_$t.txt")" \
    "$(row uniform 4 "$O/del2d_$t.txt")" "$(row ball 4 "$O/hull3d_$t.txt")" \
    "$(row sphere 4 "$O/hull3d_$t.txt")" "$(row uniform 14 "$O/del3d_$t.txt")"
done
echo "# one core: CGAL 2D $(row uniform 12 "$O/del2d_1.txt"), CGAL hull ball" \
  "$(row ball 11 "$O/hull3d_1.txt"), sphere $(row sphere 11 "$O/hull3d_1.txt") ms"
grep -hE "^(uniform|ball|sphere|note)" "$O/anchor_del2d.txt" "$O/anchor_hull3d.txt" 2>/dev/null |
  sed 's/^/# /' || true
