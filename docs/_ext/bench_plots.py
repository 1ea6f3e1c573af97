"""Benchmark plots drawn from the CSVs the benches write (docs/bench_*.csv), when the site is
built, so the page shows the measurements themselves.

``.. bench-plot:: FILE.csv[,FILE2.csv]`` with options:

- ``:problem:``  the CSV's problem column (e.g. delaunay2d)
- ``:kind:``     ``scaling`` (time against n, log-log, one line per backend; default) or
  ``bars`` (one group per distribution at the n given by ``:n:``, log time)
- ``:distribution:`` (scaling) the distribution, or a prefix ending in ``*`` for a family of
  them (each row's n on the axis); ``:distributions:`` (bars) a comma list
- ``:n:``        (bars) the size compared
- ``:backends:`` a comma list of backends to show, in order (default: all in the file); in
  ``bars``, ``B@device`` is backend B's device-resident time as a bar of its own
- ``:labels:``   backend=label pairs separated by semicolons, for the legend
- ``:caption:``  the figure's caption; the machine (the CSV's device column) is added to it
- ``:xlabel:``   (scaling) what n counts (default "n")

Every plot names its machine: the GPU for gpugeom's rows and the CPU anchors' rows as the CSV
names them. A CSV without a header line gets the benches' standard columns. Rows repeated for
one backend and n keep the last (the benches append as they go; the last run is the final one).
"""
import hashlib
import sys
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import directives
from sphinx.errors import ExtensionError
from sphinx.util.docutils import SphinxDirective

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
from bench_csv import is_ours as _ours, read_rows  # noqa: E402  (the benches' one reader)


def _machine(rows):
    gpus = sorted({r["device"] for r in rows if r["device"].startswith("NVIDIA")})
    cpus = sorted({r["device"] for r in rows if not r["device"].startswith("NVIDIA")})
    text = ", ".join(gpus) if gpus else "the CPU"
    if cpus:
        text += " (anchors and CPU rows on its host: " + ", ".join(cpus) + ")"
    return text


class BenchPlot(SphinxDirective):
    required_arguments = 1
    option_spec = {
        "problem": directives.unchanged_required,
        "kind": lambda a: directives.choice(a, ("scaling", "bars")),
        "distribution": directives.unchanged,
        "distributions": directives.unchanged,
        "n": directives.nonnegative_int,
        "backends": directives.unchanged,
        "labels": directives.unchanged,
        "caption": directives.unchanged,
        "xlabel": directives.unchanged,
    }

    def run(self):
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        docs = Path(self.env.srcdir)
        files = [f.strip() for f in self.arguments[0].split(",")]
        rows = []
        for f in files:
            p = docs / f
            if not p.exists():
                raise self.error(f"bench-plot: no file {f} in docs/")
            rows += read_rows(p)
            self.env.note_dependency(str(p))
        prob = self.options["problem"]
        rows = [r for r in rows if r["problem"] == prob]
        kind = self.options.get("kind", "scaling")
        labels = dict(kv.strip().split("=", 1) for kv in self.options.get("labels", "").split(";")
                      if kv.strip())
        want = [b.strip() for b in self.options.get("backends", "").split(",") if b.strip()]
        if kind == "scaling":
            dist = self.options.get("distribution", "")
            if dist.endswith("*"):  # a family: every distribution with that prefix, n from each
                rows = [r for r in rows if r["distribution"].startswith(dist[:-1])]
            else:
                rows = [r for r in rows if r["distribution"] == dist]
        else:
            dists = [d.strip() for d in self.options.get("distributions", "").split(",")]
            n = self.options.get("n")
            rows = [r for r in rows if r["distribution"] in dists and int(r["n"]) == n]
        if want:
            rows = [r for r in rows if r["backend"] in {b.split("@")[0] for b in want}]
        if not rows:
            raise self.error(f"bench-plot: no rows for {prob} in {files} with these options")
        backends = want or sorted({r["backend"] for r in rows}, key=lambda b: (not _ours(b), b))
        # the last row of each (backend, distribution, n) is the one kept
        series = {}
        for r in rows:
            series[(r["backend"], r["distribution"], int(r["n"]))] = r

        fig, ax = plt.subplots(figsize=(7.5, 4.2))
        if kind == "scaling":
            for b in backends:
                pts = sorted((n, float(r["with_copies_ms"]), float(r["device_resident_ms"] or 0))
                             for (bb, _, n), r in series.items() if bb == b)
                if not pts:
                    continue
                lab = labels.get(b, b)
                style = "o-" if _ours(b) else "s--"
                ax.loglog([p[0] for p in pts], [p[1] for p in pts], style,
                          label=lab + (" (end to end)" if _ours(b) else ""))
                if b == "cuda" and any(p[2] > 0 for p in pts):
                    ax.loglog([p[0] for p in pts if p[2] > 0], [p[2] for p in pts if p[2] > 0],
                              "o:", label=lab + " (device-resident)")
            ax.set_xlabel(self.options.get("xlabel", "n"))
            ax.set_title(f"{prob}, {dist.rstrip('*')}")
        else:
            import numpy as np

            dists = [d for d in dists if any(k[1] == d for k in series)]
            width = 0.8 / max(1, len(backends))
            for i, b in enumerate(backends):
                # "cuda@device": that backend's device-resident time, as a bar of its own
                base, col = (b.split("@")[0], "device_resident_ms") if "@" in b else \
                    (b, "with_copies_ms")
                ys = [float(series[(base, d, n)][col]) if (base, d, n) in series
                      and float(series[(base, d, n)][col] or 0) > 0 else np.nan for d in dists]
                ax.bar(np.arange(len(dists)) + i * width, ys, width, label=labels.get(b, b))
            ax.set_xticks(np.arange(len(dists)) + width * (len(backends) - 1) / 2)
            ax.set_xticklabels(dists, rotation=20)
            ax.set_yscale("log")
            ax.set_title(f"{prob}, n = {n:,}")
        ax.set_ylabel("ms (log scale)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # beside, not over

        key = hashlib.sha1(repr((self.arguments, sorted(self.options.items()))).encode()).hexdigest()
        out_dir = docs / "_generated" / "bench"
        out_dir.mkdir(parents=True, exist_ok=True)
        name = f"{prob}_{kind}_{key[:10]}.png"
        fig.savefig(out_dir / name, dpi=100, bbox_inches="tight")
        plt.close(fig)

        rel = "/" + str((out_dir / name).relative_to(docs))
        fig_node = nodes.figure()
        fig_node += nodes.image(uri=rel, alt=f"{prob} benchmark")
        cap = self.options.get("caption", "")
        text = (cap + " " if cap else "") + f"Measured on {_machine(rows)}; from {', '.join(files)}."
        fig_node += nodes.caption(text=text)
        return [fig_node]


def setup(app):
    app.add_directive("bench-plot", BenchPlot)
    return {"version": "1", "parallel_read_safe": True}
