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
expect 2 "slices apply to 3D grids only" -- "$G" edt "$W/one.pgm" -o "$W/z.npy" --slices 0
printf 'P2\n2 2\n255\n0 0\n0 0\n' >"$W/none.pgm"
expect 3 "has no site" -- "$G" edt "$W/none.pgm" -o "$W/z.npy"
[ -e "$W/z.npy" ] && { echo "FAIL: a failed edt left an output file"; fail=1; }
expect 2 "sampling needs one value per axis" -- "$G" edt "$W/one.pgm" -o "$W/z.npy" --sampling 1,2,3
expect 2 "raw input needs --shape and --dtype" -- "$G" edt "$W/vol.raw" -o "$W/z.npy"
expect 2 "outputs are .npy files" -- "$G" edt "$W/one.pgm" -o "$W/z.png"
# a failed write leaves no file behind
expect 3 "cannot create" -- "$G" gen uniform2d -n 10 -o "$W/nodir/x.xyz"
[ -e "$W/nodir" ] && { echo "FAIL: output folder appeared"; fail=1; }
exit $fail
