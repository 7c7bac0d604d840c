"""Height map files for the tests, written without an imaging library: PNG
(the chunks of the PNG specification, zlib-compressed scanlines with
filter 0) and raw little-endian uint16 files."""
import struct
import zlib

import numpy as np

SIGNATURE = b"\x89PNG\r\n\x1a\n"
GREY, RGB = 0, 2   # PNG colour types


def _chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def png_bytes(samples, bit_depth=16, colour=GREY, size=None):
    """A PNG of ``samples`` (rows x cols, or rows x cols x 3 for RGB), big-endian
    as PNG stores 16-bit samples. ``size`` (width, height) overrides the
    header's size, for a header that claims more than the data holds."""
    a = np.asarray(samples)
    height, width = size[::-1] if size else a.shape[:2]
    dtype = ">u2" if bit_depth == 16 else "u1"
    rows = a.astype(dtype).reshape(a.shape[0], -1)
    raw = b"".join(b"\x00" + row.tobytes() for row in rows)
    header = struct.pack(">IIBBBBB", width, height, bit_depth, colour, 0, 0, 0)
    return SIGNATURE + _chunk(b"IHDR", header) + _chunk(b"IDAT", zlib.compress(raw)) + _chunk(b"IEND", b"")


def write_png(path, samples, **kw):
    with open(path, "wb") as f:
        f.write(png_bytes(samples, **kw))
    return str(path)


def write_raw(path, samples):
    """rows x cols samples as little-endian uint16, row after row."""
    with open(path, "wb") as f:
        f.write(np.asarray(samples).astype("<u2").tobytes())
    return str(path)


def heights_of(samples, scale, offset):
    """The grid a height map gives (service/scene/height_map_file.h): the file's first row at the largest y."""
    return offset + scale * (np.asarray(samples, dtype=np.float64)[::-1] / 65535.0)
