#!/usr/bin/env bash
# End-to-end checks of the gpugeom command-line program: what a user types, and its errors.
set -u
G="$1"
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
fail=0
expect() {  # expect RC PATTERN -- command...
  local rc=$1 pat=$2
  shift 3
  local out
  out=$("$@" 2>&1)
  local got=$?
  if [ "$got" != "$rc" ] || ! grep -qE -- "$pat" <<<"$out"; then
    echo "FAIL: $* -> rc $got (want $rc), output:"; echo "$out" | head -5; fail=1
  else
    echo "ok: $*"
  fi
}
expect 0 "wrote 1000000 uniform3d" -- "$G" gen uniform3d -n 1000000 -o "$W/p.ply"
expect 0 "1000000 vertices, 3D" -- "$G" info "$W/p.ply"
expect 0 "wrote 2000 circle2d" -- "$G" gen circle2d -n 2e3 -o "$W/c.csv"
expect 0 "2000 points, 2D" -- "$G" info "$W/c.csv"
expect 0 "auto:" -- "$G" info --device
expect 0 "usage: gpugeom gen" -- "$G" gen --help
expect 0 "usage: gpugeom check" -- "$G" check --help
expect 0 "usage: gpugeom info" -- "$G" info --help
expect 0 "commands:" -- "$G" --help
expect 2 "unknown command" -- "$G" frobnicate
expect 2 "unknown distribution" -- "$G" gen cube3d -n 10 -o "$W/x.ply"
expect 2 "missing -n" -- "$G" gen uniform3d -o "$W/x.ply"
expect 2 "unknown option" -- "$G" gen uniform3d -n 5 -o "$W/x.ply" --bogus
expect 2 "unknown backend" -- "$G" --backend tpu info --device
printf 'ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nend_header\n1 2\n3 x\n' >"$W/bad.ply"
expect 3 "bad.ply:8: expected a number" -- "$G" info "$W/bad.ply"
expect 3 "cannot open" -- "$G" info "$W/missing.xyz"
expect 2 "unknown point format|unknown mesh format" -- "$G" info "$W/file.abc"
# check: a hand-made valid 2D Delaunay triangulation and a broken one
printf '4 2 0 0\n0 0 0\n1 1 0\n2 0 1\n3 1.2 1.1\n' >"$W/q.node"
printf '2 3 0\n0 0 1 2\n1 1 3 2\n' >"$W/q.ele"
expect 0 "valid delaunay2d" -- "$G" check "$W/q.ele"
printf '2 3 0\n0 0 1 3\n1 0 3 2\n' >"$W/bad.ele"
cp "$W/q.node" "$W/bad.node"
expect 1 "not locally Delaunay" -- "$G" check "$W/bad.ele"
# edt: a small image, its outputs, and its errors
printf 'P2\n5 3\n255\n0 0 0 0 0\n0 0 255 0 0\n0 0 0 0 0\n' >"$W/one.pgm"
expect 0 "15 voxels on cpu, exact" -- "$G" edt "$W/one.pgm" -o "$W/d.npy" --labels "$W/l.npy" --preview "$W/p.png" --voronoi
[ -s "$W/d.npy" ] && [ -s "$W/l.npy" ] && [ -s "$W/p.png" ] || { echo "FAIL: edt outputs missing"; fail=1; }
expect 0 "usage: gpugeom edt" -- "$G" edt --help
expect 0 "JFA \(approximate\)" -- "$G" edt "$W/one.pgm" -o "$W/j.npy" --sites zero --sampling 1,2 --method jfa
expect 2 "slices apply to grids of 3 or more axes" -- "$G" edt "$W/one.pgm" -o "$W/z.npy" --slices 0
printf 'P2\n2 2\n255\n0 0\n0 0\n' >"$W/none.pgm"
expect 3 "has no site" -- "$G" edt "$W/none.pgm" -o "$W/z.npy"
[ -e "$W/z.npy" ] && { echo "FAIL: a failed edt left an output file"; fail=1; }
expect 2 "sampling needs one value per axis" -- "$G" edt "$W/one.pgm" -o "$W/z.npy" --sampling 1,2,3
expect 2 "raw input needs --shape and --dtype" -- "$G" edt "$W/vol.raw" -o "$W/z.npy"
expect 2 "outputs are .npy files" -- "$G" edt "$W/one.pgm" -o "$W/z.png"
# cvd and stipple: a 40 x 30 gradient (dark on the left), its outputs, and their errors
{ printf 'P2\n40 30\n255\n'; for y in $(seq 30); do for x in $(seq 40); do printf '%d ' $((x * 6)); done; echo; done; } >"$W/grad.pgm"
expect 0 "stipple .*: 300 dots" -- "$G" stipple "$W/grad.pgm" -n 300 -o "$W/s.svg" --png "$W/s.png"
[ "$(grep -c '<circle' "$W/s.svg")" = 300 ] && [ -s "$W/s.png" ] || { echo "FAIL: stipple outputs"; fail=1; }
# the dots crowd where the image is dark: more of them in the left half than in the right
left=$(grep -o 'cx="[0-9.]*"' "$W/s.svg" | tr -dc '0-9.\n' | awk '$1 < 20' | wc -l)
[ "$left" -gt 200 ] || { echo "FAIL: stipple dots not denser where dark ($left of 300 left)"; fail=1; }
expect 0 "cvd .*: 50 sites" -- "$G" cvd "$W/grad.pgm" -n 50 -o "$W/c.xyz" --mass "$W/m.npy" --energy "$W/e.csv" --preview "$W/v.png"
[ "$(wc -l <"$W/c.xyz")" = 50 ] && [ -s "$W/m.npy" ] && [ -s "$W/v.png" ] || { echo "FAIL: cvd outputs"; fail=1; }
expect 0 "cvd .*: 50 sites" -- "$G" cvd "$W/grad.pgm" --initial "$W/c.xyz" -o "$W/c2.npy" --iterations 3
expect 0 "usage: gpugeom cvd" -- "$G" cvd --help
expect 0 "usage: gpugeom stipple" -- "$G" stipple --help
expect 3 "positive at only" -- "$G" cvd "$W/grad.pgm" -n 5000 -o "$W/z.xyz"
expect 3 "zero everywhere" -- "$G" cvd "$W/none.pgm" -n 5 -o "$W/z.xyz"
[ -e "$W/z.xyz" ] && { echo "FAIL: a failed cvd left an output file"; fail=1; }
expect 2 "give -o OUT.svg" -- "$G" stipple "$W/grad.pgm" -o "$W/s.pdf"
expect 2 "supersample must be in 1..64" -- "$G" cvd "$W/grad.pgm" -n 5 -o "$W/z.xyz" --supersample 0
expect 2 "either -n N or --initial" -- "$G" cvd "$W/grad.pgm" -o "$W/z.xyz"
# delaunay2d: outputs in each mesh format, the checker, Voronoi JSON, drawings, errors
expect 0 "wrote 3000 grid2d" -- "$G" gen grid2d -n 3000 -o "$W/g.npy"
expect 0 "check: valid Delaunay" -- "$G" delaunay2d "$W/g.npy" -o "$W/g.ply" --check
expect 0 "valid delaunay2d" -- "$G" check "$W/g.ply"
for ext in off obj ele vtu npy; do
  expect 0 "2000 points -> 1998 triangles" -- "$G" delaunay2d "$W/c.csv" -o "$W/t.$ext"
  [ -s "$W/t.$ext" ] || { echo "FAIL: delaunay2d wrote no .$ext"; fail=1; }
