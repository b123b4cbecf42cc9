#!/usr/bin/env python3
"""Writes a small .glb laid out the way Blender's glTF 2.0 exporter (io_scene_gltf2, Blender 4.x,
default settings) writes one, for tests of `steadylight render FILE.glb` without Blender:

- binary container: JSON chunk padded with spaces, BIN chunk padded with zeros, one buffer;
- Blender's Z-up world turned into glTF's Y-up (+Y Up on): Blender (x, y, z) -> glTF (x, z, -y);
- a camera (50 mm lens, 36 mm sensor, 16:9, so yfov from the horizontal fov and aspectRatio);
- a point lamp as KHR_lights_punctual in the default "Standard" lighting mode: W / 4pi * 683 cd;
- meshes with POSITION (min/max), NORMAL, TEXCOORD_0, one primitive per material, uint16 indices
  (uint32 when a mesh has more than 65535 vertices; the floor uses them here to cover both);
- Principled BSDF materials: baseColorFactor, metallicFactor 0, roughnessFactor 0.5,
  doubleSided (backface culling off), Emission x Strength as emissiveFactor plus
  KHR_materials_emissive_strength when the strength is above 1;
- an action sampled at every frame (30 fps, frames 1-24) as LINEAR translation and rotation
  channels, key times frame / fps in seconds;
- custom properties as `extras`.

Usage: make_blender_glb.py OUT.glb
"""
import json
import math
import struct
import sys

FPS = 30
FRAMES = range(1, 25)


class Builder:
    def __init__(self):
        self.bin = bytearray()
        self.gltf = {
            "asset": {"generator": "Khronos glTF Blender I/O v4.1.63", "version": "2.0"},
            "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength"],
            "extensions": {"KHR_lights_punctual": {"lights": []}},
            "scene": 0, "scenes": [{"name": "Scene", "nodes": []}],
            "nodes": [], "meshes": [], "materials": [], "cameras": [], "animations": [],
            "accessors": [], "bufferViews": [], "buffers": [],
        }

    def accessor(self, fmt, values, type_, component, target=None, minmax=False):
        while len(self.bin) % 4:
            self.bin.append(0)
        data = b"".join(struct.pack("<" + fmt, *v) if isinstance(v, tuple) else struct.pack("<" + fmt, v)
                        for v in values)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target:
            view["target"] = target
        self.bin += data
        self.gltf["bufferViews"].append(view)
        acc = {"bufferView": len(self.gltf["bufferViews"]) - 1, "componentType": component,
               "count": len(values), "type": type_}
        if minmax:
            acc["min"] = [min(v[i] for v in values) for i in range(3)]
            acc["max"] = [max(v[i] for v in values) for i in range(3)]
        self.gltf["accessors"].append(acc)
        return len(self.gltf["accessors"]) - 1

    def material(self, name, color, emission=None, strength=1.0):
        m = {"name": name, "doubleSided": True,
             "pbrMetallicRoughness": {"baseColorFactor": color + [1.0], "metallicFactor": 0, "roughnessFactor": 0.5}}
        if emission:
            m["emissiveFactor"] = emission
            if strength > 1:
                m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
        self.gltf["materials"].append(m)
        return len(self.gltf["materials"]) - 1

    def primitive(self, positions, normals, indices, material, wide_indices=False):
        uvs = [(0.5 + p[0] * 0.1, 0.5 + p[2] * 0.1) for p in positions]
        return {"attributes": {"POSITION": self.accessor("fff", positions, "VEC3", 5126, 34962, minmax=True),
                               "NORMAL": self.accessor("fff", normals, "VEC3", 5126, 34962),
                               "TEXCOORD_0": self.accessor("ff", uvs, "VEC2", 5126, 34962)},
                "indices": self.accessor("I" if wide_indices else "H", indices, "SCALAR",
                                         5125 if wide_indices else 5123, 34963),
                "material": material}

    def mesh(self, name, primitives):
        self.gltf["meshes"].append({"name": name, "primitives": primitives})
        return len(self.gltf["meshes"]) - 1

    def node(self, node):
        self.gltf["nodes"].append(node)
        self.gltf["scenes"][0]["nodes"].append(len(self.gltf["nodes"]) - 1)
        return len(self.gltf["nodes"]) - 1

    def write(self, path):
        self.gltf["buffers"] = [{"byteLength": len(self.bin)}]
        text = json.dumps(self.gltf, separators=(",", ":")).encode()
        text += b" " * (-len(text) % 4)
        binary = bytes(self.bin) + b"\0" * (-len(self.bin) % 4)
        total = 12 + 8 + len(text) + 8 + len(binary)
        with open(path, "wb") as out:
            out.write(struct.pack("<4sII", b"glTF", 2, total))
            out.write(struct.pack("<I4s", len(text), b"JSON") + text)
            out.write(struct.pack("<I4s", len(binary), b"BIN\0") + binary)


def y_up(x, y, z):
    """Blender's Z-up coordinates in glTF's Y-up frame, as the exporter's +Y Up option does."""
    return (x, z, -y)


def plane(half_x, half_y):
    """A Blender plane in its local XY (normal +Z), already in glTF axes: y up."""
    corners = [(-half_x, -half_y), (half_x, -half_y), (half_x, half_y), (-half_x, half_y)]
    return [y_up(x, y, 0) for x, y in corners], [y_up(0, 0, 1)] * 4, [0, 1, 2, 0, 2, 3]


