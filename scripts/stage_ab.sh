#!/usr/bin/env bash
# Developer helper: stages two or more builds' benchmark binaries for bench/ab_all.sh on the lent
# GPU machine, packed to fit one carry. For each LABEL=BUILD_DIR it copies
# BUILD_DIR/bench/gpugeom_bench_<cap> to .devbin/LABEL/ (stripped), with the shared libraries
# they need beyond a bare CUDA image in .devbin/lib (libtbb, which 3D Delaunay's bench links for
# CGAL's parallel triangulation, among them), and packs the binaries into .devbin/bins.tar.xz
# (xz -9: builds of one source share most of their bytes, so two builds cost little more than
# one). The carry limit is 64 MiB: a pack over 62 MiB is refused (stage fewer capabilities).
# Usage: scripts/stage_ab.sh "del2d hull3d del3d" P=/tmp/wtP/build B=build-cuda
# (caps: edt cvd del2d cdt2d hull3d del3d dynamic). On the GPU machine:
#   (cd .devbin && tar xJf bins.tar.xz) && CAPS="..." bench/ab_all.sh .devbin/P .devbin/B
set -euo pipefail
cd "$(dirname "$0")/.."
caps=$1
shift
rm -rf .devbin && mkdir -p .devbin/lib .devbin/pack
for spec in "$@"; do
  label=${spec%%=*} dir=${spec#*=}
  mkdir -p ".devbin/pack/$label"
  for c in $caps; do
    f="$dir/bench/gpugeom_bench_$c"
    [ -x "$f" ] || { echo "stage_ab: $f is not built" >&2; exit 2; }
    cp "$f" ".devbin/pack/$label/"
    ldd "$f" | awk '/=> \//{print $3}' | grep -E 'libcudart|libgomp|libpng|libgmp|libmpfr|libz\.|libtbb' |
      xargs -r -I{} cp -L {} .devbin/lib/
  done
  strip --strip-unneeded ".devbin/pack/$label"/*
done
tar cf - -C .devbin/pack . | xz -9 -T1 >.devbin/bins.tar.xz
rm -rf .devbin/pack
bytes=$(du -cb .devbin | tail -1 | cut -f1)
echo "stage_ab: .devbin holds $((bytes / 1048576)) MiB"
if [ "$bytes" -gt $((62 * 1048576)) ]; then
  echo "stage_ab: over 62 MiB, more than one carry takes: stage fewer capabilities" >&2
  exit 1
fi
