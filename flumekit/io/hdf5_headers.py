"""A netCDF-4 variable's description and attributes, decoded from the HDF5 file's bytes.

Opening a file with the netCDF library first reads megabytes of it to recognise its format,
and reading an attribute through the HDF5 library costs tens of microseconds (an open, a
type and a space query, a read); a folder of runs has thousands. A dataset's object header
holds its shape, type, where its values are and its attributes: up to eight whole, more in a
fractal heap indexed by a version 2 B-tree of their names (HDF5 file format specification
3.0, sections III.A.2, III.G, IV.A.1.b and IV.A.2). They are decoded here from the file's
bytes, the attributes into the values the netCDF4 library gives (``Variable.getncattr``),
after checking every block read against its checksum as the HDF5 library does. Only what
this module fully understands is decoded: it leaves the rest to the HDF5 library
(attributes of other types, such as lists of strings, or indexed by a deeper B-tree:
:attr:`Header.attributes` is None) or, for a header it cannot read, raises
:class:`Unsupported`, and the caller reads the file with the netCDF4 library.
"""

from __future__ import annotations

import struct
from typing import NamedTuple

import numpy as np

__all__ = ["SKIPPED", "Header", "Unsupported", "check_superblock", "checksums_match",
           "read_header", "root_attributes"]

#: attributes netCDF-4 keeps for its dimension scales, not a variable's attributes
SKIPPED = frozenset({"DIMENSION_LIST", "REFERENCE_LIST"})
#: (precision, exponent location, exponent size, mantissa size, bias) of the IEEE binary
#: formats by size in bytes, and the sign bit's location
_IEEE = {4: ((0, 32, 23, 8, 0, 23, 127), 31), 8: ((0, 64, 52, 11, 0, 52, 1023), 63)}
_UNDEFINED = 0xFFFFFFFFFFFFFFFF
#: lookup3's mix and final rounds on (a, b, c) = indices 0, 1, 2: (x, y, z, rotation) and
#: (x, y, rotation)
_MIX = ((0, 2, 1, 4), (1, 0, 2, 6), (2, 1, 0, 8), (0, 2, 1, 16), (1, 0, 2, 19), (2, 1, 0, 4))
_FINAL = ((2, 1, 14), (0, 2, 11), (1, 0, 25), (2, 1, 16), (0, 2, 4), (1, 0, 14), (2, 1, 24))


class Unsupported(Exception):
    """A header this module does not decode; read the file with the netCDF4 library."""


def check_superblock(head: bytes) -> None:
    """Check that a file starts as the netCDF library writes netCDF-4 files.

    Parameters
    ----------
    head : bytes
        The file's first 11 bytes (or more).

    Raises
    ------
    Unsupported
        Unless they are the HDF5 signature and a version 2 or 3 superblock with 8-byte
        addresses and lengths, which this module decodes.

    Examples
    --------
    >>> check_superblock(bytes([0x89]) + b"HDF" + bytes([13, 10, 26, 10, 2, 8, 8]))
    """
    if (head[:8] != b"\x89HDF\r\n\x1a\n" or head[8:9] not in (b"\x02", b"\x03")
            or head[9:11] != b"\x08\x08"):
        raise Unsupported("not an HDF5 file with a version 2 or 3 superblock of 8-byte offsets")


def _rot(x: np.ndarray, k: int) -> np.ndarray:
    return (x << np.uint32(k)) | (x >> np.uint32(32 - k))


