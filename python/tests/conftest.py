"""Shared fixtures: the backends to run on (cpu always; cuda where a usable GPU is present); a
LocalCluster for gpugeom.dask, and a worker that dies mid-run."""
import contextlib
import os

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


class _KillOnce:
    """Ends the worker process the first time a task whose key holds `word` starts (a crash
    mid-run)."""

    def __init__(self, word, marker):
        self.word, self.marker = word, marker

    def transition(self, key, start, finish, **kwargs):
        if (finish == "executing" and self.word in str(key)
                and not os.path.exists(self.marker)):
            open(self.marker, "w").close()
            os._exit(1)


@pytest.fixture
def kill_worker_once(cluster_client, tmp_path):
    """with kill_worker_once(word) as killed: ... kills the worker that first starts a task whose
    key holds `word`; killed() says whether one died."""
    distributed = pytest.importorskip("distributed")

    @contextlib.contextmanager
    def run(word):
        marker = str(tmp_path / f"killed-{word}")
        plugin = type("KillOnce", (_KillOnce, distributed.WorkerPlugin), {})(word, marker)
        cluster_client.register_plugin(plugin, name="kill-once")
        try:
            yield lambda: os.path.exists(marker)
        finally:
            cluster_client.unregister_worker_plugin("kill-once")
    return run
