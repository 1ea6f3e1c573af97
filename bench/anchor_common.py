"""Helpers the Python anchor scripts share: timing one call (or the median of several) and
appending a CSV row in the format every benchmark driver writes (bench_csv.hpp)."""
import statistics
import time


def timed_ms(fn, *args):
    """(result, milliseconds) of fn(*args), wall clock."""
    t0 = time.perf_counter()
    out = fn(*args)
    return out, 1e3 * (time.perf_counter() - t0)


def med(fn, reps, sync=None):
    """Median milliseconds of reps calls of fn(), each between two calls of sync (a device
    synchronise, so that queued GPU work is timed) when given."""
    ts = []
    for _ in range(reps):
        if sync:
            sync()
        t0 = time.perf_counter()
        fn()
        if sync:
            sync()
        ts.append(1e3 * (time.perf_counter() - t0))
    return statistics.median(ts)


def append_row(csv, problem, distribution, n, tool, ms, resident_ms=0, machine="cpu-1core"):
    """One row whose compute and with-copies times are the same measurement (a CPU anchor, or an
    end-to-end call); machine: where it ran (the GPU's name for gpugeom's rows)."""
    if not csv:
        return
    with open(csv, "a") as c:
        c.write(f"{problem},{distribution},{n},{tool},{machine},0,{ms},0,{resident_ms},{ms},0\n")
