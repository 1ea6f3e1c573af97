#!/usr/bin/env bash
# The command line's files on a machine (issue 24's targets): the host's facts, the page cache's
# own write and read rates (dd, the floor under every writer), the library's readers and writers
# (gpugeom_bench_io), then whole commands timed as a user meets them (process start, CUDA
# context and files included): `gpugeom hull3d` on a 2·10^6-point .xyz and `gpugeom delaunay2d`
# of 10^6 points to a binary .vtu.
#
#   bench/cli_io.sh GPUGEOM BENCH_IO|- [DIR]      (DIR: where the files go; default /tmp)
set -euo pipefail
G=$1
B=$2
D=${3:-/tmp}/gg_cli_io
mkdir -p "$D"
echo "== host: $(nproc) CPUs; $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
df -hT "$D" | tail -1
echo "== page cache floor (dd, 58 MB in 1 MiB blocks)"
dd if=/dev/zero of="$D/dd.bin" bs=1M count=58 2>&1 | tail -1
dd if="$D/dd.bin" of=/dev/null bs=1M 2>&1 | tail -1
rm -f "$D/dd.bin"
if [ "$B" != - ]; then  # (- : the readers and writers are timed elsewhere, e.g. by io_table.py)
  echo "== gpugeom_bench_io"
  "$B" --sizes "${SIZES:-1e6,1e7}" --reps "${REPS:-3}" --dir "$D"
fi
echo "== whole commands"
"$G" gen uniform3d -n 2000000 -o "$D/p.xyz"
"$G" gen uniform2d -n 1000000 -o "$D/u.npy"
for r in 1 2 3 4 5; do
  /usr/bin/time -f "hull3d p.xyz -> h.ply whole command %e s" "$G" --quiet hull3d "$D/p.xyz" -o "$D/h.ply"
done
"$G" --verbose hull3d "$D/p.xyz" -o "$D/h.ply" 2>&1 | grep '^\[time\]'
for r in 1 2 3; do  # the floors under it: a process that only starts the GPU; no GPU at all
  /usr/bin/time -f "info --device whole command %e s" "$G" info --device >/dev/null
  /usr/bin/time -f "hull3d --backend cpu whole command %e s" "$G" --quiet --backend cpu hull3d "$D/p.xyz" -o "$D/h.ply"
done
for r in 1 2 3; do
  "$G" --verbose delaunay2d "$D/u.npy" -o "$D/t.vtu" 2>&1 | grep '^\[time\] write' | sed 's/^/delaunay2d -> t.vtu /'
done
rm -rf "$D"