def checksums_match(pieces: list[bytes]) -> np.ndarray:
    """Tell which metadata blocks match their checksum, all blocks at once.

    HDF5 ends each object header chunk with Bob Jenkins' lookup3 hash (``hashlittle``,
    initial value 0) of the bytes before it; the HDF5 library refuses a block that does not
    match, and so must a reader that decodes the bytes itself. The hash is sequential
    within a block, so it is computed for every block at once, word by word.

    Parameters
    ----------
    pieces : list of bytes
        Each block followed by its 4-byte little-endian checksum.

    Returns
    -------
    numpy.ndarray of bool
        One per piece.

    References
    ----------
    .. [1] B. Jenkins, "lookup3.c", 2006, http://burtleburtle.net/bob/c/lookup3.c
    .. [2] The HDF Group, "HDF5 File Format Specification Version 3.0", section II.B
       (checksums).

    Examples
    --------
    >>> text = b"Four score and seven years ago"
    >>> checksums_match([text + (0x17770551).to_bytes(4, "little"), text + bytes(4)])
    array([ True, False])
    """
    lengths = np.array([len(p) - 4 for p in pieces], dtype=np.int64)
    order = np.argsort(-lengths, kind="stable")  # the longest first: the live ones lead
    blocks = -(-lengths[order] // 12)
    width = 12 * max(int(blocks.max(initial=0)), 1)
    raw = b"".join(pieces[k][:-4] + bytes(width - len(pieces[k]) + 4) for k in order)
    words = np.frombuffer(raw, "<u4").reshape(len(pieces), width // 4).astype(np.uint32)
    stored = np.array([int.from_bytes(p[-4:], "little") for p in pieces], dtype=np.uint32)
    abc = np.empty((3, len(pieces)), np.uint32)
    abc[:] = ((0xDEADBEEF + lengths[order]) % 2**32).astype(np.uint32)
    for step in range(width // 12):
        live = int(np.count_nonzero(blocks > step))
        v = abc[:, :live]
        v += words[:live, 3 * step:3 * step + 3].T
        mixed = list(v.copy())
        for x, y, z, k in _MIX:  # x -= y; x ^= rot(y, k); y += z
            mixed[x] = (mixed[x] - mixed[y]) ^ _rot(mixed[y], k)
            mixed[y] = mixed[y] + mixed[z]
        final = list(v.copy())
        for x, y, k in _FINAL:  # x ^= y; x -= rot(y, k)
            final[x] = (final[x] ^ final[y]) - _rot(final[y], k)
        last = blocks[:live] == step + 1
        v[:] = np.where(last, final, mixed)
    match = np.empty(len(pieces), bool)
    match[order] = abc[2] == stored[order]
    return match


def _chunks(buffer, address: int, pieces: list):
    """Yield ``(type, flags, creation order, data offset, data size)`` of each message.

    The object header at ``address`` and its continuation chunks; each chunk's bytes with
    its checksum are appended to ``pieces``.
    """
    if bytes(buffer[address:address + 5]) != b"OHDR\x02":
        raise Unsupported("not a version 2 object header")
    flags = buffer[address + 5]
    at = address + 6 + (16 if flags & 0x20 else 0) + (4 if flags & 0x10 else 0)
    width = 1 << (flags & 0x03)
    size = int.from_bytes(buffer[at:at + width], "little")
    at += width
    ordered = bool(flags & 0x04)
    head = 6 if ordered else 4
    pieces.append(bytes(buffer[address:at + size + 4]))
    pending = [(at, at + size)]
    while pending:
        at, end = pending.pop(0)
        while end - at >= head:
            kind, length, mflags = struct.unpack_from("<BHB", buffer, at)
            order = struct.unpack_from("<H", buffer, at + 4)[0] if ordered else None
            data = at + head
            if kind == 0x10:  # continuation: (address, length) of the next chunk
                where, extent = struct.unpack_from("<QQ", buffer, data)
                if bytes(buffer[where:where + 4]) != b"OCHK":
                    raise Unsupported("a continuation chunk without its signature")
                pieces.append(bytes(buffer[where:where + extent]))
                pending.append((where + 4, where + extent - 4))
            else:
                yield kind, mflags, order, data, length
            at = data + length


def _space(buffer, at: int) -> tuple[int, ...] | None:
    """Decode a dataspace message: its dimensions, () when scalar, None when null."""
    version, rank, flags = buffer[at], buffer[at + 1], buffer[at + 2]
    if version == 1:
        kind, dims_at = (0 if rank == 0 else 1), at + 8
    elif version == 2:
        kind, dims_at = buffer[at + 3], at + 4
    else:
        raise Unsupported(f"dataspace message version {version}")
    if kind == 2:
        return None
    if kind not in (0, 1) or flags & 0x02:
        raise Unsupported("a dataspace with permutation indices or of unknown type")
    return struct.unpack_from(f"<{rank}Q", buffer, dims_at) if kind else ()


def _type(buffer, at: int) -> tuple[str, int]:
    """Decode a datatype message: ``("S" | "O" | "i" | "u" | "f", size in bytes)``.

    "S" a fixed-length string, "O" a variable-length one.
    """
    head, bits0, bits1, bits2, size = struct.unpack_from("<BBBBI", buffer, at)
    kind, version = head & 0x0F, head >> 4
    if version not in (1, 2, 3):
        raise Unsupported(f"datatype message version {version}")
    if kind == 9 and bits0 & 0x0F == 1 and bits1 in (0, 1):
        return "O", size  # variable-length string, ASCII or UTF-8
    if kind == 3 and bits0 & 0x0F in (0, 1) and bits0 >> 4 in (0, 1):
        return "S", size  # fixed length, null-terminated or null-padded, ASCII or UTF-8
    if kind == 0 and bits0 in (0x00, 0x08) and not bits1 | bits2 and size in (1, 2, 4, 8):
        if struct.unpack_from("<HH", buffer, at + 8) == (0, 8 * size):
            return ("i" if bits0 else "u"), size  # little-endian, two's complement
    if kind == 1 and size in _IEEE and bits0 == 0x20 and not bits2:
        props, sign = _IEEE[size]
        if bits1 == sign and struct.unpack_from("<HHBBBBI", buffer, at + 8) == props:
            return "f", size  # little-endian IEEE binary32 or binary64
    raise Unsupported(f"datatype class {kind} (bit fields {bits0:#x} {bits1:#x} {bits2:#x})")


def _value(name: str, kind: str, size: int, space, buffer, at: int):
    """Return an attribute's value as ``netCDF4.Variable.getncattr`` does."""
    if space is None or len(space) > 1:
        raise Unsupported(f"attribute '{name}': empty or of more than one dimension")
    if kind == "O":
        raise Unsupported(f"attribute '{name}': variable-length strings")
    if kind == "S":
        if space or name == "_FillValue":
            raise Unsupported(f"attribute '{name}': an array of strings or a character fill")
        text = bytes(buffer[at:at + size])
        return text.decode("utf-8", errors="replace").replace("\x00", "")
    count = space[0] if space else 1
    values = np.frombuffer(buffer, np.dtype(f"<{kind}{size}"), count, at)
    values = values.astype(np.dtype(f"{kind}{size}"))  # a copy in native byte order
    return values[0] if count == 1 else values


class Header(NamedTuple):
    """What an object header says of a dataset (:func:`read_header`)."""

    #: name -> value as the netCDF4 library gives it; None when not decoded here
    attributes: dict | None
    #: the dimensions' sizes; () for a scalar
    shape: tuple[int, ...]
    #: the values' type in memory; object for variable-length strings; None for a type not
    #: read here (fixed-length strings, compound, big-endian, ...)
    dtype: np.dtype | None
    #: (file offset [bytes], size [bytes]) of values stored contiguously, else None
    contiguous: tuple[int, int] | None


def _parse(buffer, address: int, decoded: dict | None, pieces: list):
    """Decode an object header: (attributes or None, shape, (kind, size), contiguous)."""
    decoded = {} if decoded is None else decoded
    found: list | None = []
    shape = kind_size = None
    contiguous: tuple[int, int] | None = None
    external = False
    for kind, mflags, order, at, length in _chunks(buffer, address, pieces):
        if kind == 0x01:
            shape = _space(buffer, at)
        elif kind == 0x03:
            try:
                kind_size = _type(buffer, at)
            except Unsupported:
                kind_size = ("", 0)  # not read here (a netCDF dimension's dummy type)
        elif kind == 0x07:
            external = True  # values in other files: left to the HDF5 library
        elif kind == 0x08 and buffer[at] in (3, 4) and buffer[at + 1] == 1:
            contiguous = struct.unpack_from("<QQ", buffer, at + 2)
        elif kind == 0x15:  # attribute info: dense storage has a fractal heap address
            heap, names = struct.unpack_from("<QQ", buffer, at + (4 if buffer[at + 1] & 1 else 2))
            if heap != _UNDEFINED:
                try:
                    dense = _dense(buffer, heap, names, pieces)
                except Unsupported:
                    found = None  # for the HDF5 library to read
                    continue
                for order, at_, length_ in dense:
                    found = _collect(found, buffer, at_, length_, order, decoded)
                    if found is None:
                        break
        elif kind == 0x0C and found is not None:
            # a shared message is for the HDF5 library to read
            found = None if mflags & 0x02 else _collect(found, buffer, at, length, order,
                                                        decoded)
    if external or (contiguous is not None and contiguous[0] == _UNDEFINED):
        contiguous = None
    if found is not None:
        if all(order is not None for order, _ in found):
            found.sort(key=lambda x: x[0])
        found = {a[0]: _copy(a[1]) for _, a in found if a is not None}
    return found, shape, kind_size, contiguous


def root_attributes(buffer, decoded: dict | None = None, pieces: list | None = None):
    """Decode the root group's attributes (a netCDF file's global attributes).

    Parameters
    ----------
    buffer : bytes-like
        The file's bytes (a memory map), from its start, with a superblock
        :func:`check_superblock` accepts.
    decoded, pieces
        As for :func:`read_header`.

    Returns
    -------
    dict or None
        As :attr:`Header.attributes`.

    Examples
    --------
    >>> import mmap, tempfile
    >>> import h5py
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = f"{folder}/run.h5"
    ...     with h5py.File(path, "w", libver="latest") as h:
    ...         h.attrs["title"] = np.bytes_(b"run 1")
    ...     with open(path, "rb") as f, mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ) as m:
    ...         print(root_attributes(m))
    {'title': 'run 1'}
    """
    checked_here = pieces is None
    pieces = [] if pieces is None else pieces
    (address,) = struct.unpack_from("<Q", buffer, 36)  # in a version 2 or 3 superblock
    found = _parse(buffer, address, decoded, pieces)[0]
    if checked_here and not checksums_match(pieces).all():
        raise Unsupported("an object header does not match its checksum")
    return found


def read_header(buffer, address: int, decoded: dict | None = None,
                pieces: list | None = None) -> Header:
    """Decode a dataset's object header: its attributes, shape, type and where its values are.

    Parameters
    ----------
    buffer : bytes-like
        The file's bytes (a memory map), from its start.
    address : int
        The object header's address in the file [bytes].
    decoded : dict, optional
        Attribute messages already decoded (their bytes -> (name, value)), filled in here:
        the runs of a stage repeat most of their attributes byte for byte, and a dict look-up
        is cheaper than decoding.
    pieces : list, optional
        Where to append the header's chunks with their checksums, for the caller to check
        those of many headers at once (:func:`checksums_match`) before it trusts what is
        returned. Without it they are checked here.

    Returns
    -------
    Header
        The attributes in their creation order, as the netCDF4 library gives them (a
        string, a NumPy scalar, or a 1-D array for several values), the netCDF-4
        bookkeeping attributes included (``_Netcdf4Dimid``, ``CLASS``, ...) except the
        dimension scales' reference lists (``DIMENSION_LIST``, ``REFERENCE_LIST``); None
        when one is not decoded here (a list of strings, a shared message, about thirty
        attributes or more), for the HDF5 library to read.

    Raises
    ------
    Unsupported
        For an object that is not a dataset, a header or an attribute this module does not
        decode, or (without ``pieces``) a header that does not match its checksum.

    Examples
    --------
    >>> import mmap, tempfile
    >>> import h5py
    >>> with tempfile.NamedTemporaryFile(suffix=".h5") as f:
    ...     with h5py.File(f.name, "w", libver="latest") as h:
    ...         h.create_dataset("x", data=[1.0, 2.0]).attrs["units"] = np.bytes_(b"m")
    ...     with h5py.File(f.name, "r") as h, open(f.name, "rb") as raw:
    ...         at = h.id.links.get_info(b"x").u  # the object header's address
    ...         with mmap.mmap(raw.fileno(), 0, access=mmap.ACCESS_READ) as m:
    ...             header = read_header(m, at)
    >>> header.attributes, header.shape, header.dtype
    ({'units': 'm'}, (2,), dtype('float64'))
    """
    checked_here = pieces is None
    pieces = [] if pieces is None else pieces
    found, shape, kind_size, contiguous = _parse(buffer, address, decoded, pieces)
    if checked_here and not checksums_match(pieces).all():
        raise Unsupported("an object header does not match its checksum")
    if shape is None or kind_size is None:
        raise Unsupported("not a dataset")
    kind, size = kind_size
    dtype = (None if kind in ("", "S") else np.dtype(object) if kind == "O"
             else np.dtype(f"{kind}{size}"))
    return Header(found, shape, dtype, contiguous)


def _collect(found: list | None, buffer, at: int, length: int, order, decoded: dict):
    """Append the attribute message at ``at`` to ``found``; None if it is not decoded here."""
    if found is None:
        return None
    key = bytes(buffer[at:at + length])
    try:
        if key not in decoded:
            decoded[key] = _attribute(buffer, at)
    except Unsupported:
        return None  # for the HDF5 library to read
    found.append((order, decoded[key]))
    return found


def _dense(buffer, heap: int, btree: int, pieces: list) -> list[tuple[int, int, int]]:
    """Locate the attributes an object stores densely: (creation order, address, size).

    Their messages are objects of a fractal heap, found through the records of a version 2
    B-tree indexing their names (HDF5 file format specification 3.0, sections III.G "Fractal
    Heap" and III.A.2 "Version 2 B-trees"); only a B-tree of one leaf node (fewer than
    about 30 attributes) and objects in the heap's direct blocks are located here.
    """
    if bytes(buffer[btree:btree + 6]) != b"BTHD\x00\x08":
        raise Unsupported("not a version 2 B-tree of attribute names")
    record, depth, root, count = struct.unpack_from("<HHxxQH", buffer, btree + 10)
    pieces.append(bytes(buffer[btree:btree + 38]))
    if depth != 0 or record != 17 or bytes(buffer[root:root + 6]) != b"BTLF\x00\x08":
        raise Unsupported("attribute names in a B-tree of more than one node")
    pieces.append(bytes(buffer[root:root + 6 + count * record + 4]))
    if bytes(buffer[heap:heap + 5]) != b"FRHP\x00":
        raise Unsupported("not a fractal heap")
    id_size, filters, flags, max_object = struct.unpack_from("<HHBI", buffer, heap + 5)
    huge, tiny = struct.unpack_from("<Q", buffer, heap + 86)[0], struct.unpack_from(
        "<Q", buffer, heap + 102)[0]
    width, start, max_direct, max_bits, _, block, rows = struct.unpack_from(
        "<HQQHHQH", buffer, heap + 110)
    pieces.append(bytes(buffer[heap:heap + 146]))
    if filters or huge or tiny or not flags & 0x02:
        raise Unsupported("a fractal heap with filters, huge or tiny objects or unchecked blocks")
    offset_bytes = -(-max_bits // 8)
    length_bytes = min((max_direct.bit_length() - 1 + 7) // 8,
                       (max_object.bit_length() - 1) // 8 + 1)
    # the direct blocks: (offset in the heap, size, address)
    if rows == 0:
        blocks = [(0, start, block)]
    else:
        if bytes(buffer[block:block + 5]) != b"FHIB\x00":
            raise Unsupported("not a fractal heap indirect block")
        direct_rows = (max_direct.bit_length() - start.bit_length()) + 2
        if rows > direct_rows:
            raise Unsupported("a fractal heap with indirect blocks below its root")
        at = block + 13 + offset_bytes
        addresses = struct.unpack_from(f"<{rows * width}Q", buffer, at)
        pieces.append(bytes(buffer[block:at + 8 * rows * width + 4]))
        blocks, offset = [], 0
        for k, address in enumerate(addresses):
            size = start * 2 ** max(k // width - 1, 0)
            if address != _UNDEFINED:
                blocks.append((offset, size, address))
            offset += size
    for _, size, address in blocks:
        if bytes(buffer[address:address + 5]) != b"FHDB\x00":
            raise Unsupported("not a fractal heap direct block")
        at = address + 13 + offset_bytes  # its checksum, computed with the field zeroed
        data = bytes(buffer[address:address + size])
        pieces.append(data[:at - address] + bytes(4) + data[at - address + 4:]
                      + data[at - address:at - address + 4])
    found = []
    for k in range(count):
        at = root + 6 + k * record
        ident = bytes(buffer[at:at + id_size])
        mflags, order = struct.unpack_from("<BI", buffer, at + 8)
        if ident[0] != 0 or mflags & 0x02:
            raise Unsupported("an attribute that is not a managed object of the heap")
        offset = int.from_bytes(ident[1:1 + offset_bytes], "little")
        length = int.from_bytes(ident[1 + offset_bytes:1 + offset_bytes + length_bytes],
                                "little")
        for start_, size, address in blocks:
            if start_ <= offset and offset + length <= start_ + size:
                found.append((order, address + offset - start_, length))
                break
        else:
            raise Unsupported("an attribute outside the heap's direct blocks")
    return found


def _copy(value):
    """Copy an array value: each variable's attributes are its own."""
    return value.copy() if isinstance(value, np.ndarray) else value


def _attribute(buffer, at: int):
    """Decode an attribute message: (name, value), None for a skipped one."""
    version, aflags, n_name, n_type, n_space = struct.unpack_from("<BBHHH", buffer, at)
    if version == 1:
        pad, name_at = 8, at + 8
    elif version in (2, 3):
        pad, name_at = 1, at + 8 + (version == 3)
    else:
        raise Unsupported(f"attribute message version {version}")
    if version > 1 and aflags & 0x03:
        raise Unsupported("an attribute with a shared datatype or dataspace")
    name = bytes(buffer[name_at:name_at + n_name]).rstrip(b"\x00").decode("utf-8")
    if name in SKIPPED:
        return None
    type_at = name_at + -(-n_name // pad) * pad
    space_at = type_at + -(-n_type // pad) * pad
    data_at = space_at + -(-n_space // pad) * pad
    return name, _value(name, *_type(buffer, type_at), _space(buffer, space_at), buffer,
                        data_at)
