"""SciPy's own tests of ``distance_transform_edt`` (``scipy/ndimage/tests/test_morphology.py``),
run against gpugeom's with SciPy's name substituted at every call (issue 54): every one must
pass."""
import os

import pytest

scipy = pytest.importorskip("scipy")

SOURCE = os.path.join(os.path.dirname(scipy.__file__), "ndimage", "tests", "test_morphology.py")
if not os.path.exists(SOURCE):
    pytest.skip("this SciPy was installed without its tests", allow_module_level=True)

CALL = "ndimage.distance_transform_edt("


class _Outcomes:
    def __init__(self):
        self.outcome = {}

    def pytest_runtest_logreport(self, report):
        if report.when == "call" or report.outcome != "passed":
            self.outcome[report.nodeid.split("::", 1)[1]] = report.outcome


def test_scipy_distance_transform_edt_tests_pass(tmp_path):
    src = open(SOURCE).read()
    assert src.count(CALL) >= 10, "SciPy's test_morphology.py no longer calls it so: update"
    assert "from . import types\n" in src, "SciPy's test_morphology.py changed: update the shim"
    src = src.replace("from . import types\n", "from scipy.ndimage.tests import types\n", 1)
    # SciPy's conftest gives the array namespace as a fixture: NumPy's here (gpugeom's own tests
    # cover CuPy and PyTorch).
    src = ("import gpugeom as _gg\n" + src.replace(CALL, "_gg.distance_transform_edt(") +
           "\n\n@pytest.fixture\ndef xp():\n    return np\n")
    (tmp_path / "test_morphology_gpugeom.py").write_text(src)
    seen = _Outcomes()
    pytest.main(["-q", "--tb=short", "-p", "no:cacheprovider", "--rootdir", str(tmp_path),
                 "-k", "distance_transform_edt", str(tmp_path / "test_morphology_gpugeom.py")],
                plugins=[seen])
    ran = dict(seen.outcome)
    assert len(ran) >= 40, f"only {len(ran)} of SciPy's tests were collected (SciPy 1.17: 42)"
    wrong = [f"{k}: {v}" for k, v in sorted(ran.items()) if v not in ("passed", "skipped")]
    assert not wrong, "SciPy's tests that fail:\n" + "\n".join(wrong)
