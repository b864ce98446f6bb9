"""msgpack bytes from a peer -> Python objects, never allocating far beyond the bytes' size.

``msgpack.unpackb`` allocates an array's list as soon as it reads the array's count. Its
default limits only cap each count at the input's size, so nested forged counts add up: 100 kB
of array headers, each claiming 100 000 elements, made it reserve 80 MB (a 2 MB one, 16 GB)
before it noticed the data was short. The fast path here caps every array at FAST_PATH_LEN
elements (all the protocol sends, but for long parameter arrays), which bounds what forged
headers can reserve to well under a megabyte (maps are not reserved ahead: a dict grows as
it is filled); a message with a longer one is first
walked header by header, as the C++ codec does (bridge_plugin/src/protocol/parse.cpp), so
no count beyond the bytes left reaches msgpack.
"""

from __future__ import annotations

from typing import Any

import msgpack

#: The longest array the fast path accepts: a message with a longer one is checked first
#: (structure_problem), then unpacked with counts capped at its size.
FAST_PATH_LEN = 64
#: As the C++ codec's kMaxNesting: a message nests a handful of levels.
MAX_NESTING = 32

_SHORT = "the data ends early"


def unpack_bounded(data: bytes) -> Any:
    """One msgpack value with str keys or not (``strict_map_key=False``), str as str.
    Raises ValueError (or another msgpack exception) for anything that is not exactly one
    well-formed value; never reserves memory for a count the bytes cannot hold."""
    size = len(data)
    try:
        return _unpack(data, min(size, FAST_PATH_LEN))
    except ValueError as exc:
        if "exceeds max_array_len" not in str(exc):
            raise
    problem = structure_problem(data)
    if problem:
        raise ValueError(problem)
    return _unpack(data, size)


def _unpack(data: bytes, array_limit: int) -> Any:
    size = len(data)
    return msgpack.unpackb(
        data,
        raw=False,
        strict_map_key=False,
        max_array_len=array_limit,
        max_map_len=size,
        max_str_len=size,
        max_bin_len=size,
        max_ext_len=size,
    )


def _header(data: bytes, pos: int) -> tuple[int, int, int]:
    """(bytes the header and its payload take, elements that follow, 1 for a container)."""
    b = data[pos]
    if b <= 0x7F or b >= 0xE0 or b in (0xC0, 0xC2, 0xC3):  # fixint, nil, bool
        return 1, 0, 0
    if 0x80 <= b <= 0x8F:
        return 1, 2 * (b & 0x0F), 1
    if 0x90 <= b <= 0x9F:
        return 1, b & 0x0F, 1
    if 0xA0 <= b <= 0xBF:
        return 1 + (b & 0x1F), 0, 0
    fixed = _FIXED.get(b)
    if fixed is not None:
        return fixed, 0, 0
    sized = _SIZED.get(b)
    if sized is not None:  # str, bin, ext 8/16/32: a length, then (ext) a type byte
        width, extra = sized
        return 1 + width + extra + _length(data, pos + 1, width), 0, 0
    container = _CONTAINERS.get(b)
    if container is not None:
        width, per_element = container
        return 1 + width, per_element * _length(data, pos + 1, width), 1
    raise ValueError(f"byte 0x{b:02x} at offset {pos} is no msgpack type")


def _length(data: bytes, pos: int, width: int) -> int:
    if pos + width > len(data):
        raise ValueError(_SHORT)
    return int.from_bytes(data[pos : pos + width], "big")


# head byte -> total size (numbers, fixext)
_FIXED = {
    0xCA: 5, 0xCB: 9, 0xCC: 2, 0xCD: 3, 0xCE: 5, 0xCF: 9,
    0xD0: 2, 0xD1: 3, 0xD2: 5, 0xD3: 9,
    0xD4: 3, 0xD5: 4, 0xD6: 6, 0xD7: 10, 0xD8: 18,
}  # fmt: skip
# head byte -> (length width, bytes after the length before the payload)
_SIZED = {
    0xC4: (1, 0), 0xC5: (2, 0), 0xC6: (4, 0),  # bin
    0xC7: (1, 1), 0xC8: (2, 1), 0xC9: (4, 1),  # ext
    0xD9: (1, 0), 0xDA: (2, 0), 0xDB: (4, 0),  # str
}  # fmt: skip
# head byte -> (count width, elements per count)
_CONTAINERS = {0xDC: (2, 1), 0xDD: (4, 1), 0xDE: (2, 2), 0xDF: (4, 2)}


def structure_problem(data: bytes) -> str:
    """What is wrong with ``data`` as exactly one msgpack value, or "" when nothing is:
    read header by header without building anything, so that every count is checked against
    the bytes that remain before msgpack allocates for it."""
    size = len(data)
    open_levels: list[int] = []  # per open array or map: the elements it has left
    pending = 1  # the elements left to read, all levels together
    pos = 0
    while pending > 0:
        if pos >= size:
            return _SHORT
        try:
            taken, elements, container = _header(data, pos)
        except ValueError as exc:
            return str(exc)
        if taken > size - pos:
            return _SHORT
        pos += taken
        pending -= 1
        if open_levels:
            open_levels[-1] -= 1
        if container:
            if len(open_levels) >= MAX_NESTING:
                return f"arrays and maps nested deeper than {MAX_NESTING} levels"
            # Every element takes at least one byte: a count beyond the bytes left is forged.
            if pending + elements > size - pos:
                return f"{_SHORT}: {elements} elements declared with {size - pos} bytes left"
            pending += elements
            open_levels.append(elements)
        while open_levels and open_levels[-1] == 0:
            open_levels.pop()
    if pos != size:
        return f"{size - pos} extra bytes after the message"
    return ""
