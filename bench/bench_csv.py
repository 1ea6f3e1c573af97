"""The benches' CSV rows, read one way for every reader (bench/plot.py, the documentation's
bench-plot directive): the benches write a header line, but rows appended by hand or by older
runs may have none, and then take the standard columns."""
import csv

COLUMNS = ["problem", "distribution", "n", "backend", "device", "upload_ms", "compute_ms",
           "download_ms", "device_resident_ms", "with_copies_ms", "exact_fraction"]
# gpugeom's own rows; every other backend is an anchor (CGAL, Qhull, SciPy, gDel3D, ...).
GPUGEOM = ("cuda", "cpu", "gpugeom")


def read_rows(path):
    """Every row of the CSV at ``path`` as a dict of its columns (strings)."""
    with open(path, newline="") as f:
        first = f.readline()
        f.seek(0)
        if first.startswith("problem,"):
            return list(csv.DictReader(f))
        return list(csv.DictReader(f, fieldnames=COLUMNS))


def is_ours(backend):
    """Whether a row's backend is gpugeom's (as opposed to an anchor's)."""
    return backend.startswith(GPUGEOM)
