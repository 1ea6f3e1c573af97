#!/usr/bin/env bash
# Do two builds give the same results? Runs the CLIs of builds A and B on the same generated
# inputs (general position, grids, circles and spheres, duplicates, near-degenerate sets) and
# compares the output files byte for byte. For refactors that must not change any output.
# Usage: bench/same_output.sh CLI_A CLI_B [cpu|cuda] [sets]. Prints one line per case; exit 1
# on a difference. With "sets", meshes are compared as sets of oriented simplices (the same
# triangles in any order, each from any starting corner), for changes that may reorder them.
# ONLY="cdt2d mesh2d": those commands only.
set -u
A=$1 B=$2 BK=${3:-cpu} MODE=${4:-bytes}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
diffs=0
gen() { "$A" --quiet gen "$1" -n "$2" -o "$W/$3" --seed "${4:-1}"; }
gen uniform2d 200000 u2.npy
gen gaussian2d 100000 g2.npy
gen grid2d 90000 grid2.npy
gen circle2d 20000 c2.npy
gen thin_circle2d 50000 tc2.npy
gen two_segments2d 5000 s2.npy
gen uniform3d 200000 u3.npy
gen ball3d 200000 b3.npy
gen sphere3d 50000 sp3.npy
gen grid3d 64000 grid3.npy
gen thin_box3d 50000 tb3.npy
# Duplicates: a grid and a shuffled copy of part of it, one file.
python3 - "$W" <<'EOF'
import sys, numpy as np
w = sys.argv[1]
for src, dst in (("grid2.npy", "dup2.npy"), ("grid3.npy", "dup3.npy")):
    p = np.load(f"{w}/{src}")
    rng = np.random.default_rng(7)
    q = np.concatenate([p, p[rng.permutation(len(p))[: len(p) // 3]]])
    np.save(f"{w}/{dst}", q[rng.permutation(len(q))])
EOF
# A planar straight-line graph (Triangle's .poly): random points, a square boundary and random
# chords (some crossing, for --split); and an image and a volume for the distance transform.
python3 - "$W" <<'EOF'
import sys, numpy as np
w = sys.argv[1]
rng = np.random.default_rng(3)
pts = np.concatenate([[[0, 0], [1, 0], [1, 1], [0, 1]], rng.random((3000, 2)) * 0.96 + 0.02])
seg = [[0, 1], [1, 2], [2, 3], [3, 0]]
seg += [list(rng.choice(np.arange(4, len(pts)), 2, replace=False)) for _ in range(40)]
with open(f"{w}/pslg.poly", "w") as f:
    f.write(f"{len(pts)} 2 0 0\n")
    f.writelines(f"{i} {float(x)!r} {float(y)!r}\n" for i, (x, y) in enumerate(pts))
    f.write(f"{len(seg)} 0\n")
    f.writelines(f"{i} {a} {b}\n" for i, (a, b) in enumerate(seg))
    f.write("0\n")
np.save(f"{w}/img.npy", (rng.random((300, 200)) < 0.01).astype(np.uint8))
np.save(f"{w}/vol.npy", (rng.random((40, 50, 60)) < 0.002).astype(np.uint8))
EOF
same_sets() {  # two .off meshes: the same oriented triangles?
  python3 - "$1" "$2" <<'PY'
import sys
def faces(path):
    tok = open(path).read().split()
    nv, nf = int(tok[1]), int(tok[2])
    t = tok[4 + 3 * nv:]
    out = set()
    for i in range(nf):
        a, b, c = (int(x) for x in t[4 * i + 1 : 4 * i + 4])
        r = min((a, b, c), (b, c, a), (c, a, b))  # rotations keep the orientation
        out.add(r)
    return out
sys.exit(0 if faces(sys.argv[1]) == faces(sys.argv[2]) else 1)
PY
}
run() {  # $1 command, $2 input, $3 output extension, then the command's options
  [ -z "${ONLY:-}" ] || [[ " $ONLY " == *" $1 "* ]] || return 0  # ONLY="cdt2d edt": those only
  local name="$1 $2${4:+ ${*:4}}"
  "$A" --quiet --backend "$BK" "$1" "$W/$2" -o "$W/a.$3" "${@:4}" >"$W/a.log" 2>&1
  local ra=$?
  "$B" --quiet --backend "$BK" "$1" "$W/$2" -o "$W/b.$3" "${@:4}" >"$W/b.log" 2>&1
  local rb=$?
  if [ $ra -ne $rb ]; then
    echo "DIFF  $name: exit $ra vs $rb"
    diffs=$((diffs + 1))
  elif [ $ra -ne 0 ]; then
    if cmp -s "$W/a.log" "$W/b.log"; then echo "same  $name (both refused)"; else
      echo "DIFF  $name: messages differ"
      diffs=$((diffs + 1))
    fi
  elif cmp -s "$W/a.$3" "$W/b.$3"; then
    echo "same  $name"
  elif [ "$MODE" = sets ] && same_sets "$W/a.$3" "$W/b.$3"; then
    echo "same  $name (as sets)"
  else
    echo "DIFF  $name"
    diffs=$((diffs + 1))
  fi
  rm -f "$W/a.$3" "$W/b.$3"
}
EXT=ply
[ "$MODE" = sets ] && EXT=off
for f in u2 g2 grid2 c2 tc2 s2 dup2; do run delaunay2d $f.npy $EXT; done
for f in u3 b3 sp3 grid3 tb3 dup3; do run hull3d $f.npy $EXT; done
# The other capabilities (their outputs compared byte for byte whatever the mode).
for f in u3 b3 sp3 grid3 tb3 dup3; do run delaunay3d $f.npy npy; done
run cdt2d pslg.poly ply --split
run mesh2d pslg.poly ply -q 25 --split
run edt img.npy npy
run edt vol.npy npy
run cells u3.npy npy --box 0,1
run cells u3.npy npy --box 0,1 --periodic xyz
echo "differences: $diffs"
[ $diffs -eq 0 ]
