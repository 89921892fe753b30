"""A check of MATLAB level-5 ``.mat`` files for the damage that crashes SciPy's reader.

SciPy's compiled reader (``scipy.io.loadmat``; ``_mio5_utils.pyx``, SciPy 1.17) looks the data
type of each numeric or character element up in a C array of 20 pointers without checking it:
an element whose type is unknown or not numeric (``miMATRIX``, the reserved 8, 10, 11, ≥ 19)
makes the process die of SIGSEGV/SIGBUS instead of raising. A damaged file produces such
elements easily, e.g. a flipped "complex" flag makes the reader take the next variable's tag for
the imaginary part. Cells and structures nested thousands deep would overflow its C stack.

:func:`mat5_problem` reads the file the way that reader does — the same elements in the same
order, their tags only, skipping the data — and reports the first element that would crash it.
Wherever SciPy would raise an ordinary exception instead, the check stops (SciPy's exception
becomes the one-line error of :func:`bearingsim.io.read_cwru_mat`).

The layout is that of *MATLAB MAT-File Format* (The MathWorks), "Level 5 MAT-File Format": a
128-byte header (version 0x0100, endian indicator ``IM``/``MI`` in bytes 126-127), then one
``miMATRIX`` element per variable, or an ``miCOMPRESSED`` element holding it zlib-compressed.
An element is an 8-byte tag (data type, byte count) and its data padded to 8 bytes, or a "small
data element": type and byte count (≤ 4) in the first 4 bytes, the data in the next 4. An array
is its flags (class, complex), dimensions and name, then by class: the real and imaginary parts
(numeric), row indices, column pointers and values (sparse), the characters (char), one
``miMATRIX`` per element (cell), field names and one ``miMATRIX`` per element and field
(structure; an object adds its class name).
"""

from __future__ import annotations

import math
import struct
import zlib
from typing import IO

__all__ = ["MAX_INFLATED_BYTES", "mat5_problem"]

#: the data types SciPy can read numeric or character data of (``mdtypes_template`` of
#: ``scipy.io.matlab._mio5_params``): miINT8 ... miUINT64, miUTF8/16/32
_NUMERIC = frozenset({1, 2, 3, 4, 5, 6, 7, 9, 12, 13, 16, 17, 18})
_MATRIX, _COMPRESSED = 14, 15
_CELL, _STRUCT, _OBJECT, _CHAR, _SPARSE, _FUNCTION, _OPAQUE = 1, 2, 3, 4, 5, 16, 17
_NUMERIC_CLASSES = range(6, 16)  # mxDOUBLE_CLASS ... mxUINT64_CLASS

#: largest decompressed size of one ``miCOMPRESSED`` variable [bytes]: 2 GiB, 270 M samples in
#: float64, 60 times the largest CWRU record; a larger one (a "zip bomb" of a few MB can claim
#: many GB) is refused
MAX_INFLATED_BYTES = 2 * 2**30

#: data kept to look at (dimensions, field names) [bytes]; longer data is skipped
_KEEP_BYTES = 2**20

#: cells and structures nested deeper than this are refused (SciPy reads them recursively in C)
MAX_DEPTH = 200


class _Stop(Exception):
    """SciPy raises an ordinary exception here: nothing further to check."""


class _Bad(Exception):
    """SciPy would crash here; the message says why."""


def mat5_problem(fh: IO[bytes], size: int) -> str | None:
    """What in the level-5 MAT file open in ``fh`` (``size`` bytes) would crash SciPy's reader,
    or ``None`` (also for files of other levels, which SciPy refuses or reads safely)."""
    fh.seek(0)
    head = fh.read(128)
    if len(head) < 128 or 0 in head[:4]:
        return None  # a level-4 file, or too short: SciPy's own checks refuse it cleanly
    order = {b"IM": "<", b"MI": ">"}.get(head[126:128])
    if order is None or struct.unpack(order + "H", head[124:126])[0] != 0x0100:
        return None  # not level 5 (v7.3 is HDF5): SciPy raises
    pos = 128
    try:
        while pos < size:
            fh.seek(pos)
            tag = fh.read(8)
            if len(tag) < 8:
                return None
            mdtype, nbytes = struct.unpack(order + "II", tag)
            if nbytes == 0:
                return None
            if mdtype == _COMPRESSED:
                reader = _Reader(_Inflated(fh.read(nbytes), pos), order)
                if reader.full_tag()[0] != _MATRIX:
                    return None
            elif mdtype == _MATRIX:
                reader = _Reader(_File(fh), order)
            else:
                return None
            reader.array(0)
            pos += 8 + nbytes
    except _Stop:
        return None
    except _Bad as exc:
        return str(exc)
    return None


class _File:
    """The file from its current position, as SciPy's reader sees it (reads past a variable's
    end go on into the next)."""

    def __init__(self, fh: IO[bytes]) -> None:
        self.fh = fh

    def where(self) -> str:
        return f"byte {self.fh.tell()}"

    def read(self, n: int) -> bytes:
        b = self.fh.read(n)
        if len(b) < n:
            raise _Stop
        return b

    def skip(self, n: int) -> None:
        here = self.fh.tell()
        self.fh.seek(0, 2)
        if here + n > self.fh.tell():
            raise _Stop
        self.fh.seek(here + n)


