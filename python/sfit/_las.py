"""Airborne LiDAR in ASPRS LAS files (versions 1.0 ... 1.4, point formats 0 ... 10, not
compressed), read with numpy alone: no Debian 12 package reads LAS (PDAL and laspy are not in
it), and the uncompressed format is a fixed header and fixed-size records.

The rows are the scan lines. A LAS point carries two flags for them: the scan direction and
"edge of flight line", set on the last point of a scan line before the mirror turns. A new row
starts after an edge point and wherever the scan direction changes. A file that sets neither
flag anywhere has no scan lines to give and is refused (give the rows yourself).

A large file is read in pieces of whole scan lines (scan_lines(), read_points()), each by the
worker that owns it, only its part of the file. Lines that run backwards (an oscillating
mirror's way back) are reversed, so all rows run one way.
"""

import os
import struct

import numpy as np

from ._errors import Error


def _error(code, message, path):
    e = Error(message)
    e.code = code
    e.exit_code = {"input-unreadable": 3, "input-syntax": 4, "input-data": 5}[code]
    e.file = str(path)
    return e


class Header:
    """What the reader needs of a LAS public header block."""

    def __init__(self, path):
        self.path = str(path)
        try:
            with open(path, "rb") as f:
                h = f.read(375)
            size = os.path.getsize(path)
        except OSError as e:
            raise _error("input-unreadable", f"{path}: cannot read the file ({e.strerror})", path)
        if len(h) < 227 or h[:4] != b"LASF":
            raise _error("input-syntax", f"{path}: not a LAS file (no 'LASF' signature)", path)
        self.version = (h[24], h[25])
        self.offset = struct.unpack_from("<I", h, 96)[0]
        fmt = h[104]
        if fmt & 0xC0:
            raise _error("input-syntax", f"{path}: a compressed (LAZ) point format {fmt}; sfit "
                         "reads uncompressed LAS only (decompress it first, e.g. with laszip)",
                         path)
        if fmt > 10:
            raise _error("input-syntax", f"{path}: unknown LAS point format {fmt}", path)
        self.format = fmt
        self.record = struct.unpack_from("<H", h, 105)[0]
        need = 20 if fmt < 6 else 30
        if self.record < need:
            raise _error("input-syntax", f"{path}: point records of {self.record} bytes, "
                         f"format {fmt} needs at least {need}", path)
        count = struct.unpack_from("<I", h, 107)[0]
        if self.version >= (1, 4) and len(h) >= 255 and count == 0:
            count = struct.unpack_from("<Q", h, 247)[0]
        self.scale = np.array(struct.unpack_from("<3d", h, 131))
        self.shift = np.array(struct.unpack_from("<3d", h, 155))
        if not np.all(np.isfinite(self.scale)) or np.any(self.scale == 0) or \
                not np.all(np.isfinite(self.shift)):
            raise _error("input-data", f"{path}: scale factors {self.scale.tolist()} or offsets "
                         f"{self.shift.tolist()} are not usable", path)
        have = max(0, (size - self.offset) // self.record) if self.offset <= size else 0
        if have < count:
            raise _error("input-syntax", f"{path}: the header promises {count} points, the file "
                         f"holds {have} (truncated?)", path)
        self.count = int(count)

    def records(self, first, count):
        """Records first ... first + count - 1 as a memory map of raw bytes (count, record)."""
        return np.memmap(self.path, dtype=np.uint8, mode="r",
                         offset=self.offset + first * self.record, shape=(count, self.record))

    def flags(self, rec):
        """(scan direction, edge of flight line) of the records, as booleans."""
        b = rec[:, 14] if self.format < 6 else rec[:, 15]
        return (b & 0x40) != 0, (b & 0x80) != 0


def _breaks(header, first, count):
    """For points first ... first + count - 1: whether a new scan line starts at each (the
    first point of the file starts none; the point before `first` is read for the others)."""
    lo = max(0, first - 1)
    rec = header.records(lo, first + count - lo)
    direction, edge = header.flags(rec)
    b = np.zeros(len(rec), dtype=bool)
    b[1:] = edge[:-1] | (direction[1:] != direction[:-1])
    return b[first - lo:]


def _xyz(header, rec):
    out = np.empty((len(rec), 3))
    for a in range(3):
        raw = np.ascontiguousarray(rec[:, 4 * a:4 * a + 4]).view("<i4")[:, 0]
        out[:, a] = raw * header.scale[a] + header.shift[a]
    return out


def scan_lines(path, chunk_points):
    """How to read `path` in pieces: (reference, [(first, count, lines)]). Each piece starts at
    a scan line and holds whole lines, at most chunk_points points unless one line is longer;
    `lines` is the number of scan lines in it. `reference` is the direction of the file's first
    line (its last point minus its first), which read_points() turns every line to. Refuses a
    file without scan-line flags."""
    h = Header(path)
    if h.count == 0:
        return np.zeros(3), []
    rec = h.records(0, h.count)
    direction, edge = h.flags(rec)
    if not (direction.any() or edge.any()):
        raise _error("input-data", f"{path}: no point sets the scan direction or edge-of-flight-"
                     "line flag, so the file gives no scan lines; pass the points with their rows "
                     "(sfit.dask.fit(points, rows=...))", path)
    b = np.zeros(h.count, dtype=bool)
    b[1:] = edge[:-1] | (direction[1:] != direction[:-1])
    starts = np.concatenate([[0], np.flatnonzero(b), [h.count]])
    first_line = _xyz(h, rec[[0, starts[1] - 1]])
    pieces = []
    k = 0
    while k < len(starts) - 1:
        m = k + 1  # whole lines while they fit (at least one)
        while m < len(starts) - 1 and starts[m + 1] - starts[k] <= chunk_points:
            m += 1
        pieces.append((int(starts[k]), int(starts[m] - starts[k]), m - k))
        k = m
    return first_line[1] - first_line[0], pieces


def read_points(path, first, count, row_offset, reference):
    """Points first ... first + count - 1 of `path` (whole scan lines, from scan_lines()) as
    (count, 4): x, y, z in the file's units (scale and offset applied) and the scan line counted
    from `row_offset`. A line that runs against `reference` (the oscillating mirror's way back)
    is reversed, so every row runs the same way, as the in-memory fit orients them."""
    h = Header(path)
    xyz = _xyz(h, h.records(first, count))
    b = _breaks(h, first, count)
    b[0] = False
    rows = row_offset + np.cumsum(b)
    for s, e in zip(np.concatenate([[0], np.flatnonzero(b)]),
                    np.concatenate([np.flatnonzero(b), [count]])):
        if np.dot(xyz[e - 1] - xyz[s], reference) < 0:
            xyz[s:e] = xyz[s:e][::-1].copy()
    return np.column_stack([xyz, rows.astype(float)])
