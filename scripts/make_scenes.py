#!/usr/bin/env python3
"""Writes the scenes: scenes/ball.json, table.json and cornell.json, and the truth suite's
corridor.json, mirror_room.json, flythrough.json, glass_move.json, switch_room.json,
daylit_room.json, daylit_sun.json, outdoor_hdri.json, and the moving lights' torch_corridor.json
and daylit_sweep.json (docs/truth-suite.md), and
daylit_glazed.json, the daylit room behind a pane of glass, which the suite measures apart.

BALL and TABLE follow docs/test-scenes.md exactly; their keyframes (one per
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


def keyframes(values, fps=FPS):
    """A linear track with one key per frame, frame f at time f / fps."""
    return {"interpolation": "linear",
            "times": [round(f / fps, 6) for f in range(len(values))],
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


SUITE_FRAMES = 30  # the truth suite's animations: one second at 30 fps


def suite_times():
    return [f / (SUITE_FRAMES - 1) for f in range(SUITE_FRAMES)]


def corridor_scene():
    """A corridor lit by three small ceiling panels, a point lamp and a spot lamp (no mirrors, no
    glass: a path tracer cannot find a point light's caustics), with a figure walking along it
    past the camera. Several small lights: the direct light's noise shows on the flat walls."""
    w, h, d = 2.4, 2.6, 10.0
    objects = [{"name": name, "shape": shape, "material": "wall" if name not in ("floor", "ceiling") else name}
               for name, shape in room(w, h, d, closed_front=True).items()]
    for i, z in enumerate([2.0, 5.0, 8.0]):
        objects.append(ceiling_light(f"panel{i}", 1.0, 1.4, h - 0.01, z - 0.2, z + 0.2, [14, 13, 11]))
    ts = suite_times()
    objects.append({"name": "figure", "shape": box([0, 0, 0], [0.4, 1.7, 0.3]), "material": "figure",
                    "animation": {"translation": keyframes([[0.8, 0.85, 7.0 - 5.5 * t] for t in ts])}})
    lights = [{"type": "point", "name": "lamp", "position": [1.9, 1.8, 9.2], "intensity": [3.0, 2.6, 2.0]},
              {"type": "spot", "name": "spot", "position": [0.2, 2.3, 4.0], "direction": [0.6, -1, 0.3],
               "intensity": [6, 6, 7], "cone_degrees": 35}]
    materials = {"wall": lambert([0.70, 0.68, 0.62]), "floor": lambert([0.45, 0.40, 0.35]),
                 "ceiling": lambert([0.80, 0.80, 0.80]), "figure": lambert([0.20, 0.35, 0.60])}
    camera = {"position": [1.6, 1.5, 0.3], "look_at": [1.1, 1.2, 6.0], "fov_y": 55, "resolution": [320, 240]}
    return {"name": "corridor", "frames": {"count": SUITE_FRAMES, "fps": FPS}, "camera": camera,
            "materials": materials, "objects": objects, "lights": lights}


def torch_corridor_scene():
    """The corridor with its ceiling panels and lamps standing still, and a torch (a spot lamp)
    carried by the figure as it walks towards the camera, shining ahead of it onto the floor:
    one light that moves among several that do not, every frame its own segment."""
    scene = corridor_scene()
    scene["name"] = "torch_corridor"
    ts = suite_times()
    scene["lights"].append({"type": "spot", "name": "torch", "position": [1.15, 1.3, 6.8], "direction": [0, -0.6, -1],
                            "intensity": [5, 4.6, 3.8], "cone_degrees": 28,
                            "animation": {"translation": keyframes([[1.15, 1.3, 6.8 - 5.5 * t] for t in ts])}})
    return scene


def mirror_room_scene():
    """BALL's room with a mirror on the left wall and a glossy floor, both seeing a ball that
    rolls across: specular paths that meet a moving object."""
    objects = cornell_room_objects()
    for o in objects:
        if o["name"] == "floor":
            o["material"] = "glossy_floor"
    objects.append({"name": "mirror", "shape": quad([0.02, 1.0, 1.0], [0, 2.8, 0], [0, 0, 3.5]), "material": "mirror"})
    ts = suite_times()
    objects.append({"name": "ball", "shape": {"type": "sphere", "center": [0, 0, 0], "radius": 0.6},
                    "material": "blue", "animation": {"translation": keyframes([[4.3 - 2.6 * t, 0.6, 2.2] for t in ts])}})
    materials = cornell_materials()
    materials["glossy_floor"] = {"type": "glossy", "reflectance": [0.55, 0.5, 0.45], "roughness": 0.35}
    materials["mirror"] = {"type": "mirror", "reflectance": [0.9, 0.9, 0.9]}
    return {"name": "mirror_room", "frames": {"count": SUITE_FRAMES, "fps": FPS}, "camera": ball_camera(),
            "materials": materials, "objects": objects}


def flythrough_scene():
    """The Cornell box seen by a camera that moves in and turns (the static cache covers every
    view of the segment), with a small box sliding on the floor."""
    objects = cornell_room_objects()
    objects.append({"name": "short_box", "shape": box([0, 0, 0], [1.65, 1.65, 1.65]), "material": "white",
                    "transform": {"translation": [3.7, 0.825, 1.9], "rotation": {"axis": [0, 1, 0], "degrees": -17}}})
    ts = suite_times()
    objects.append({"name": "cube", "shape": box([0, 0, 0], [0.6, 0.6, 0.6]), "material": "blue",
                    "animation": {"translation": keyframes([[1.0 + 1.5 * t, 0.3, 1.0] for t in ts])}})
    camera = {"position": [2.75, 2.75, -7.2], "look_at": [2.75, 2.75, 0], "fov_y": 40, "resolution": [320, 240],
              "animation": {"translation": keyframes([[2.75 + 1.2 * t, 2.4 + 0.6 * t, -7.2 + 3.0 * t] for t in ts]),
                            "rotation": keyframes([y_rotation(180 - 12 * t) for t in ts])}}
    return {"name": "flythrough", "frames": {"count": SUITE_FRAMES, "fps": FPS}, "camera": camera,
            "materials": cornell_materials(), "objects": objects}


def glass_move_scene():
    """A glass sphere moving under an area light over a diffuse floor: dynamic caustics and
    specular paths through a moving object."""
    objects = [{"name": name, "shape": shape, "material": "white" if name != "back" else "green"}
               for name, shape in room(5.5, 5.5, 5.5, closed_front=False).items()]
    objects.append(ceiling_light("light", 2.2, 3.3, 5.49, 2.2, 3.3, [30, 28, 24]))
    ts = suite_times()
    objects.append({"name": "glass_ball", "shape": {"type": "sphere", "center": [0, 0, 0], "radius": 0.7},
                    "material": "glass", "animation": {"translation": keyframes([[1.6 + 2.3 * t, 1.3, 2.6] for t in ts])}})
    objects.append({"name": "block", "shape": box([4.2, 0.5, 4.0], [1.0, 1.0, 1.0]), "material": "red"})
    materials = {"white": lambert([0.725, 0.71, 0.68]), "green": lambert([0.14, 0.45, 0.091]),
                 "red": lambert([0.63, 0.065, 0.05]), "glass": {"type": "dielectric", "ior": 1.5}}
    return {"name": "glass_move", "frames": {"count": SUITE_FRAMES, "fps": FPS}, "camera": ball_camera(),
            "materials": materials, "objects": objects}


def switch_room_scene():
    """BALL's room lit by its ceiling light and a spot lamp, where a second ceiling light switches
    on at frame 15 (a step in its emission) and the lamp dims: two segments, each with its own
    static cache, while a ball rolls across the floor."""
    objects = cornell_room_objects()
    on = SUITE_FRAMES // 2 / FPS
    objects.append({"name": "second_light", "shape": quad([0.8, 5.49, 0.8], [1.0, 0, 0], [0, 0, 1.0]),
                    "animation": {"emission": {"interpolation": "step", "times": [0, round(on, 6)],
                                               "values": [0, [10, 10, 12]]}}})
    ts = suite_times()
    objects.append({"name": "ball", "shape": {"type": "sphere", "center": [0, 0, 0], "radius": 0.5},
                    "material": "blue", "animation": {"translation": keyframes([[1.2 + 3.0 * t, 0.5, 2.0] for t in ts])}})
    lights = [{"type": "spot", "name": "lamp", "position": [4.8, 4.5, 0.8], "direction": [-0.4, -1, 0.5],
               "intensity": 8, "cone_degrees": 30,
               "animation": {"intensity": {"interpolation": "step", "times": [0, round(on, 6)], "values": [8, 3]}}}]
    return {"name": "switch_room", "frames": {"count": SUITE_FRAMES, "fps": FPS}, "camera": ball_camera(),
            "materials": cornell_materials(), "objects": objects, "lights": lights}


def daylit_room_objects():
    """BALL's room closed on every side, with a window 2.5 m wide and 2 m high in the green wall
    (x = 5.5) and its tall box; a blue ball bounces along the room through the sunbeam."""
    walls = room(5.5, 5.5, 5.5, closed_front=True)
    objects = [{"name": name, "shape": walls[name], "material": material}
               for name, material in [("floor", "white"), ("ceiling", "white"), ("back", "white"),
                                      ("front", "white"), ("left", "red")]]
    green = [("right_below_window", quad([5.5, 0, 0], [0, 0, 5.5], [0, 2, 0])),
             ("right_above_window", quad([5.5, 4, 0], [0, 0, 5.5], [0, 1.5, 0])),
             ("right_before_window", quad([5.5, 2, 0], [0, 0, 1.5], [0, 2, 0])),
             ("right_behind_window", quad([5.5, 2, 4], [0, 0, 1.5], [0, 2, 0]))]
    objects += [{"name": name, "shape": shape, "material": "green"} for name, shape in green]
    objects.append({"name": "tall_box", "shape": box([0, 0, 0], [1.65, 3.3, 1.65]), "material": "white",
                    "transform": {"translation": [1.85, 1.65, 3.7], "rotation": {"axis": [0, 1, 0], "degrees": 17}}})
    # Two bounces over the animation: keys every quarter second, the last at its last frame.
    objects.append({"name": "ball", "shape": {"type": "sphere", "radius": 0.45}, "material": "blue",
                    "animation": {"translation": {
                        "interpolation": "linear", "times": [0, 0.25, 0.5, 0.75, round((SUITE_FRAMES - 1) / FPS, 6)],
                        "values": [[4.5, 0.45, 2.6], [3.6, 1.9, 2.6], [2.75, 0.45, 2.6], [1.9, 1.9, 2.6],
                                   [1.0, 0.45, 2.6]]}}})
    return objects


DAYLIT_WINDOW = {"corner": [5.5, 2, 1.5], "edge_u": [0, 0, 2.5], "edge_v": [0, 2, 0]}
DAYLIT_SUN = {"type": "sun", "name": "sun", "direction": [-1, -0.7, 0.25], "irradiance": [3.6, 3.4, 3.0],
              "angle_degrees": 0.53}


def daylit_scene(name, world, glazed=False):
    """The daylit room: its only light a sun (and a world, if given) through the window, marked
    as a portal; the camera inside by the front wall. Glazed: a pane of glass 1 cm thick fills
    the window, just outside the wall's plane."""
    objects = daylit_room_objects()
    materials = cornell_materials()
    if glazed:
        objects.append({"name": "pane", "shape": box([5.505, 3, 2.75], [0.01, 2, 2.5]), "material": "glass"})
        materials["glass"] = {"type": "dielectric", "ior": 1.5}
    camera = {"position": [2.75, 2.3, 0.25], "look_at": [2.75, 1.7, 5.5], "up": [0, 1, 0], "fov_y": 65,
              "resolution": [320, 240]}
    scene = {"name": name, "frames": {"count": SUITE_FRAMES, "fps": FPS}, "camera": camera,
             "materials": materials, "objects": objects, "lights": [DAYLIT_SUN]}
    if world:
        scene["world"] = world
    scene["portals"] = [DAYLIT_WINDOW]
    return scene


def daylit_sweep_scene():
    """`daylit_sun` with the sun turning 25 degrees about the vertical over the animation, as
    in a time-lapse: its beam sweeps across the floor and the far wall while the ball bounces
    through it. The sun moves every frame: every frame its own segment."""
    scene = daylit_scene("daylit_sweep", None)
    sun = dict(DAYLIT_SUN)
    sun["animation"] = {"rotation": {"interpolation": "linear", "times": [0, round((SUITE_FRAMES - 1) / FPS, 6)],
                                     "values": [[0, 0, 0, 1], [round(c, 6) for c in y_rotation(-25)]]}}
    scene["lights"] = [sun]
    return scene


def outdoor_hdri_scene():
    """Outdoors under Blender's courtyard world (scenes/worlds/courtyard.exr, CC0): a ground of
    20 m x 20 m, a white block and an ochre column, and a ball rolling across in front of them.
    The image's light comes mostly from the open sky towards +x: soft shadows falling to -x."""
    objects = [{"name": "ground", "shape": quad([-10, 0, -10], [0, 0, 20], [20, 0, 0]), "material": "ground"},
               {"name": "block", "shape": box([0, 0, 0], [0.8, 0.8, 0.8]), "material": "white",
                "transform": {"translation": [-1.2, 0.4, 1.4], "rotation": {"axis": [0, 1, 0], "degrees": 25}}},
               {"name": "column", "shape": box([1.3, 0.8, 1.8], [0.5, 1.6, 0.5]), "material": "ochre"}]
    ts = suite_times()
    objects.append({"name": "ball", "shape": {"type": "sphere", "center": [0, 0, 0], "radius": 0.35},
                    "material": "blue", "animation": {"translation": keyframes([[1.8 - 3.6 * t, 0.35, 0.2] for t in ts])}})
    materials = {"ground": lambert([0.45, 0.42, 0.38]), "white": lambert([0.725, 0.71, 0.68]),
                 "ochre": lambert([0.65, 0.4, 0.15]), "blue": lambert([0.15, 0.3, 0.8])}
    camera = {"position": [0, 1.3, -4.0], "look_at": [0, 0.6, 1.0], "up": [0, 1, 0], "fov_y": 50,
              "resolution": [320, 240]}
    return {"name": "outdoor_hdri", "frames": {"count": SUITE_FRAMES, "fps": FPS}, "camera": camera,
            "materials": materials, "objects": objects, "world": {"image": "worlds/courtyard.exr"}}


def dumps(scene):
    """Indented JSON with short numeric arrays kept on one line."""
    text = json.dumps(scene, indent=2)
    return re.sub(r"\[\s+([-\d.e,\s]+?)\s+\]", lambda m: "[" + re.sub(r"\s+", " ", m.group(1)) + "]", text) + "\n"


def main():
    scenes = [("ball", ball_scene()), ("table", table_scene()), ("cornell", cornell_scene()),
              ("corridor", corridor_scene()), ("mirror_room", mirror_room_scene()),
              ("flythrough", flythrough_scene()), ("glass_move", glass_move_scene()),
              ("switch_room", switch_room_scene()),
              ("daylit_room", daylit_scene("daylit_room", {"color": [0.25, 0.35, 0.55], "strength": 1})),
              ("daylit_sun", daylit_scene("daylit_sun", None)),
              ("torch_corridor", torch_corridor_scene()),
              ("daylit_sweep", daylit_sweep_scene()),
              ("daylit_glazed", daylit_scene("daylit_glazed", {"color": [0.25, 0.35, 0.55], "strength": 1},
                                             glazed=True)),
              ("outdoor_hdri", outdoor_hdri_scene())]
    for name, scene in scenes:
        with open(os.path.join(SCENES, name + ".json"), "w") as f:
            f.write(dumps(scene))


if __name__ == "__main__":
    main()
