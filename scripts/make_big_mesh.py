#!/usr/bin/env python3
"""Writes a big textured glTF scene for the README's load-time, memory and frame-time figures:
a procedural terrain of N x N quads (2 N^2 triangles; N = 1024 gives 2,093,058), rolling hills
with smooth normals, TEXCOORD_0 tiled 16 times over a 256 x 256 PNG (made here, stored in the
.glb), lit by an emissive panel above it and seen by a perspective camera. Pure Python: no
Blender or numpy needed.

Usage: make_big_mesh.py OUT.glb [--quads N]
"""
import array
import json
import math
import struct
import sys
import zlib


def png(width, height, pixel):
    """An 8-bit RGB PNG from pixel(x, y) -> (r, g, b)."""
    raw = bytearray()
    for y in range(height):
        raw.append(0)
        for x in range(width):
            raw.extend(pixel(x, y))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(bytes(raw), 6)) + chunk(b"IEND", b""))


def tile(x, y):
    on = ((x // 32) + (y // 32)) % 2
    g = 150 + int(40 * math.sin(x * 0.3) * math.sin(y * 0.3))
    return (g, 110, 60) if on else (70, g // 2 + 40, 60)


def terrain(n, size=20.0):
    """Positions, normals, uvs (float32 arrays) and uint32 indices of an n x n quad height field."""
    def height(u, v):
        return 0.6 * math.sin(u * 9.0) * math.cos(v * 7.0) + 0.25 * math.sin(u * 31.0 + v * 17.0)

    positions, normals, uvs = array.array("f"), array.array("f"), array.array("f")
    step = 1.0 / n
    for j in range(n + 1):
        v = j * step
        for i in range(n + 1):
            u = i * step
            h = height(u, v)
            positions.extend((size * (u - 0.5), h, size * (v - 0.5)))
            dhdu = (height(u + 1e-3, v) - height(u - 1e-3, v)) / 2e-3 / size
            dhdv = (height(u, v + 1e-3) - height(u, v - 1e-3)) / 2e-3 / size
            length = math.sqrt(dhdu * dhdu + 1 + dhdv * dhdv)
            normals.extend((-dhdu / length, 1 / length, -dhdv / length))
            uvs.extend((u * 16, v * 16))
    indices = array.array("I")
    row = n + 1
    for j in range(n):
        for i in range(n):
            a = j * row + i
            indices.extend((a, a + row, a + 1, a + 1, a + row, a + row + 1))
    return positions, normals, uvs, indices


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    n = int(argv[argv.index("--quads") + 1]) if "--quads" in argv else 1024
    positions, normals, uvs, indices = terrain(n)
    image = png(256, 256, tile)
    # The light: a 4 m x 4 m panel 8 m up, facing down.
    panel = array.array("f", [-2, 8, -2, 2, 8, -2, 2, 8, 2, -2, 8, 2])
    panel_indices = array.array("I", [0, 1, 2, 0, 2, 3])
    blobs = [positions.tobytes(), normals.tobytes(), uvs.tobytes(), indices.tobytes(), panel.tobytes(),
             panel_indices.tobytes(), image]
    targets = [34962, 34962, 34962, 34963, 34962, 34963, None]  # ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER
    views, offset = [], 0
    binary = bytearray()
    for blob, target in zip(blobs, targets):
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob)})
        if target:
            views[-1]["target"] = target
        binary += blob
        while len(binary) % 4:
            binary.append(0)
        offset = len(binary)
    count = (n + 1) * (n + 1)
    gltf = {
        "asset": {"version": "2.0", "generator": "steadylight scripts/make_big_mesh.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0, "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"name": "Terrain", "mesh": 0}, {"name": "Panel", "mesh": 1},
                  {"name": "Camera", "camera": 0, "translation": [0, 6, 12],
                   "rotation": [-0.2588190, 0, 0, 0.9659258]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "aspectRatio": 4 / 3, "znear": 0.1}}],
        "buffers": [{"byteLength": len(binary)}],
        "bufferViews": views,
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3",
             "min": [min(positions[0::3]), min(positions[1::3]), min(positions[2::3])],
             "max": [max(positions[0::3]), max(positions[1::3]), max(positions[2::3])]},
            {"bufferView": 1, "componentType": 5126, "count": count, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": count, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
            {"bufferView": 4, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-2, 8, -2], "max": [2, 8, 2]},
            {"bufferView": 5, "componentType": 5125, "count": 6, "type": "SCALAR"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]},
                   {"primitives": [{"attributes": {"POSITION": 4}, "indices": 5, "material": 1}]}],
        "materials": [{"name": "Ground", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0,
                                                                   "roughnessFactor": 0.6}},
                      {"name": "Panel", "emissiveFactor": [1, 1, 1], "doubleSided": False,
                       "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 20}},
                       "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"wrapS": 10497, "wrapT": 10497}],
        "images": [{"bufferView": 6, "mimeType": "image/png"}],
    }
    text = json.dumps(gltf).encode()
    while len(text) % 4:
        text += b" "
    with open(argv[1], "wb") as out:
        out.write(struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + 8 + len(binary)))
        out.write(struct.pack("<II", len(text), 0x4E4F534A) + text)
        out.write(struct.pack("<II", len(binary), 0x004E4942) + bytes(binary))


if __name__ == "__main__":
    main(sys.argv)
