"""The examples run (small sizes, whatever backend is present) and draw their pictures."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("matplotlib")
EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

CASES = [
    ("terrain_voronoi.py", ["--levels", "8"]),
    ("edt_labels.py", []),
    ("stipple_photo.py", ["-n", "400", "--iterations", "15"]),
    ("hull_scan.py", ["-n", "20000"]),
    ("particle_cells.py", ["-n", "3000"]),
    ("spacetime_clearance.py", ["-n", "24", "--frames", "12"]),
    ("terrain_breaklines.py", ["--levels", "6"]),
    ("mesh_domain.py", ["--size", "0.01"]),
    ("dtfe_density.py", ["-n", "20000", "--pixels", "120"]),
    ("digital_methods.py", ["-n", "3000"]),
]


@pytest.mark.parametrize("script,args", CASES, ids=[c[0] for c in CASES])
def test_example_runs(script, args, tmp_path):
    out = tmp_path / (script[:-3] + ".png")
    r = subprocess.run([sys.executable, str(EXAMPLES / script), "-o", str(out)] + args,
                       capture_output=True, text=True, timeout=300, env=dict(os.environ))
    assert r.returncode == 0, r.stdout + r.stderr
    assert out.stat().st_size > 10000
    if "exact check" in r.stdout:
        assert "exact check: True" in r.stdout, r.stdout
