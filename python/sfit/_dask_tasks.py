"""The tasks of sfit.dask (docs/python.md, "More than one machine"): what a worker computes
from one chunk of points. Every result is a small plain object or numpy array."""

import numpy as np

from . import _sfit
from ._dask_input import _block_stats

class _Chunk:
    """A chunk's points with their rows' statistics, as one task result (a tuple would be
    taken for a task by Dask's graph optimisation)."""

    __slots__ = ("block", "info")

    def __init__(self, block, info):
        self.block, self.info = block, info


def _rows_sample(block, info, step):
    """The chunk's points of every step-th row (and the last row), with the row starts moved so
    each kept point keeps its index in its row (the points between were taken out)."""
    if step == 1:
        return _Chunk(block, info)
    g0, r0, starts, sizes, M = info
    r = block[:, 3].astype(np.int64)
    keep = (r % step == 0) | (r == M - 1)
    removed = np.cumsum(~keep)
    first = np.flatnonzero(np.diff(r, prepend=-1))  # each row's first point in the chunk
    starts = starts.copy()
    starts[r[first] - r0] -= removed[first] - ~keep[first]
    return _Chunk(block[keep], (g0, r0, starts, sizes, M))


class _First:
    """Pass 1 of a chunk: its statistics and, for the search's sample, the points of every
    step-th row and of its last row (the last row of the data is the last of each chunk
    holding it), with each point's position in the chunk (column 4)."""

    __slots__ = ("stats", "sample")

    def __init__(self, stats, sample):
        self.stats, self.sample = stats, sample


def _first_pass(block, step):
    stats = _block_stats(block)
    if stats is None or "error" in stats:
        return _First(stats, None)
    r = block[:, 3]
    keep = np.flatnonzero((r.astype(np.int64) % step == 0) | (r == r[-1]))
    return _First(stats, np.column_stack([block[keep], keep.astype(float)]))


def _stats_of(first):
    return first.stats


def _sample_of(first, info, step):
    """The sample of a chunk from its pass-1 points (every step-th row and the data's last
    row), with the row starts moved so each kept point keeps its index in its row."""
    g0, r0, starts, sizes, M = info
    a = first.sample
    r = a[:, 3].astype(np.int64)
    keep = (r % step == 0) | (r == M - 1)
    a = a[keep]
    r = r[keep]
    first_of_row = np.flatnonzero(np.diff(r, prepend=-1))
    starts = starts.copy()
    # g0 + (position in the sample) - start' = g0 + (position in the chunk) - start.
    starts[r[first_of_row] - r0] -= a[first_of_row, 4].astype(np.int64) - first_of_row
    return _Chunk(np.ascontiguousarray(a[:, :4]), (g0, r0, starts, sizes, M))


def _partial(chunk, centre, nu, nv, spec):
    block, info = chunk.block, chunk.info
    return _sfit._partial_normal_equations(block, info[0], info[1], info[2], info[3], info[4],
                                           centre, nu, nv, *spec)


def _deviation(chunk, centre, control, spec):
    block, info = chunk.block, chunk.info
    if len(block) == 0:
        return np.zeros(3)
    return _sfit._chunk_deviation(block, info[0], info[1], info[2], info[3], info[4], centre,
                                  control, *spec)
