"""Where the chunks of a sweep run: in this process, in local worker processes, or on Dask.

The designs are cut into chunks of whole designs whose boundaries depend only
on the chunk size, never on who evaluates them; every backend evaluates a
chunk by the same function (:func:`evaluate_chunk`), so the table is the same
bit for bit whichever ran it.  Each process builds the compiled mechanism once
(:func:`compiled_state`, cached per sweep specification; loaded from the on-disk cache
of compiled topologies, without SymPy) and reuses it for all its chunks.

:class:`Execution` says which (``execution`` of :func:`linkage_sym.design.sweep`):

* in-process (default): chunk after chunk, with a progress bar on a terminal
  (tqdm, the ``progress`` extra);
* ``workers=N``: a :class:`concurrent.futures.ProcessPoolExecutor` of ``N``
  processes (started by ``spawn``: a fresh interpreter each);
* ``dask=ADDRESS``: the chunks go to a ``dask.distributed`` scheduler
  (``"local"`` starts a :class:`~dask.distributed.LocalCluster` of ``workers``
  processes, one thread each); dask's distributed scheduler is the ``sweep`` extra.
"""

from __future__ import annotations

import functools
import os
from dataclasses import dataclass

import numpy as np

from linkage_sym.design.errors import SweepError
from linkage_sym.numeric.engine import heap
from linkage_sym.output import chunk_bounds, progress_bar

__all__ = ["Execution", "Spec", "compiled_state", "evaluate_chunk", "run_chunks", "chunk_bounds"]

TARGET_ENTRIES = 1 << 16
"""Designs x path points per chunk by default.  Measured on 10^5 four-bars x 361 steps (CPU
time, one core): 16,000 entries 3.2 s, 32,000 2.5 s, 65,000 2.0 s, 130,000 2.2 s, 260,000
2.3 s -- smaller chunks pay Python's overhead per call, larger ones leave the cache.  Again
with the limit positions located per run (:data:`RUN_DESIGNS`), the crank-rocker's ``K``
and transmission angle over 40,000 designs x 361 steps: 46,000 entries 1.04 s, 65,000
1.00 s, 92,000 0.98 s, 130,000 1.02 s, 520,000 3.2 s."""


@dataclass(frozen=True)
class Execution:
    """How a sweep runs its chunks: in this process (the default), in local processes, or
    on Dask; the results are the same bit for bit whichever runs them.

    Attributes
    ----------
    workers : int, optional
        Local processes (default: this process only); with ``dask="local"``, the
        LocalCluster's.
    dask : str or dask.distributed.Client, optional
        A scheduler address, ``"local"`` (a LocalCluster of ``workers`` processes) or a
        client: the chunks run there.
    chunk_designs : int, optional
        Designs per chunk (default: about 65,000 design-steps a chunk, :data:`TARGET_ENTRIES`;
        8 designs when they run one at a time).
    progress : bool
        A progress bar on a terminal (tqdm).
    backend : str
        ``"numpy"`` (the default: arrays over designs x steps) or ``"numba"``: the
        generated closed forms compiled by numba, one loop over designs x steps
        (:mod:`linkage_sym.design.numba_sweep`; the ``numba`` extra), for the metrics
        ``assemblable``, ``grashof``, ``K`` and ``min_transmission_deg`` of scenes of
        dyads; its numbers are the NumPy backend's within a few rounding errors, not bit
        for bit.

    The sweep checks them; a problem names the attribute (``workers``, ``chunk_designs``,
    ``backend``).

    Examples
    --------
    >>> Execution(workers=2)
    Execution(workers=2, dask=None, chunk_designs=None, progress=False, backend='numpy')
    """

    workers: int | None = None
    dask: object = None
    chunk_designs: int | None = None
    progress: bool = False
    backend: str = "numpy"


@dataclass(frozen=True)
class Spec:
    """What a worker needs to evaluate chunks: the scene, the varied names, the metrics."""

    scene: object
    names: tuple
    metrics: tuple
    output: str | None = None
    trace: tuple | None = None
    forces: bool = False  # compile the force blocks (a varied mass or load, or force metrics)
    backend: str = "numpy"  # or "numba" (linkage_sym.design.numba_sweep)