done
expect 0 "valid delaunay2d" -- "$G" check "$W/t.ele"
# VTU: binary by default, zlib with --compress, text with --ascii; each checks valid
expect 0 "valid delaunay2d" -- "$G" check "$W/t.vtu"
grep -q 'format="appended"' "$W/t.vtu" || { echo "FAIL: .vtu is not binary by default"; fail=1; }
expect 0 "2000 points -> 1998 triangles" -- "$G" delaunay2d "$W/c.csv" -o "$W/z.vtu" --compress
grep -q 'vtkZLibDataCompressor' "$W/z.vtu" || { echo "FAIL: --compress wrote no zlib"; fail=1; }
expect 0 "valid delaunay2d" -- "$G" check "$W/z.vtu"
expect 0 "2000 points -> 1998 triangles" -- "$G" delaunay2d "$W/c.csv" -o "$W/a.vtu" --ascii
grep -q 'format="ascii"' "$W/a.vtu" || { echo "FAIL: --ascii wrote no text"; fail=1; }
for f in t z a; do  # the duplicate map rides along as point data, and check still reads it
  grep -aq '<PointData>' "$W/$f.vtu" && grep -aq 'Name="duplicate_of"' "$W/$f.vtu" ||
    { echo "FAIL: $f.vtu has no duplicate_of point data"; fail=1; }
