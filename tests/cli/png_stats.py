#!/usr/bin/env python3
"""Statistics of 8-bit RGB PNGs as steadylight writes them, in pure Python (zlib, no numpy):
`mean` the mean code value; `redness` the mean of R - (G + B) / 2 over the left and over the
right third of the image (where a red object is).

Usage: png_stats.py mean A.png | png_stats.py redness A.png
"""
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour == 2 and interlace == 0, "expected 8-bit RGB, not interlaced"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride, bpp = zlib.decompress(idat), width * 3, 3
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):  # undo the PNG row filters (PNG spec §9.2)
            a = line[i - bpp] if i >= bpp else 0
            b = previous[i]
            c = previous[i - bpp] if i >= bpp else 0
            if kind == 1: line[i] = (line[i] + a) & 255
            elif kind == 2: line[i] = (line[i] + b) & 255
            elif kind == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        previous = line
    return width, height, b"".join(rows)


if __name__ == "__main__":
    if sys.argv[1:2] == ["mean"] and len(sys.argv) == 3:
        _, _, pixels = read_png(sys.argv[2])
        print(f"{sum(pixels) / len(pixels):.3f}")
    elif sys.argv[1:2] == ["redness"] and len(sys.argv) == 3:
        w, h, pixels = read_png(sys.argv[2])
        def redness(x0, x1):
            values = [pixels[3 * (y * w + x)] - (pixels[3 * (y * w + x) + 1] + pixels[3 * (y * w + x) + 2]) / 2
                      for y in range(h) for x in range(x0, x1)]
            return sum(values) / len(values)
        print(f"{redness(0, w // 3):.3f} {redness(w - w // 3, w):.3f}")
    else:
        sys.exit(__doc__)