SETTLE_BYTES = 30 << 20
"""The block :func:`settle_allocator` allocates and frees (below glibc's 32 MB cap of its
dynamic mmap threshold)."""

def settle_allocator() -> None:
    """Free one large block once per process, so the chunks' arrays stop costing page faults.

    A chunk's arrays (about 0.5 MB each, a few MB at once) are freed when the chunk is
    done.  glibc's ``malloc`` maps blocks above its mmap threshold (128 kB at start) anew
    each time and returns free memory at the top of its heap to the system above its trim
    threshold, so every chunk faulted its pages in again (measured: 1.6 million page
    faults and half the time in the kernel for 10^5 four-bars).  Freeing a mapped block
    raises both thresholds (to the block's size and twice that), after which the arrays
    come from the heap and stay there (:func:`linkage_sym.numeric.engine.heap.settle`).
    """
    heap.settle(SETTLE_BYTES)


@functools.lru_cache(maxsize=4)
def compiled_state(spec: Spec):
    """``(model, metric plan)`` of ``spec``: the compiled mechanism's model of its scene
    (:class:`~linkage_sym.design.evaluate.Model`) and its
    :class:`~linkage_sym.design.metrics.MetricPlan`, built once per process and spec
    (cached) and shared by all the chunks it evaluates."""
    from linkage_sym.design.evaluate import Model
    from linkage_sym.design.metrics import MetricPlan

    settle_allocator()

    plan = MetricPlan(spec.scene, spec.metrics, spec.output, spec.trace)
    if spec.backend == "numba":
        from linkage_sym.design.numba_sweep import NumbaModel

        return NumbaModel(spec.scene, plan, forces=plan.forces or spec.forces), plan
    model = Model(spec.scene, forces=plan.forces or spec.forces)
    return model, plan


def evaluate_chunk(spec: Spec, values: np.ndarray) -> dict:
    """The metric columns of the designs ``values`` (n, k) of one chunk."""
    model, plan = compiled_state(spec)
    P = model.design_params(spec.names, values)
    sol = model.solve(P, len(values), plan.need, plan.unwrap(model), rates=plan.rates(model))
    return plan.compute(model, sol)


TASKS_PER_WORKER = 4
"""Parallel runs hand each process about this many tasks, each a run of consecutive chunks:
a task per chunk (a few hundred designs) cost more in scheduling than in solving (measured:
a million four-bars on a 2-process LocalCluster took 2.1x the time of --workers 2 with one
task per chunk).  The chunks, and so every design's numbers, stay the same."""


def evaluate_chunks(spec: Spec, parts: list) -> list[dict]:
    """:func:`evaluate_chunk` of each of ``parts``, in order (one parallel task, or a run of
    :data:`RUN_DESIGNS` in this process): the limit positions of all of them located
    together (:meth:`~linkage_sym.design.metrics.MetricPlan.finish`: the same numbers)."""
    model, plan = compiled_state(spec)
    begun = []
    every = None  # the run's designs assembled at once (a design's assembly is its own)
    if not model.one_at_a_time and len(parts) > 1:
        values = np.concatenate(parts)
        every = model.assemble(model.design_params(spec.names, values), len(values))
    a = 0
    for values in parts:
        n = len(values)
        P = model.design_params(spec.names, values)
        asm = None if every is None else model.assembly_of(every, a, a + n)
        sol = model.solve(P, n, plan.need, plan.unwrap(model), asm, plan.rates(model))
        begun.append(plan.begin(model, sol))
        a += n
    return plan.finish(model, begun)


RUN_DESIGNS = 8192
"""Designs whose chunks run together in this process (:func:`evaluate_chunks`): their limit
positions are located in one Newton iteration, each step one call of the generated
functions instead of one per chunk (measured: the crank-rocker's ``K`` over 40,000 designs
x 361 steps, chunks of 181 designs, spent a third of its time in those calls one chunk at
a time)."""


def _runs(parts: list) -> list[tuple[int, list]]:
    """``parts`` in runs of consecutive chunks of about :data:`RUN_DESIGNS` designs."""
    out, k = [], 0
    while k < len(parts):
        j, size = k, 0
        while j < len(parts) and (j == k or size + len(parts[j]) <= RUN_DESIGNS):
            size += len(parts[j])
            j += 1
        out.append((k, parts[k:j]))
        k = j
    return out


