"""The allocator's state: page faults NumPy's arrays need not pay (NumPy only).

glibc's ``malloc`` serves a block above its mmap threshold (128 kB when a
process starts) with freshly mapped pages, and gives them back to the
system when the block is freed; it also returns free memory at the top of
its heap above its trim threshold.  Every page is then faulted in again at
its first touch: about 1.7 µs a page on this project's virtual machines,
per step as much as a whole four-bar run computes.  Freeing one mapped block
raises both thresholds (to its size and twice that, up to :data:`MMAP_CAP`),
after which blocks of that size come from the heap and their pages stay.

* :func:`settle` raises the thresholds (a block allocated and freed
  untouched: no page is touched), for code whose arrays come and go, as a
  design sweep's chunks;
* :func:`warm` also touches the pages once, for a run whose first call
  should not pay them (``compile_plan`` warms the memory of its runs).

On other allocators both are an allocation and a free.  A process does each
size once: what it has settled or warmed, it keeps.  :func:`available_memory`
tells how much more the process can take (result files are chunked by it, a
sweep too large for it is refused before its arrays are made).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

MMAP_CAP = 32 << 20
"""glibc's cap on its dynamic mmap threshold (64-bit): a larger block is mapped afresh at
every allocation, whatever was freed before, so neither function acts above it."""

_settled = 0  # the largest block this process has allocated and freed (bytes)
_warmed = 0  # the most heap memory this process has touched and kept (bytes)


def settle(nbytes: int) -> int:
    """Allocate and free ``nbytes`` untouched, raising glibc's thresholds past them.

    Returns the bytes allocated: 0 above :data:`MMAP_CAP` or up to what this
    process has settled already.

    Examples
    --------
    >>> settle(MMAP_CAP + 1)
    0
    """
    global _settled
    nbytes = int(nbytes)
    if nbytes <= _settled or nbytes > MMAP_CAP:
        return 0
    np.empty(nbytes, np.uint8)  # allocated and freed at once
    _settled = nbytes
    return nbytes


def warm(nbytes: int) -> int:
    """Touch ``nbytes`` of heap memory and hand them back to the allocator, kept.

    After :func:`settle` the block comes from the heap; its pages are touched
    (a ``bytearray`` is zeroed; unlike a NumPy array of 4 MiB or more it is not
    given huge pages, whose first touch here can stall for milliseconds) and,
    freed, they stay in the heap for the next allocations.  Returns the bytes
    touched: 0 above :data:`MMAP_CAP` or up to what this process has warmed.

    Examples
    --------
    >>> warm(MMAP_CAP + 1)
    0
    """
    global _warmed
    nbytes = int(nbytes)
    if nbytes <= _warmed or nbytes > MMAP_CAP:
        return 0
    settle(nbytes)
    bytearray(nbytes)  # allocated, zeroed, freed
    _warmed = nbytes
    return nbytes


def _read_int(path: str) -> int | None:
    try:
        text = Path(path).read_text().strip()
    except OSError:
        return None
    return int(text) if text.isdigit() else None


def available_memory() -> int | None:
    """Bytes this process can still take (``None`` if unknown).

    Linux's estimate of memory available without swapping (``MemAvailable``
    of ``/proc/meminfo``), lowered to what a cgroup's memory limit leaves
    (v2 ``memory.max - memory.current``, v1 ``limit_in_bytes -
    usage_in_bytes``); elsewhere the free physical pages.
    """
    found = []
    try:
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemAvailable:"):
                found.append(int(line.split()[1]) * 1024)
                break
    except (OSError, ValueError, IndexError):
        pass
    for limit, usage in (("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current"),
                         ("/sys/fs/cgroup/memory/memory.limit_in_bytes",
                          "/sys/fs/cgroup/memory/memory.usage_in_bytes")):
        lim, use = _read_int(limit), _read_int(usage)
        if lim is not None and use is not None and lim < 2**60:
            found.append(max(0, lim - use))
    if not found:
        try:
            found.append(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
        except (ValueError, OSError, AttributeError):
            return None
    return min(found)


def gib(nbytes: int) -> str:
    """``nbytes`` in GiB for a message, any integer however large (a float would overflow).

    Examples
    --------
    >>> gib(3 * 2**30), gib(10**400)
    ('3 GiB', '9.31e+390 GiB')
    """
    from decimal import Decimal  # only for a message

    return f"{Decimal(int(nbytes)) / 2**30:.3g} GiB"
