#!/usr/bin/env bash
# Runs on the lent GPU machine (repository root, .devbin/ carried): where the GPU time of a
# bench run goes, kernel by kernel. Nsight Compute (ncu) times every launch of the command
# (gpu__time_duration only, so the run stays close to its own speed) and the summary groups
# the launches by the lambda they run (the enclosing function and the lambda's instance there,
# read from the demangled closure names: the n-th lambda of that signature in the function) or
# by the kernel's name. The sum of the kernels against the
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
head = rows[0]
name_at, t_at = head.index("Kernel Name"), head.index("gpu__time_duration.sum")
units = rows[1][t_at] or "nsecond"
scale = {"nsecond": 1e-6, "usecond": 1e-3, "msecond": 1.0, "second": 1e3}.get(units, 1e-6)
def cut_group(s, open_, close):
    """s less its last balanced open_ ... close group (s ends with close)."""
    depth = 0
    for j in range(len(s) - 1, -1, -1):
        if s[j] == close:
            depth += 1
        elif s[j] == open_:
            depth -= 1
            if depth == 0:
                return s[:j]
    return ""
def key_of(name):
    kernel = re.match(r"(?:void )?([\w:]+)", name).group(1).split("::")[-1]
    i = name.find("::[lambda")
    if i < 0:
        return re.sub(r"<.*", "", name)[:90]
    inst = re.search(r"\(instance (\d+)\)", name[i:]).group(1)
    s = name[:i]
    # the enclosing function: the last identifier before its parameter list and template
    # arguments, which are cut from the end as balanced groups
    if s.endswith(" const"):
        s = s[:-6]
    if s.endswith(")"):
        s = cut_group(s, "(", ")")
    while s.endswith(">"):
        s = cut_group(s, "<", ">")
    fn = re.search(r"([\w~]+(?:::[\w~]+)?)$", s)
    return f"{kernel} {fn.group(1) if fn else s[-40:]} #{inst}"
groups = defaultdict(lambda: [0, 0.0]); total = 0.0
for r in rows[2:]:
    k = key_of(r[name_at]); ms = float(r[t_at].replace(",", "")) * scale
    groups[k][0] += 1; groups[k][1] += ms; total += ms
print(f"{len(rows) - 2} launches, {total:.1f} ms of kernels")
for k, (n, ms) in sorted(groups.items(), key=lambda kv: -kv[1][1])[:40]:
    print(f"{ms:9.2f} {n:8d}  {k}")
PY