done
expect 0 "valid delaunay2d" -- "$G" check "$W/a.vtu"
expect 2 "--compress applies to -o FILE.vtu" -- "$G" delaunay2d "$W/c.csv" -o "$W/z.ply" --compress
expect 0 "2000 points -> " -- "$G" delaunay2d "$W/c.csv" --voronoi "$W/v.json" --clip -1,-1,2,2 --draw "$W/t.svg"
python3 - "$W/v.json" <<'PY' || { echo "FAIL: Voronoi JSON"; fail=1; }
import json, sys
v = json.load(open(sys.argv[1]))
assert len(v["regions"]) == 2000 and len(v["clipped"]) == 2000
assert all(len(c) >= 3 for c in v["clipped"])
assert len(v["ridge_points"]) == len(v["ridge_vertices"])
PY
grep -q "<polygon" "$W/t.svg" || { echo "FAIL: delaunay2d drawing has no Voronoi cells"; fail=1; }
expect 0 "2000 points -> " -- "$G" delaunay2d "$W/c.csv" --draw "$W/t.png"
[ -s "$W/t.png" ] || { echo "FAIL: delaunay2d PNG"; fail=1; }
printf '0 0\n1 1\n2 2\n3 3\n' >"$W/line.xyz"
expect 3 "one line" -- "$G" delaunay2d "$W/line.xyz" -o "$W/l.ply"
printf '0 0\n1 0\nnan 1\n' >"$W/nan.xyz"
expect 3 "NaN" -- "$G" delaunay2d "$W/nan.xyz" -o "$W/l.ply"
[ -e "$W/l.ply" ] && { echo "FAIL: a failed delaunay2d left an output file"; fail=1; }
printf '0 0 0\n1 0 1\n0 1 0\n' >"$W/p3.xyz"
expect 3 "3D points" -- "$G" delaunay2d "$W/p3.xyz" -o "$W/l.ply"
expect 2 "nothing to do" -- "$G" delaunay2d "$W/c.csv"
expect 2 "writes .svg or .png" -- "$G" delaunay2d "$W/c.csv" --draw "$W/t.pdf"
expect 0 "usage: gpugeom delaunay2d" -- "$G" delaunay2d --help
# cdt2d: Triangle's .poly (an L with a square hole, a divider and two regions), its outside
# removed or kept, areas of what is written, the checker, a point file with .npy segments, errors
cat >"$W/l.poly" <<'POLY'
# an L (area 75, hull 87.5) with a 2x2 hole at (3, 2)
12 2 0 1
1 0 0
2 10 0
3 10 5
4 5 5
5 5 10
6 0 10
7 2 1
8 4 1
9 4 3
10 2 3
11 5 0
12 1 8
12 1
1 1 11 1
2 11 2 1
3 2 3 1
4 3 4 1
5 4 5 1
6 5 6 1
7 6 1 1
8 7 8 0
9 8 9 0
10 9 10 0
11 10 7 0
12 11 4 0
1
1 3 2
2
1 1 8 7.0 -1
2 8 2 9.0 -1
POLY
expect 0 "check: valid constrained Delaunay" -- "$G" cdt2d "$W/l.poly" -o "$W/l.ele" --check
expect 0 "removed" -- "$G" cdt2d "$W/l.poly" -o "$W/lh.ele" --hull
expect 0 "12 segments" -- "$G" cdt2d "$W/l.poly" -o "$W/l.vtu"
python3 - "$W" <<'PY' || { echo "FAIL: cdt2d areas"; fail=1; }
import sys
w = sys.argv[1]
def area(stem):
    node = [l.split() for l in open(f"{w}/{stem}.node") if l.strip() and not l.startswith("#")]
    ele = [l.split() for l in open(f"{w}/{stem}.ele") if l.strip() and not l.startswith("#")]
    base = int(node[1][0])
    p = {int(r[0]): (float(r[1]), float(r[2])) for r in node[1:]}
    a = 0.0
    for r in ele[1:]:
        (x0, y0), (x1, y1), (x2, y2) = (p[int(v)] for v in r[1:4])
        a += ((x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0)) / 2
    return a