def cube_halves():
    """Blender's default cube (size 2) with its six faces in two material slots, as the exporter
    splits a mesh into one primitive per material: three faces each."""
    faces = []
    for axis in range(3):
        for sign in (-1, 1):
            normal = [0, 0, 0]
            normal[axis] = sign
            u, v = [a for a in range(3) if a != axis]
            quad = []
            for a, b in [(-1, -1), (1, -1), (1, 1), (-1, 1)]:
                p = [0, 0, 0]
                p[axis], p[u], p[v] = sign, a, b
                quad.append(y_up(*p))
            faces.append((quad, y_up(*normal)))
    prims = []
    for half in (faces[:3], faces[3:]):
        positions, normals, indices = [], [], []
        for quad, n in half:
            # Counter-clockwise seen from outside, as glTF wants front faces.
            e1 = [quad[1][i] - quad[0][i] for i in range(3)]
            e2 = [quad[2][i] - quad[0][i] for i in range(3)]
            cross = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
            order = [0, 1, 2, 0, 2, 3] if sum(c * m for c, m in zip(cross, n)) > 0 else [0, 2, 1, 0, 3, 2]
            indices += [len(positions) + i for i in order]
            positions += quad
            normals += [n] * 4
        prims.append((positions, normals, indices))
    return prims


def quat_about_blender_z(angle):
    """A rotation about Blender's Z, which is glTF's Y after the Y-up conversion (x, y, z, w)."""
    return (0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2))


def main(path):
    b = Builder()
    grey = b.material("Floor", [0.8, 0.8, 0.8])
    red = b.material("Red", [0.8, 0.1, 0.1])
    blue = b.material("Blue", [0.1, 0.2, 0.8])
    lamp = b.material("Emission", [0.0, 0.0, 0.0], emission=[1.0, 0.95, 0.9], strength=6.0)

    floor = b.mesh("Plane", [b.primitive(*plane(4, 4), grey, wide_indices=True)])
    b.node({"name": "Floor", "mesh": floor, "extras": {"note": "custom property"}})
    wall = b.mesh("Plane.001", [b.primitive(*plane(4, 2), grey)])
    # A wall 4 m behind the origin: Blender rotation 90 deg about X, location (0, 4, 2).
    s = math.sqrt(0.5)
    b.node({"name": "Wall", "mesh": wall, "translation": list(y_up(0, 4, 2)), "rotation": [s, 0, 0, s]})
    light_mesh = b.mesh("Plane.002", [b.primitive(*plane(0.6, 0.6), lamp)])
    b.node({"name": "Light Panel", "mesh": light_mesh, "translation": list(y_up(0, 0, 3))})

    cube = b.mesh("Cube", [b.primitive(p, n, i, m) for (p, n, i), m in zip(cube_halves(), (red, blue))])
    cube_node = b.node({"name": "Cube", "mesh": cube, "translation": list(y_up(-1.5, 0, 0.4)),
                        "scale": [0.4, 0.4, 0.4]})

    watts = 100.0
    b.gltf["extensions"]["KHR_lights_punctual"]["lights"].append(
        {"name": "Point", "type": "point", "color": [1, 1, 1], "intensity": watts / (4 * math.pi) * 683})
    b.node({"name": "Point", "translation": list(y_up(1, -1, 2.5)),
            "extensions": {"KHR_lights_punctual": {"light": 0}}})

    aspect = 1920 / 1080
    xfov = 2 * math.atan(18 / 50)
    b.gltf["cameras"].append({"name": "Camera", "type": "perspective",
                              "perspective": {"aspectRatio": aspect, "yfov": 2 * math.atan(math.tan(xfov / 2) / aspect),
                                              "znear": 0.1, "zfar": 100}})
    # Blender camera at (0, -7, 1.2) with rotation (90, 0, 0) deg looks along +Y: glTF's -z, no rotation.
    b.node({"name": "Camera", "camera": 0, "translation": list(y_up(0, -7, 1.2))})

    # The cube slides along Blender's X from -1.5 to 1.5 and turns about Z, sampled every frame.
    times = [f / FPS for f in FRAMES]
    u = [(f - FRAMES[0]) / (len(FRAMES) - 1) for f in FRAMES]
    translations = [y_up(-1.5 + 3 * t, 0, 0.4) for t in u]
    rotations = [quat_about_blender_z(math.pi / 2 * t) for t in u]
    time_acc = b.accessor("f", times, "SCALAR", 5126)
    b.gltf["accessors"][time_acc].update({"min": [times[0]], "max": [times[-1]]})
    b.gltf["animations"].append({
        "name": "CubeAction",
        "channels": [{"sampler": 0, "target": {"node": cube_node, "path": "translation"}},
                     {"sampler": 1, "target": {"node": cube_node, "path": "rotation"}}],
        "samplers": [{"input": time_acc, "interpolation": "LINEAR", "output": b.accessor("fff", translations, "VEC3", 5126)},
                     {"input": time_acc, "interpolation": "LINEAR", "output": b.accessor("ffff", rotations, "VEC4", 5126)}]})
    b.write(path)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