class _Inflated:
    """The inflated content of an ``miCOMPRESSED`` element, read forward in chunks (memory stays
    at a chunk; at most :data:`MAX_INFLATED_BYTES` are inflated)."""

    _CHUNK = 2**20

    def __init__(self, data: bytes, at: int) -> None:
        self.z = zlib.decompressobj()
        self.pending = data
        self.buf = b""
        self.pos = 0  # bytes of the inflated stream consumed
        self.at = at

    def where(self) -> str:
        return f"byte {self.pos} of the compressed variable at byte {self.at}"

    def _more(self) -> None:
        if self.pos > MAX_INFLATED_BYTES:
            raise _Bad(
                f"the compressed variable at byte {self.at} inflates to more than "
                f"{MAX_INFLATED_BYTES // 2**30} GiB"
            )
        if not self.pending:
            raise _Stop
        try:
            more = self.z.decompress(self.pending, self._CHUNK)
        except zlib.error:
            raise _Stop from None
        self.pending = self.z.unconsumed_tail
        if not more and not self.pending:
            raise _Stop
        self.buf += more

    def read(self, n: int) -> bytes:
        while len(self.buf) < n:
            self._more()
        out, self.buf = self.buf[:n], self.buf[n:]
        self.pos += n
        return out

    def skip(self, n: int) -> None:
        while n > len(self.buf):
            n -= len(self.buf)
            self.pos += len(self.buf)
            self.buf = b""
            self._more()
        self.buf = self.buf[n:]
        self.pos += n


class _Reader:
    """The element reads of SciPy's ``VarReader5``, on tags only."""

    def __init__(self, src: _File | _Inflated, order: str) -> None:
        self.src, self.order = src, order

    def full_tag(self) -> tuple[int, int]:  # cread_full_tag
        return struct.unpack(self.order + "II", self.src.read(8))

    def element(self, keep: bool = False, limit: int | None = None) -> tuple[int, int, bytes]:
        """read_element / read_element_into: (type, byte count, data if ``keep``)."""
        raw = self.src.read(8)
        first, count = struct.unpack(self.order + "II", raw)
        if first >> 16:  # small data element
            if first >> 16 > 4:
                raise _Stop
            return first & 0xFFFF, first >> 16, raw[4 : 4 + (first >> 16)]
        if limit is not None and count > limit:
            raise _Stop
        if keep and count <= _KEEP_BYTES:
            data = self.src.read(count)
        else:
            self.src.skip(count)
            data = b""
        pad = -count % 8
        if pad:
            try:
                self.src.skip(pad)
            except _Stop:
                pass  # SciPy seeks past the end; its next read raises
        return first, count, data

    def numeric(self, what: str) -> None:  # read_numeric; read_char when it has data
        where = self.src.where()
        mdtype, count, _ = self.element()
        if mdtype not in _NUMERIC and (what != "character data" or count):
            raise _Bad(f"the {what} at {where} is of the unknown data type {mdtype}")

    def int8_string(self, keep: bool = False) -> tuple[int, bytes]:  # read_int8_string
        mdtype, count, data = self.element(keep)
        if mdtype not in (1, 16):
            raise _Stop
        return count, data

    def int32s(self, limit: int) -> tuple[int, ...]:  # read_into_int32s
        mdtype, count, data = self.element(True, limit)
        if mdtype not in (5, 6):
            raise _Stop
        values = struct.unpack(f"{self.order}{count // 4}i", data[: count // 4 * 4])
        if mdtype == 6 and any(v < 0 for v in values):
            raise _Stop
        return values

    def matrix(self, depth: int) -> None:  # read_mi_matrix
        mdtype, count = self.full_tag()
        if mdtype != _MATRIX:
            raise _Stop
        if count:
            self.array(depth)

    def array(self, depth: int) -> None:
        """read_header and array_from_header."""
        if depth > MAX_DEPTH:
            raise _Bad(f"cells or structures nested deeper than {MAX_DEPTH} at {self.src.where()}")
        self.src.skip(8)  # the tag of the array flags, not looked at
        flags = struct.unpack(self.order + "II", self.src.read(8))[0]
        mclass, complex_ = flags & 0xFF, flags >> 11 & 1
        if mclass == _OPAQUE:  # name; then read_opaque: type system, class name, the matrix
            for _ in range(3):
                self.int8_string()
            self.matrix(depth + 1)
            return
        dims = self.int32s(128)
        self.int8_string()  # name
        if mclass in _NUMERIC_CLASSES:
            self.numeric("real part")
            if complex_:
                self.numeric("imaginary part")
        elif mclass == _SPARSE:
            self.numeric("row indices")
            self.numeric("column pointers")
            self.numeric("values")
            if complex_:
                self.numeric("imaginary values")
        elif mclass == _CHAR:
            self.numeric("character data")
        elif mclass == _CELL:
            for _ in range(_count(dims)):
                self.matrix(depth + 1)
        elif mclass in (_STRUCT, _OBJECT):
            if mclass == _OBJECT:
                self.int8_string()  # class name
            length = self.int32s(4)
            if len(length) != 1 or length[0] == 0:
                raise _Stop
            count, names = self.int8_string(keep=True)
            n_names = count // length[0]
            for i in range(max(n_names, 0) if names else 0):  # PyUnicode_FromString of each
                try:
                    names[i * length[0] :].split(b"\0", 1)[0].decode()
                except UnicodeDecodeError:
                    raise _Stop from None
            for _ in range(_count(dims) * max(n_names, 0)):
                self.matrix(depth + 1)
        elif mclass == _FUNCTION:
            self.matrix(depth + 1)


def _count(dims: tuple[int, ...]) -> int:
    """Elements of an array of ``dims`` (a negative dimension: NumPy refuses the array)."""
    if any(d < 0 for d in dims):
        raise _Stop
    return math.prod(dims)
