"""The command line each gallery example runs with when the documentation is built: small
sizes, so the whole gallery takes a minute or two on the CPU executor, and the picture written
into a temporary folder (sphinx-gallery collects the figures the example leaves open)."""
import os
import tempfile

SMALL = {
    "terrain_voronoi.py": ["--levels", "8"],
    "terrain_breaklines.py": ["--levels", "6"],
    "stipple_photo.py": ["-n", "1500", "--iterations", "20"],
    "hull_scan.py": ["-n", "20000"],
    "particle_cells.py": ["-n", "3000"],
    "spacetime_clearance.py": ["-n", "24", "--frames", "12"],
    "mesh_domain.py": [],
    "dtfe_density.py": ["-n", "60000", "--pixels", "200"],
    "digital_methods.py": ["-n", "10000"],
}
_OUT = tempfile.mkdtemp(prefix="gpugeom-gallery-")


def example_argv(sphinx_gallery_conf, script_vars):
    name = os.path.basename(script_vars["src_file"])
    return ["-o", os.path.join(_OUT, name[:-3] + ".png")] + SMALL.get(name, [])
