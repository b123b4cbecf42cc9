#!/usr/bin/env python3
"""Writes scenes/ball.json, scenes/table.json and scenes/cornell.json.

BALL and TABLE follow ../shared/scenes/BALL.md and TABLE.md exactly; their keyframes (one per
frame, linear in between) are computed here. The JSON files are committed too, so the renderer
never needs Python. Run from anywhere: python3 scripts/make_scenes.py
"""
import json
import math
import os
import re

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.join(HERE, "..", "scenes")
FRAMES = 60
FPS = 30


def quad(corner, edge_u, edge_v):
    """A quad whose front side is cross(edge_u, edge_v)."""
    return {"type": "quad", "corner": corner, "edge_u": edge_u, "edge_v": edge_v}


def box(center, size):
    return {"type": "box", "center": center, "size": size}


def lambert(reflectance):
    return {"type": "lambert", "reflectance": reflectance}


def keyframes(values):
    """A linear track with one key per frame, frame f at time f / FPS."""
    return {"interpolation": "linear",
            "times": [round(f / FPS, 6) for f in range(FRAMES)],
            "values": [[round(c, 6) for c in v] for v in values]}


def y_rotation(degrees):
    half = math.radians(degrees) / 2
    return [0.0, math.sin(half), 0.0, math.cos(half)]


def room(width, height, depth, closed_front):
    """Single-sided walls of [0,w]x[0,h]x[0,d], all facing the interior."""
    w, h, d = width, height, depth
    walls = {
        "floor": quad([0, 0, 0], [0, 0, d], [w, 0, 0]),
        "ceiling": quad([0, h, 0], [w, 0, 0], [0, 0, d]),
        "back": quad([0, 0, d], [0, h, 0], [w, 0, 0]),
        "left": quad([0, 0, 0], [0, h, 0], [0, 0, d]),
        "right": quad([w, 0, 0], [0, 0, d], [0, h, 0]),
    }
    if closed_front:
        walls["front"] = quad([0, 0, 0], [w, 0, 0], [0, h, 0])
    return walls


def ceiling_light(name, x0, x1, y, z0, z1, radiance):
    """A one-sided emitter facing down (-y)."""
    return {"name": name, "shape": quad([x0, y, z0], [x1 - x0, 0, 0], [0, 0, z1 - z0]), "emission": radiance}


def cornell_room_objects():
    walls = room(5.5, 5.5, 5.5, closed_front=False)
    materials = {"floor": "white", "ceiling": "white", "back": "white", "left": "red", "right": "green"}
    objects = [{"name": name, "shape": shape, "material": materials[name]} for name, shape in walls.items()]
    objects.append(ceiling_light("light", 2.0, 3.5, 5.49, 2.0, 3.5, [17, 12, 4]))
    objects.append({"name": "tall_box", "shape": box([0, 0, 0], [1.65, 3.3, 1.65]), "material": "white",
                    "transform": {"translation": [1.85, 1.65, 3.7], "rotation": {"axis": [0, 1, 0], "degrees": 17}}})
    return objects


def cornell_materials():
    return {"white": lambert([0.725, 0.71, 0.68]), "red": lambert([0.63, 0.065, 0.05]),
            "green": lambert([0.14, 0.45, 0.091]), "blue": lambert([0.15, 0.3, 0.8])}


def ball_camera():
    return {"position": [2.75, 2.75, -7.2], "look_at": [2.75, 2.75, 0], "up": [0, 1, 0],
            "fov_y": 40, "resolution": [320, 240]}


def ball_scene():
    centres = []
    for f in range(FRAMES):
        t = f / (FRAMES - 1)
        centres.append([4.5 - 3.5 * t, 0.5 + 1.5 * abs(math.sin(2 * math.pi * t)), 1.2])
    objects = cornell_room_objects()
    objects.append({"name": "ball", "shape": {"type": "sphere", "center": [0, 0, 0], "radius": 0.5},
                    "material": "blue", "animation": {"translation": keyframes(centres)}})
    return {"name": "ball", "frames": {"count": FRAMES, "fps": FPS}, "camera": ball_camera(),
            "materials": cornell_materials(), "objects": objects}