assert area("l") == 71.0, area("l")
assert area("lh") == 83.5, area("lh")
PY
grep -q 'Name="attribute"' "$W/l.vtu" || { echo "FAIL: cdt2d .vtu has no attribute cell data"; fail=1; }
expect 0 "12 segments" -- "$G" cdt2d "$W/l.poly" --draw "$W/l.svg"
grep -q 'stroke="#15c"' "$W/l.svg" || { echo "FAIL: cdt2d drawing has no segments"; fail=1; }
# mesh2d: the same domain refined (Triangle's -q and -a), checked, written as Triangle writes.
expect 0 "check: valid quality mesh" -- "$G" mesh2d "$W/l.poly" -q 30 -a 0.5 -o "$W/m.ele" --check
[ -s "$W/m.node" ] || { echo "FAIL: mesh2d wrote no .node beside the .ele"; fail=1; }
expect 0 "smallest angles" -- "$G" mesh2d "$W/l.poly" -q 25 -o "$W/m.vtu" --draw "$W/m.svg"
expect 0 "smallest angles" -- "$G" mesh2d "$W/l.poly" -q 30 -o "$W/m.msh"
grep -q '^\$Elements' "$W/m.msh" || { echo "FAIL: mesh2d .msh has no elements"; fail=1; }
expect 2 "33.8" -- "$G" mesh2d "$W/l.poly" -q 40 -o "$W/refused.ele"
[ ! -e "$W/refused.ele" ] || { echo "FAIL: a refused mesh2d wrote its output"; fail=1; }
expect 0 "usage: gpugeom mesh2d" -- "$G" mesh2d --help
expect 0 "12 segments" -- "$G" cdt2d "$W/l.poly" --draw "$W/l.png"
[ -s "$W/l.png" ] || { echo "FAIL: cdt2d PNG"; fail=1; }
# its segment edges as a .poly, triangulated again: the same triangles
expect 0 "12 segments" -- "$G" cdt2d "$W/l.poly" -o "$W/l2.ele" --poly "$W/edges.poly"
expect 0 "13 triangles" -- "$G" cdt2d "$W/edges.poly" -o "$W/l3.ele" --check
cmp -s "$W/l2.ele" "$W/l3.ele" || { echo "FAIL: cdt2d of its own .poly differs"; fail=1; }
python3 -c "import numpy as np; np.save('$W/s.npy', np.array([[0, 1], [1, 2], [2, 0]], dtype=np.int32))"
printf '0 0\n4 0\n2 3\n2 1\n1 2\n' >"$W/tri.xyz"
expect 0 "check: valid constrained Delaunay" -- "$G" cdt2d "$W/tri.xyz" --segments "$W/s.npy" --check
python3 -c "import numpy as np; np.save('$W/x.npy', np.array([[0, 1], [2, 3]], dtype=np.int32))"
printf '0 0\n2 2\n0 2\n2 0\n' >"$W/x.xyz"
expect 3 "segments 0 and 1 cross" -- "$G" cdt2d "$W/x.xyz" --segments "$W/x.npy" -o "$W/x.ele"
[ -e "$W/x.ele" ] && { echo "FAIL: a failed cdt2d left an output file"; fail=1; }
# --split: a vertex at (1, 1), four triangles, checked; the .node lists the new point
expect 0 "1 crossings split -> 4 triangles" -- "$G" cdt2d "$W/x.xyz" --segments "$W/x.npy" -o "$W/x.ele" --split --check
grep -Eq '^ *4 +1 +1' "$W/x.node" || { echo "FAIL: cdt2d --split .node lacks the new point"; fail=1; }
printf '2 2 0 0\n1 0 0\n2 1 1\n1 0\n1 1 3\n0\n' >"$W/bad.poly"
expect 3 "bad.poly:5: segment endpoint 3 names no vertex" -- "$G" cdt2d "$W/bad.poly" --check
expect 2 "needs --segments" -- "$G" cdt2d "$W/tri.xyz" -o "$W/t.ele"
expect 0 "usage: gpugeom cdt2d" -- "$G" cdt2d --help
# hull3d: mesh formats, the checker, Qhull-style .npy, errors, no file left on failure
expect 0 "wrote 5000 ball3d" -- "$G" gen ball3d -n 5000 -o "$W/ball.npy"
for ext in ply off obj vtu npy; do
  expect 0 "5000 points -> " -- "$G" hull3d "$W/ball.npy" -o "$W/h.$ext"
  [ -s "$W/h.$ext" ] || { echo "FAIL: hull3d wrote no .$ext"; fail=1; }
