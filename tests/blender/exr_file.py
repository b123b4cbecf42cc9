"""Reads the channels of a scanline OpenEXR file, uncompressed or ZIP/ZIPS, half or float: what
steadylight and Blender write here. The standard library alone (Python 3 as Debian has it,
without OpenImageIO), for the add-on's tests.

    channels = read_exr("frame.exr")   # {"ViewLayer.Combined.R": [floats, row by row from the top], ...}
"""
import struct
import zlib

COMPRESSION = {0: "none", 2: "zips", 3: "zip"}
PIXEL_TYPE = {1: ("e", 2), 2: ("f", 4)}  # half, float (uint is not written here)


def read_header(data):
    if data[:4] != b"\x76\x2f\x31\x01":
        raise ValueError("not an OpenEXR file")
    pos, header = 8, {}
    while data[pos] != 0:
        name_end = data.index(b"\0", pos)
        type_end = data.index(b"\0", name_end + 1)
        name, kind = data[pos:name_end].decode(), data[name_end + 1:type_end].decode()
        (size,) = struct.unpack_from("<i", data, type_end + 1)
        value = data[type_end + 5:type_end + 5 + size]
        header[name] = (kind, value)
        pos = type_end + 5 + size
    return header, pos + 1


def channel_list(value):
    channels, pos = [], 0
    while value[pos] != 0:
        end = value.index(b"\0", pos)
        (pixel_type,) = struct.unpack_from("<i", value, end + 1)
        channels.append((value[pos:end].decode(), pixel_type))
        pos = end + 1 + 16
    return channels


def undo_zip(raw):
    """OpenEXR's ZIP: deflate of the bytes split in two interleaved halves, delta-coded."""
    data = bytearray(zlib.decompress(raw))
    for i in range(1, len(data)):
        data[i] = (data[i - 1] + data[i] - 128) & 0xFF
    half = (len(data) + 1) // 2
    out = bytearray(len(data))
    out[0::2], out[1::2] = data[:half], data[half:]
    return bytes(out)


def read_exr(path):
    with open(path, "rb") as f:
        data = f.read()
    header, pos = read_header(data)
    channels = channel_list(header["channels"][1])
    compression = COMPRESSION.get(header["compression"][1][0])
    if compression is None:
        raise ValueError(f"{path}: compression {header['compression'][1][0]} is not read here")
    x0, y0, x1, y1 = struct.unpack("<4i", header["dataWindow"][1])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    lines_per_block = 16 if compression == "zip" else 1
    blocks = (height + lines_per_block - 1) // lines_per_block
    offsets = struct.unpack_from(f"<{blocks}Q", data, pos)
    values = {name: [] for name, _ in channels}
    for offset in offsets:
        y, size = struct.unpack_from("<ii", data, offset)
        raw = data[offset + 8:offset + 8 + size]
        lines = min(lines_per_block, y1 - y + 1)
        expected = lines * width * sum(PIXEL_TYPE[t][1] for _, t in channels)
        block = raw if compression == "none" or size == expected else undo_zip(raw)
        at = 0
        for _ in range(lines):
            for name, pixel_type in channels:
                code, bytes_per = PIXEL_TYPE[pixel_type]
                values[name].extend(struct.unpack_from(f"<{width}{code}", block, at))
                at += width * bytes_per
    return values, (width, height)