def cornell_scene():
    objects = cornell_room_objects()
    objects.append({"name": "short_box", "shape": box([0, 0, 0], [1.65, 1.65, 1.65]), "material": "white",
                    "transform": {"translation": [3.7, 0.825, 1.9], "rotation": {"axis": [0, 1, 0], "degrees": -17}}})
    return {"name": "cornell", "frames": {"count": 1, "fps": FPS}, "camera": ball_camera(),
            "materials": cornell_materials(), "objects": objects}


def table_scene():
    walls = room(8, 3, 6, closed_front=True)
    wall_material = {"floor": "floor", "ceiling": "ceiling", "left": "blue_wall"}
    objects = [{"name": name, "shape": shape, "material": wall_material.get(name, "wall")}
               for name, shape in walls.items()]
    light = [12, 11.5, 10.5]
    objects.append(ceiling_light("light_left", 2.1, 2.9, 2.99, 2.6, 3.4, light))
    objects.append(ceiling_light("light_right", 5.1, 5.9, 2.99, 2.6, 3.4, light))
    objects.append({"name": "table_top", "shape": box([4.0, 0.76, 3.0], [2.4, 0.08, 1.4]), "material": "table"})
    for i, (x, z) in enumerate([(2.94, 2.44), (5.06, 2.44), (2.94, 3.56), (5.06, 3.56)]):
        objects.append({"name": f"table_leg{i}", "shape": box([x, 0.36, z], [0.08, 0.72, 0.08]), "material": "table"})
    objects.append({"name": "glass_sphere", "shape": {"type": "sphere", "center": [4.6, 1.05, 3.3], "radius": 0.25},
                    "material": "glass"})
    ts = [f / (FRAMES - 1) for f in range(FRAMES)]
    objects.append({"name": "red_box", "shape": box([0, 0, 0], [0.5, 0.5, 0.5]), "material": "red",
                    "animation": {"translation": keyframes([[0.8 + 6.4 * t, 0.25, 3.0] for t in ts]),
                                  "rotation": keyframes([y_rotation(90 * t) for t in ts])}})
    objects.append({"name": "yellow_ball", "shape": {"type": "sphere", "center": [0, 0, 0], "radius": 0.2},
                    "material": "yellow",
                    "animation": {"translation": keyframes([[3.2 + 1.2 * t, 1.0, 2.8] for t in ts])}})
    materials = {"floor": lambert([0.60, 0.55, 0.50]), "ceiling": lambert([0.80, 0.80, 0.80]),
                 "blue_wall": lambert([0.30, 0.45, 0.70]), "wall": lambert([0.75, 0.75, 0.72]),
                 "table": lambert([0.55, 0.35, 0.20]), "glass": {"type": "dielectric", "ior": 1.5},
                 "red": lambert([0.70, 0.10, 0.10]), "yellow": lambert([0.80, 0.70, 0.10])}
    camera = {"position": [7.6, 2.2, 0.4], "look_at": [3.8, 0.8, 3.2], "up": [0, 1, 0],
              "fov_y": 50, "resolution": [320, 240]}
    return {"name": "table", "frames": {"count": FRAMES, "fps": FPS}, "camera": camera,
            "materials": materials, "objects": objects}


def dumps(scene):
    """Indented JSON with short numeric arrays kept on one line."""
    text = json.dumps(scene, indent=2)
    return re.sub(r"\[\s+([-\d.e,\s]+?)\s+\]", lambda m: "[" + re.sub(r"\s+", " ", m.group(1)) + "]", text) + "\n"


def main():
    for name, scene in [("ball", ball_scene()), ("table", table_scene()), ("cornell", cornell_scene())]:
        with open(os.path.join(SCENES, name + ".json"), "w") as f:
            f.write(dumps(scene))


if __name__ == "__main__":
    main()