def _tasks(parts: list, processes: int) -> list[tuple[int, list]]:
    """``parts`` grouped into runs of consecutive chunks: ``(first index, chunks)``."""
    n = max(1, min(len(parts), TASKS_PER_WORKER * max(1, processes)))
    bounds = np.linspace(0, len(parts), n + 1).round().astype(int)
    return [(int(a), parts[a:b]) for a, b in zip(bounds[:-1], bounds[1:]) if b > a]


def run_chunks(spec: Spec, values: np.ndarray, size: int, workers=None, dask=None,
               progress: bool = False) -> list[dict]:
    """Evaluate every chunk; the chunks' column dicts in order."""
    bounds = chunk_bounds(len(values), size)
    parts = [np.ascontiguousarray(values[a:b]) for a, b in bounds]
    bar = progress_bar(len(values), progress, unit="design")
    out: list = [None] * len(parts)

    def done(k, res):
        out[k] = res
        if bar is not None:
            bar.update(len(parts[k]))

    try:
        if dask is not None:
            _run_dask(spec, parts, dask, workers, done)
        elif workers is not None and workers > 1:
            _run_workers(spec, parts, workers, done)
        else:
            for k, run in _runs(parts):
                for j, res in enumerate(evaluate_chunks(spec, run)):
                    done(k + j, res)
    finally:
        if bar is not None:
            bar.close()
    return out


def _run_workers(spec, parts, workers, done):
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed

    with ProcessPoolExecutor(max_workers=workers,
                             mp_context=multiprocessing.get_context("spawn")) as ex:
        futs = {ex.submit(evaluate_chunks, spec, run): k for k, run in _tasks(parts, workers)}
        for f in as_completed(futs):
            for j, res in enumerate(f.result()):
                done(futs[f] + j, res)


def dask_client(address, workers=None):
    """A client of the scheduler at ``address`` (``"local"``: a new LocalCluster of
    ``workers`` processes, one thread each) and what to close afterwards."""
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise SweepError("dask", "needs dask's distributed scheduler, which is not installed: "
                                   "pip install 'linkage_sym[sweep]'") from None
    if address == "local":
        import dask

        # dask's nannies set MALLOC_TRIM_THRESHOLD_ (65536) in their workers, which fixes
        # glibc's thresholds: every chunk array is mapped anew, page by page (measured: 8.5
        # million page faults for 10^5 four-bars, 8x the time of --workers); the sweep's own
        # cluster keeps the dynamic thresholds (settle_allocator)
        with dask.config.set({"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}):
            cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                                   processes=True, dashboard_address=None)
        client = Client(cluster)
        return client, [client, cluster]
    try:
        client = Client(address, timeout=30)
    except OSError as err:
        raise SweepError("dask", f"cannot reach the scheduler at {address!r}: {err}") from None
    except ValueError as err:  # not an address dask can parse ('', 'tcp://', 'host:')
        raise SweepError("dask", f"{address!r} is not a scheduler address (HOST:PORT, "
                                   f"tcp://HOST:PORT, or 'local'): {err}") from None
    return client, [client]


def _run_dask(spec, parts, address, workers, done):
    from dask.distributed import as_completed

    client = address if hasattr(address, "map") else None
    closing = []
    if client is None:
        client, closing = dask_client(address, workers)
    try:
        # a key of its own (hash=False): a second sweep on the same client must not share
        # the first one's key while the scheduler releases it
        spec_f = client.scatter(spec, broadcast=True, hash=False)
        n_workers = len(client.scheduler_info().get("workers", {})) or workers or 1
        tasks = _tasks(parts, n_workers)
        futs = [client.submit(evaluate_chunks, spec_f, run, pure=False) for _, run in tasks]
        index = {f.key: k for f, (k, _) in zip(futs, tasks)}
        for f in as_completed(futs):
            for j, res in enumerate(f.result()):
                done(index[f.key] + j, res)
    finally:
        for c in closing:
            c.close()