done
expect 0 "check: valid convex hull" -- "$G" hull3d "$W/ball.npy" --check
expect 0 "valid hull3d" -- "$G" check "$W/h.off"
expect 0 "wrote 3000 grid3d" -- "$G" gen grid3d -n 3000 -o "$W/g3.npy"
expect 0 "-> 8 extreme points, 12 facets" -- "$G" hull3d "$W/g3.npy" -o "$W/h.ply"
printf '0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 3 0\n' >"$W/flat.xyz"
expect 3 "one plane" -- "$G" hull3d "$W/flat.xyz" -o "$W/hf.ply"
printf '0 0 0\n1 0 0\n0 1 0\n0 0 inf\n' >"$W/inf.xyz"
expect 3 "infinite" -- "$G" hull3d "$W/inf.xyz" -o "$W/hf.ply"
[ -e "$W/hf.ply" ] && { echo "FAIL: a failed hull3d left an output file"; fail=1; }
expect 3 "2D points" -- "$G" hull3d "$W/c.csv" -o "$W/hf.ply"
expect 2 "-o takes" -- "$G" hull3d "$W/ball.npy" -o "$W/hf.stl"
expect 0 "5000 points -> " -- "$G" hull3d "$W/ball.npy" -o "$W/h.vtu" --compress
expect 0 "valid hull3d" -- "$G" check "$W/h.vtu"
expect 0 "usage: gpugeom hull3d" -- "$G" hull3d --help
# delaunay3d: tetrahedral mesh formats (TetGen's pair too), the checker, errors, no file left
for ext in vtu ele ply npy; do
  expect 0 "5000 points -> " -- "$G" delaunay3d "$W/ball.npy" -o "$W/t.$ext"
  [ -s "$W/t.$ext" ] || { echo "FAIL: delaunay3d wrote no .$ext"; fail=1; }
