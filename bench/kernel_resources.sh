#!/usr/bin/env bash
# Runs on the lent GPU machine (cuobjdump and cu++filt are there, not on the build machine):
# registers and stack of the kernels in a binary, largest first, each named by the lambda it
# runs (the enclosing function and the lambda's instance) or by its kernel name. Occupancy
# follows from registers: 65 536 a multiprocessor, so 255 a thread holds 8 warps of 64.
#   bash bench/kernel_resources.sh .devbin/gpugeom_bench_del3d [pattern]
set -u
cuobjdump --dump-resource-usage "$1" 2>/dev/null | grep -E "Function|REG:" | paste - - |
  sed -E 's/.*Function ([^ :]+):.*REG:([0-9]+) STACK:([0-9]+).*/\2 \3 \1/' |
  while read -r r s f; do echo "$r $s $(echo "$f" | cu++filt)"; done |
  python3 -c '
import re, sys
pat = sys.argv[1] if len(sys.argv) > 1 else ""
rows = []
for line in sys.stdin:
    r, s, name = line.rstrip("\n").split(" ", 2)
    i = name.find("::[lambda")
    if i >= 0:
        inst = re.search(r"\(instance (\d+)\)", name[i:])
        head = name[:i]
        fn = re.findall(r"([\w~]+::[\w~]+)\(", head)
        key = (fn[-1] if fn else head[-60:]) + "#" + (inst.group(1) if inst else "?")
    else:
        key = re.sub(r"<.*", "", name)[:100]
    if pat in name:
        rows.append((int(r), int(s), key))
for r, s, k in sorted(rows, reverse=True)[:60]:
    print(f"{r:4d} regs {s:6d} B stack  {k}")
' "${2:-}"
