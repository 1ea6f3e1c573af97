"""The Dask cluster the gpugeom.dask benches run on: one worker process per GPU of the host (what
dask-cuda's LocalCUDACluster does, without needing it), and the bytes the workers sent each
other."""
import os

from distributed import Nanny, Scheduler, SpecCluster


def cluster(workers, cpu=False):
    """`workers` worker processes, each seeing one GPU (CUDA_VISIBLE_DEVICES; cpu: none), one
    Dask thread each. No memory limit (a block's arrays would be spilled to disk past Dask's
    default share of the host's memory), scratch space on the local disk."""
    # Dask starts its workers with OMP_NUM_THREADS=1 (distributed.nanny.pre-spawn-environ): the
    # library's host-side work (listing sites, the staged copies' helpers) would run on one core.
    # Each worker gets its share of the host's cores instead.
    cores = str(max(1, usable_cores() // workers))
    spec = {i: {"cls": Nanny, "options": {
        "nthreads": 1, "memory_limit": 0, "local_directory": "/tmp/gpugeom-dask",
        "env": {"OMP_NUM_THREADS": cores} | ({} if cpu else {"CUDA_VISIBLE_DEVICES": str(i)})}}
        for i in range(workers)}
    return SpecCluster(scheduler={"cls": Scheduler, "options": {"dashboard_address": None}},
                       workers=spec, silence_logs=40)


def usable_cores() -> int:
    """The cores this process may run on (taskset or a container's CPU set narrow them; the
    workers inherit the set), as OpenMP counts them."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def moved(client):
    """Bytes the workers have sent each other so far."""
    def sent(dask_worker):
        return int(getattr(dask_worker, "transfer_outgoing_bytes_total", 0))
    return sum(client.run(sent).values())