done
[ -s "$W/t.node" ] || { echo "FAIL: delaunay3d wrote .ele without .node"; fail=1; }
expect 0 "check: valid Delaunay tetrahedralisation" -- "$G" delaunay3d "$W/ball.npy" --check
expect 0 "valid delaunay3d" -- "$G" check "$W/t.ele"
expect 0 "valid delaunay3d" -- "$G" check "$W/t.vtu"
expect 0 "flips23" -- "$G" --verbose delaunay3d "$W/ball.npy" --check
expect 0 "check: valid Delaunay tetrahedralisation" -- "$G" delaunay3d "$W/g3.npy" --check
# the digital method: the same tetrahedra (as a set: the order may differ), its phases
expect 0 "\(digital method\)" -- "$G" delaunay3d "$W/ball.npy" --method digital --check -o "$W/td.npy"
expect 0 "digital_splay" -- "$G" --verbose delaunay3d "$W/ball.npy" --method digital --grid 32 --check
python3 - "$W/t.npy" "$W/td.npy" <<'PY' || { echo "FAIL: delaunay3d --method digital gave other tetrahedra"; fail=1; }
import sys, numpy as np
a, b = (np.sort(np.load(f), axis=1) for f in sys.argv[1:3])
sys.exit(0 if a.shape == b.shape and (np.unique(a, axis=0) == np.unique(b, axis=0)).all() else 1)
PY
expect 2 "16..1024" -- "$G" delaunay3d "$W/ball.npy" --method digital --grid 8 --check
expect 2 "needs --method digital" -- "$G" delaunay3d "$W/ball.npy" --grid 64
expect 3 "one plane" -- "$G" delaunay3d "$W/flat.xyz" -o "$W/tf.vtu"
expect 3 "infinite" -- "$G" delaunay3d "$W/inf.xyz" -o "$W/tf.vtu"
expect 3 "2D points" -- "$G" delaunay3d "$W/c.csv" -o "$W/tf.vtu"
[ -e "$W/tf.vtu" ] && { echo "FAIL: a failed delaunay3d left an output file"; fail=1; }
expect 2 "-o takes" -- "$G" delaunay3d "$W/ball.npy" -o "$W/tf.stl"
expect 0 "usage: gpugeom delaunay3d" -- "$G" delaunay3d --help
# cells: a ball in its bounding box, periodic or not; the table's volumes fill the box
expect 0 "check: the cells fill the box" -- "$G" cells "$W/ball.npy" --box -1,1 -o "$W/cells.csv" --check
expect 0 "check: the cells fill the box" -- "$G" cells "$W/ball.npy" --box -1,-1,-1,1,1,1 --periodic xz -o "$W/cells.npy" --check
python3 - "$W/cells.csv" "$W/cells.npy" <<'PY' || { echo "FAIL: cells wrote a wrong table"; fail=1; }
import sys, numpy as np
c = np.loadtxt(sys.argv[1], delimiter=",", skiprows=1)
a = np.load(sys.argv[2])
ok = c.shape == (5000, 7) and abs(c[:, 1].sum() - 8) < 1e-9 and (c[:, 6] >= 4).all()
ok = ok and a.shape == (5000, 6) and abs(a[:, 0].sum() - 8) < 1e-9
sys.exit(0 if ok else 1)
PY
expect 3 "outside the box" -- "$G" cells "$W/ball.npy" --box 0.25,0.75 -o "$W/cf.csv"
[ -e "$W/cf.csv" ] && { echo "FAIL: a failed cells left an output file"; fail=1; }
expect 2 "2 numbers" -- "$G" cells "$W/ball.npy" --box 0,1,2 --check
expect 2 "x, y, z" -- "$G" cells "$W/ball.npy" --box -1,1 --periodic w --check
expect 2 "csv or .npy" -- "$G" cells "$W/ball.npy" --box -1,1 -o "$W/cf.vtu"
expect 3 "2D points" -- "$G" cells "$W/c.csv" --box -10,10 --check
expect 0 "usage: gpugeom cells" -- "$G" cells --help
# a failed write leaves no file behind
expect 3 "cannot create" -- "$G" gen uniform2d -n 10 -o "$W/nodir/x.xyz"
[ -e "$W/nodir" ] && { echo "FAIL: output folder appeared"; fail=1; }
exit $fail
