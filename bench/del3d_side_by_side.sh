#!/usr/bin/env bash
# Runs on the lent GPU machine (repository root, .devbin/ carried): issue 46's rows of 3D
# Delaunay in one run, gpugeom (end to end and device-resident, phases, failed vertices, device
# bytes per point) beside gDel3D (the thesis authors' code, .devbin/gdel3d_bench_nocheck, copied
# from ../shared/anchors/) and CGAL (one core and all cores, through the bench, up to
# CGAL_MAX points). gDel3D draws its own points of each distribution (its own generator), so
# its rows are the same distribution and size, not the same points. Logs under $OUT; a short
# table last.
set -u
export LD_LIBRARY_PATH=$PWD/.devbin/lib:${LD_LIBRARY_PATH:-}
OUT=${OUT:-/tmp/gg_out}
mkdir -p "$OUT"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee "$OUT/gpu_del3d.txt"
REPS=${DEL3D_REPS:-3}
JOBS=${DEL3D_JOBS:-uniform:1000000 ball:1000000 gaussian:1000000 sphere:1000000 thin_sphere:1000000 grid:1000000 uniform:10000000}
CSV=${DEL3D_CSV:-$OUT/del3d.csv}
.devbin/gpugeom_bench_del3d --reps "$REPS" --cgal-max "${CGAL_MAX:-1e6}" --csv "$CSV" $JOBS 2>&1 | tee "$OUT/del3d_gpugeom.txt"
G=.devbin/gdel3d_bench_nocheck
: >"$OUT/del3d_gdel3d.txt"
if [ -x "$G" ]; then
  for j in $JOBS; do
    d=${j%%:*} n=${j##*:}
    case $d in thin_sphere) gd=thinsphere ;; uniform | ball | sphere | gaussian | grid) gd=$d ;; *) continue ;; esac
    # (gDel3D crashes at 10^7 uniform points: upstream's bug; its row is then missing)
    timeout 300 "$G" "$n" "$gd" "$REPS" 2>>"$OUT/del3d_gdel3d.err" | grep median_total_ms >>"$OUT/del3d_gdel3d.txt"
  done
fi
echo "== side by side (ms; gpugeom end to end, median of $REPS)"
GPU=$(cut -d, -f1 "$OUT/gpu_del3d.txt" | head -1)  # the name printed at the start
python3 - "$OUT/del3d_gpugeom.txt" "$OUT/del3d_gdel3d.txt" "$CSV" "$GPU" <<'PY'
import re, sys
ours = {}
for line in open(sys.argv[1]):
    f = line.split()
    if len(f) > 10 and f[2] == "cuda":
        ours[(f[0], int(float(f[1])))] = f
gd = {}
for line in open(sys.argv[2]):
    m = re.search(r"n=(\d+) dist=(\S+) median_total_ms=([\d.]+)", line)
    if m:
        gd[(m.group(2).replace("thinsphere", "thin_sphere"), int(m.group(1)))] = float(m.group(3))
# gDel3D's rows in the same CSV (its own median total, points already in its arrays)
with open(sys.argv[3], "a") as csv:
    for (d, n), ms in gd.items():
        csv.write(f"delaunay3d,{d},{n},gdel3d,{sys.argv[4]},0,{ms},0,{ms},{ms},0\n")
print(f"{'dist':12} {'n':>9} {'total':>9} {'on_dev':>8} {'ins+flip':>8} {'splay':>8} {'failed':>7} {'B/pt':>6} {'gDel3D':>9} {'gDel3D/us':>9} {'CGAL1':>8} {'CGALpar':>8}")
for (d, n), f in ours.items():
    g = gd.get((d, n))
    ratio = f"{g / float(f[3]):.2f}x" if g else "-"
    print(f"{d:12} {n:>9} {f[3]:>9} {f[4]:>8} {f[6]:>8} {f[7]:>8} {f[9]:>7} {f[12]:>6} {g if g else '-':>9} {ratio:>9} {f[13]:>8} {f[14]:>8}")
PY
