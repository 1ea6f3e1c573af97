#!/usr/bin/env bash
# Runs on the lent GPU machine (repository root, .devbin/ carried): where the GPU time of a
# bench run goes, kernel by kernel. Nsight Compute (ncu) times every launch of the command
# (gpu__time_duration only, so the run stays close to its own speed) and the summary groups
# the launches by the lambda they run (the enclosing function and the lambda's number there,
# read from nvcc's closure names) or by the kernel's name. The sum of the kernels against the
# command's own wall time shows how much of it is launches and host waits rather than work.
#   bash bench/kernel_profile.sh .devbin/gpugeom_bench_del3d --reps 1 --cgal-max 0 uniform:1000000
# Writes $OUT/kernels.csv (every launch) and prints the 40 largest groups.
set -u
export LD_LIBRARY_PATH=$PWD/.devbin/lib:${LD_LIBRARY_PATH:-}
OUT=${OUT:-/tmp/gg_out}
mkdir -p "$OUT"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
ncu --clock-control none --metrics gpu__time_duration.sum --csv --page raw "$@" >"$OUT/kernels.csv" 2>"$OUT/kernels.err"
echo "ncu exit $?"
python3 - "$OUT/kernels.csv" <<'PY'
import csv, re, sys
from collections import defaultdict
rows = [r for r in csv.reader(l for l in open(sys.argv[1]) if l.startswith('"'))]
if len(rows) < 3:
    sys.exit("no kernels profiled")
head, units = rows[0], rows[1]
name_at, t_at = head.index("Kernel Name"), head.index("gpu__time_duration.sum")
scale = {"nsecond": 1e-6, "usecond": 1e-3, "msecond": 1.0, "second": 1e3}.get(units[t_at], 1e-6)
tag = re.compile(r", &([\w:~]+), (\d+)u?>")
groups = defaultdict(lambda: [0, 0.0])
total = 0.0
for r in rows[2:]:
    name = r[name_at]
    m = tag.search(name)
    if m:
        key = m.group(1).split("::")[-2:] + ["#" + m.group(2)]
        key = "::".join(key[:-1]) + key[-1]
        kernel = re.match(r"(?:void )?([\w:]+)", name).group(1).split("::")[-1]
        key = f"{kernel} {key}"
    else:
        key = re.sub(r"<.*", "", name)[:90]
    ms = float(r[t_at].replace(",", "")) * scale
    groups[key][0] += 1
    groups[key][1] += ms
    total += ms
print(f"{len(rows) - 2} launches, {total:.1f} ms of kernels")
print(f"{'ms':>9} {'launches':>8}  kernel / lambda")
for k, (n, ms) in sorted(groups.items(), key=lambda kv: -kv[1][1])[:40]:
    print(f"{ms:9.2f} {n:8d}  {k}")
PY
