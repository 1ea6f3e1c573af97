#!/usr/bin/env python3
"""Turns bench CSV into PNG plots, per problem and distribution: time against n for every
backend and anchor (with copies), and the speed-up of each gpugeom backend over each anchor
measured at the same n (device-resident time for gpugeom, as the anchors keep their data where
they compute)."""
import collections, os, sys

from bench_csv import is_ours, read_rows

def main(path, outdir):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("note: matplotlib missing, no plots")
        return 0
    rows = read_rows(path)
    groups = collections.defaultdict(lambda: collections.defaultdict(dict))
    for r in rows:
        g = groups[(r["problem"], r["distribution"])][r["backend"]]
        g[int(r["n"])] = (float(r["with_copies_ms"]), float(r["device_resident_ms"]))
    os.makedirs(outdir, exist_ok=True)
    written = 0
    for (prob, dist), series in groups.items():
        anchors = [b for b in series if not is_ours(b)]
        ours = [b for b in series if is_ours(b)]
        fig, axes = plt.subplots(1, 2 if anchors and ours else 1, figsize=(11 if anchors and ours else 6, 4))
        axes = axes if hasattr(axes, "__len__") else [axes]
        for bk, pts in sorted(series.items()):
            ns = sorted(pts)
            axes[0].loglog(ns, [pts[n][0] for n in ns], "o-", label=bk)
        axes[0].set_xlabel("n"); axes[0].set_ylabel("ms (with copies)"); axes[0].set_title(f"{prob} / {dist}")
        axes[0].grid(True, which="both", alpha=.3); axes[0].legend()
        if anchors and ours:
            ax = axes[1]
            for o in ours:
                for a in anchors:
                    # device-resident time where the row has one (0: not measured, as on
                    # the CPU backend), else the time with copies; pairs without both skipped
                    t = lambda pt: pt[1] if pt[1] > 0 else pt[0]
                    ns = [n for n in sorted(set(series[o]) & set(series[a]))
                          if t(series[o][n]) > 0 and t(series[a][n]) > 0]
                    if ns:
                        ax.loglog(ns, [t(series[a][n]) / t(series[o][n]) for n in ns], "o-", label=f"{o} vs {a}")
            ax.axhline(1, color="grey", lw=.8)
            ax.set_xlabel("n"); ax.set_ylabel("speed-up (anchor time / gpugeom time)")
            ax.set_title("speed-up, device-resident"); ax.grid(True, which="both", alpha=.3); ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, f"{prob}_{dist}.png"), dpi=100)
        plt.close(fig)
        written += 1
    print(f"{written} plots written to {outdir}")
    return 0

if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "bench_plots"))
