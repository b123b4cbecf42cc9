"""Renders one frame of the Blender room (scripts/make_blender_scene.py), or of a steadylight JSON
scene (scripts/blender_from_json.py), with Blender's Cycles, as an independent check of
steadylight's path tracer. Not part of CI: it needs Blender and minutes.

Run headless:
  blender -b --factory-startup --python scripts/cycles_reference.py -- \
      --frame 0 --samples 1024 --out /tmp/cycles_0000.exr [--filter box] [--lambert] [--seed N] \
      [--scene room|textured] [--json SCENE.json] [--size WxH]
  blender -b FILE.blend --factory-startup --python scripts/cycles_reference.py -- --open-file ...

`--scene textured` renders the textured room of scripts/make_blender_textured_room.py instead
(no --lambert there: its materials are textured and glossy on purpose); `--json` a steadylight
JSON scene such as scenes/daylit_room.json, with its world, suns and portals as Blender's
(scripts/blender_from_json.py says how); `--open-file` the .blend Blender opened, as it is (its
world and lamps: what the Blender add-on exports, docs/blender.md); `--size` overrides the
scene's 320 x 240.

The scene is built afresh by make_blender_scene.build_scene(), the same code that exports
scenes/blender_room.glb, so both renderers see one scene. Cycles is set up to compute the same
estimate as steadylight's path tracer:
- a fixed number of samples per pixel, no adaptive sampling, no denoising;
- up to 64 bounces of every kind (Cycles' default stops diffuse paths after 4 bounces, which
  darkens a closed room); Russian roulette left on (unbiased);
- no sample clamping (Cycles clamps indirect samples at 10 by default), light threshold 0;
- pixel filter: Blender's default, Blackman-Harris 1.5 px wide; `--filter box` gives a 1 px box,
  which is what steadylight uses (it averages jittered samples inside each pixel);
- view transform Standard, look None, exposure 0, gamma 1 (they do not touch the EXR anyway);
- a black world (the room is closed, so no ray sees it), or with `--json` the scene's own;
- output: a linear 32-bit float OpenEXR (RGB), no view transform applied.
`--lambert` replaces every Principled BSDF by a Diffuse BSDF (roughness 0: Lambert) with the
same base colour, plus the same emission: Cycles 3.x shades Principled's diffuse lobe with
Disney's retro-reflection, which at Roughness 1 is brighter than Lambert at grazing angles.
"""
import argparse
import os
import sys
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_from_json  # noqa: E402
import make_blender_scene  # noqa: E402  (Blender runs this file as a script, not a package)
import make_blender_textured_room  # noqa: E402

MAX_BOUNCES = 64


def parse_args(argv):
    parser = argparse.ArgumentParser(prog="cycles_reference.py", description=__doc__.splitlines()[0])
    parser.add_argument("--frame", type=int, default=0, help="Blender frame = steadylight frame")
    parser.add_argument("--samples", type=int, default=1024, help="samples per pixel")
    parser.add_argument("--out", required=True, help="the EXR to write")
    parser.add_argument("--filter", choices=("blender", "box"), default="blender",
                        help="blender: Blackman-Harris 1.5 px (Blender's default); box: 1 px box")
    parser.add_argument("--lambert", action="store_true", help="Diffuse BSDF instead of Principled")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--threads", type=int, default=0, help="0: Blender's choice (all cores)")
    parser.add_argument("--scene", choices=("room", "textured"), default="room")
    parser.add_argument("--json", help="a steadylight JSON scene instead of --scene")
    parser.add_argument("--open-file", action="store_true", help="the .blend Blender opened, instead of --scene")
    parser.add_argument("--size", help="WxH, instead of the scene's resolution")
    return parser.parse_args(argv[argv.index("--") + 1:] if "--" in argv else [])


def use_lambert(material):
    """Swap the Principled BSDF for Diffuse BSDF (+ Emission), keeping colour and emission."""
    nodes, links = material.node_tree.nodes, material.node_tree.links
    principled = nodes["Principled BSDF"]
    output = nodes["Material Output"]
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = principled.inputs["Base Color"].default_value
    diffuse.inputs["Roughness"].default_value = 0.0
    shader = diffuse.outputs["BSDF"]
    strength = principled.inputs["Emission Strength"].default_value
    colour = principled.inputs["Emission"].default_value
    if strength > 0 and max(colour[:3]) > 0:
        emission = nodes.new("ShaderNodeEmission")
        emission.inputs["Color"].default_value = colour
        emission.inputs["Strength"].default_value = strength
        add = nodes.new("ShaderNodeAddShader")
        links.new(diffuse.outputs["BSDF"], add.inputs[0])
        links.new(emission.outputs["Emission"], add.inputs[1])
        shader = add.outputs["Shader"]
    links.new(shader, output.inputs["Surface"])
    nodes.remove(principled)


def black_world(scene):
    world = bpy.data.worlds.new("Black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
    scene.world = world


def set_up_cycles(scene, args):
    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = args.samples
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.seed = args.seed
    for name in ("max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces",
                 "volume_bounces", "transparent_max_bounces"):
        setattr(cycles, name, MAX_BOUNCES)
    cycles.sample_clamp_direct = 0.0
    cycles.sample_clamp_indirect = 0.0
    cycles.light_sampling_threshold = 0.0
    if args.filter == "box":
        cycles.pixel_filter_type, cycles.filter_width = "BOX", 1.0
    scene.render.film_transparent = False
    if args.threads:
        scene.render.threads_mode, scene.render.threads = "FIXED", args.threads
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    image = scene.render.image_settings
    image.file_format, image.color_mode, image.color_depth, image.exr_codec = "OPEN_EXR", "RGB", "32", "ZIP"


def main(argv):
    args = parse_args(argv)
    if args.scene == "textured" and args.lambert:
        sys.exit("--lambert is for the untextured room only")
    if args.json and args.lambert:
        sys.exit("--lambert is for the Blender rooms: a JSON scene's lambert materials are Diffuse BSDFs already")
    size = [int(v) for v in args.size.split("x")] if args.size else None
    if args.json:
        blender_from_json.build_scene(args.json, args.frame, size)
    elif args.open_file:
        pass
    else:
        (make_blender_textured_room if args.scene == "textured" else make_blender_scene).build_scene()
    scene = bpy.context.scene
    if size:
        scene.render.resolution_x, scene.render.resolution_y = size
    if args.lambert:
        # Materials without nodes (a grease pencil's, which a factory file holds) have no Principled.
        for material in bpy.data.materials:
            if material.use_nodes and "Principled BSDF" in material.node_tree.nodes:
                use_lambert(material)
    if not args.json and not args.open_file:
        black_world(scene)
    set_up_cycles(scene, args)
    scene.frame_set(args.frame)
    scene.render.filepath = os.path.abspath(args.out)
    scene.render.use_file_extension = False
    start = time.time()
    bpy.ops.render.render(write_still=True)
    source = args.json or (bpy.data.filepath if args.open_file else args.scene)
    print(f"cycles_reference: {source}, frame {args.frame}, {args.samples} spp, filter {args.filter}, "
          f"{'Diffuse BSDF' if args.lambert else 'Principled BSDF'}: {time.time() - start:.1f} s -> {args.out}")


if __name__ == "__main__":
    main(sys.argv)
