"""A minimal reader of the protobuf wire format (proto2 binary encoding),
and the writer of one field, for tests and benchmarks that make snapshots.

The viewer needs a few fields of the server's snapshot file (shapes, masses,
joints; service/proto/snapshot.proto). Reading the wire format directly keeps
the client free of protoc and of a protobuf runtime whose version would have
to match the generated code.
"""
import struct

import numpy as np

VARINT, FIXED64, LENGTH, FIXED32 = 0, 1, 2, 5


def _varint(data, pos):
    result = shift = 0
    while True:
        if pos >= len(data):
            raise ValueError("truncated varint")
        b = data[pos]
        pos += 1
        result |= (b & 0x7F) << shift
        if not b & 0x80:
            return result, pos
        shift += 7


def fields(data):
    """Yields (field number, wire type, value) of one message: an int for
    varints, 8 or 4 raw bytes for fixed fields, bytes for length-delimited ones."""
    data = memoryview(data).tobytes() if not isinstance(data, bytes) else data
    pos = 0
    while pos < len(data):
        key, pos = _varint(data, pos)
        number, wire = key >> 3, key & 7
        if wire == VARINT:
            value, pos = _varint(data, pos)
        elif wire == FIXED64:
            value, pos = data[pos:pos + 8], pos + 8
        elif wire == FIXED32:
            value, pos = data[pos:pos + 4], pos + 4
        elif wire == LENGTH:
            size, pos = _varint(data, pos)
            value, pos = data[pos:pos + size], pos + size
        else:
            raise ValueError("unsupported wire type %d" % wire)
        yield number, wire, value


def signed(value):
    """An int64 field's varint as a Python int (two's complement)."""
    return value - (1 << 64) if value >= 1 << 63 else value


def doubles(wire, value):
    """The doubles of a repeated double field's occurrence (packed or not)."""
    if wire == FIXED64:
        return list(struct.unpack("<d", value))
    return list(struct.unpack("<%dd" % (len(value) // 8), value))


def ints(wire, value):
    """The ints of a repeated int32 field's occurrence (packed or not)."""
    if wire == VARINT:
        return [signed(value)]
    out, pos = [], 0
    while pos < len(value):
        v, pos = _varint(value, pos)
        out.append(signed(v))
    return out


def varint_array(value):
    """The varints of a packed field as an int64 array, decoded with numpy: a
    100,000-triangle mesh's indices take 0.17 s one varint at a time. A
    varint ends at its first byte below 0x80; its value is the sum of its
    bytes' low seven bits, each shifted 7 bits more than the last."""
    b = np.frombuffer(value, dtype=np.uint8)
    if b.size == 0:
        return np.zeros(0, dtype=np.int64)
    ends = np.flatnonzero(b < 0x80)
    if ends.size == 0 or ends[-1] != b.size - 1:
        raise ValueError("truncated varint")
    starts = np.concatenate(([0], ends[:-1] + 1))
    lengths = ends - starts + 1
    if lengths.max() > 9:   # a negative int32 takes 10 bytes: past int64, read them one at a time
        return np.array(ints(LENGTH, value), dtype=np.int64)
    shift = (7 * (np.arange(b.size) - np.repeat(starts, lengths))).astype(np.int64)
    return np.add.reduceat((b & 0x7F).astype(np.int64) << shift, starts)


def _array(kind, wire, value):
    """One occurrence of a repeated field read as a numpy array (kinds
    "double_array", "int_array"): packed, or one unpacked element."""
    if kind == "double_array":
        if len(value) % 8:
            raise ValueError("packed doubles of %d bytes" % len(value))
        return np.frombuffer(value, dtype="<f8")
    if wire == VARINT:
        return np.array([signed(value)], dtype=np.int64)
    return varint_array(value)


def parse(data, schema):
    """A dict of one message's fields: ``schema`` maps field number ->
    (name, kind, repeated) with kind "double", "int", "string", "bool",
    "double_array", "int_array" or a nested schema dict. Repeated scalars
    are flat lists (packed or not); the array kinds, for the fields that
    hold large surfaces, are one numpy array (float64, int64)."""
    out, arrays = {}, {}
    for number, wire, value in fields(data):
        if number not in schema:
            continue
        name, kind, repeated = schema[number]
        if kind in ("double_array", "int_array"):
            arrays.setdefault(name, []).append(_array(kind, wire, value))
            continue
        if kind == "double":
            items = doubles(wire, value)
        elif kind == "int":
            items = ints(wire, value)
        elif kind == "bool":
            items = [bool(value)]
        elif kind == "string":
            items = [value.decode("utf-8", "replace")]
        else:
            items = [parse(value, kind)]
        if repeated:
            out.setdefault(name, []).extend(items)
        else:
            out[name] = items[-1]
    for name, chunks in arrays.items():
        out[name] = np.concatenate(chunks)
    return out


def varint_bytes(value):
    """A non-negative int as a varint."""
    out = bytearray()
    while True:
        low, value = value & 0x7F, value >> 7
        out.append(low | (0x80 if value else 0))
        if not value:
            return bytes(out)


def field(number, wire, value):
    """One field on the wire: VARINT an int, FIXED64 a double, LENGTH bytes."""
    key = varint_bytes(number << 3 | wire)
    if wire == VARINT:
        return key + varint_bytes(value)
    if wire == FIXED64:
        return key + struct.pack("<d", value)
    return key + varint_bytes(len(value)) + value
