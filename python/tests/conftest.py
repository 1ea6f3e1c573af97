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


@pytest.fixture(scope="session")
def cluster_client():
    """A LocalCluster of 2 single-threaded worker processes (gpugeom.dask's tests), once a run."""
    distributed = pytest.importorskip("distributed")
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None, silence_logs=40)
    client = distributed.Client(cluster)
    yield client
    client.close()
    cluster.close()
