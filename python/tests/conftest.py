"""Shared fixtures: the backends to run on (cpu always; cuda where a usable GPU is present)."""
import numpy as np
import pytest

import gpugeom

HAVE_GPU = gpugeom.built_with_cuda() and gpugeom.device_info()["available"]
BACKENDS = ["cpu"] + (["cuda"] if HAVE_GPU else [])


@pytest.fixture(params=BACKENDS)
def backend(request):
    return request.param


@pytest.fixture
def rng():
    return np.random.default_rng(12345)
