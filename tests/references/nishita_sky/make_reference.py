"""Renders the reference images that src/steadylight/scene/sky_nishita_test.cpp compares
steadylight's port of Blender's Sky Texture (Nishita) with: Cycles' own rendering of the sky.

    blender -b --factory-startup --python make_reference.py -- OUT_DIR

Written for Blender 3.4 (Debian 12's package), whose intern/sky the port follows. For each
parameter set it renders the world alone through a panoramic equirectangular camera
(PANORAMA_WIDTH x PANORAMA_WIDTH/2, <name>.exr) and, when the sun disc shows, a narrow
perspective view centred on the sun (<name>_sun.exr). Every image is linear scene-referred RGB
(view transform Standard, no denoising, 32-bit float EXR), each pixel the average over its
area (a box pixel filter one pixel wide). It writes references.json: the parameters of each
set (Blender's names and units) and each sun view's camera in glTF axes.

Before the sky, it checks that the panorama is laid out as steadylight expects (Blender's
Environment Texture mapping, in glTF axes y up: u = atan2(z, x)/2pi + 1/2, v = asin(y)/pi + 1/2,
v = 1 the top row): it renders a world that shows its own look-up direction and stops with an
error if any pixel's direction is off.
"""
import json
import math
import os
import sys

import bpy
import numpy as np
from mathutils import Vector

PANORAMA_WIDTH = 128
SUN_VIEW_SIZE = 64
SUN_VIEW_FOV_DEG = 1.5
SAMPLES = 4096

# Blender's defaults for the Sky Texture (Nishita), in its units (radians, metres).
DEFAULTS = dict(sun_elevation=math.radians(15), sun_rotation=0.0, sun_size=math.radians(0.545),
                sun_intensity=1.0, sun_disc=True, altitude=0.0, air_density=1.0, dust_density=1.0,
                ozone_density=1.0)

PARAMETER_SETS = {
    'default': {},
    'no_sun_disc': dict(sun_disc=False),
    'elevation45_rotation60': dict(sun_elevation=math.radians(45), sun_rotation=math.radians(60)),
    'altitude2000_dust5': dict(altitude=2000.0, dust_density=5.0),
    'intensity2': dict(sun_intensity=2.0),
    'sun_on_horizon': dict(sun_elevation=math.radians(0.1), sun_rotation=math.radians(-30)),
    'sun_below_horizon': dict(sun_elevation=math.radians(-2), sun_rotation=math.radians(200)),
}


def gltf_from_blender(v):
    """Blender (x, y, z) = glTF (x, -z, y)."""
    return [v[0], v[2], -v[1]]


def setup_scene():
    scene = bpy.context.scene
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = SAMPLES
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.pixel_filter_type = 'BOX'
    scene.cycles.filter_width = 1.0
    scene.cycles.seed = 1
    scene.render.film_transparent = False
    scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = 'Standard'
    scene.view_settings.look = 'None'
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    settings = scene.render.image_settings
    settings.file_format = 'OPEN_EXR'
    settings.color_mode = 'RGB'
    settings.color_depth = '32'
    settings.exr_codec = 'ZIP'
    camera = bpy.data.objects.new('camera', bpy.data.cameras.new('camera'))
    scene.collection.objects.link(camera)
    scene.camera = camera
    return scene, camera


def set_panorama_camera(scene, camera):
    """Cycles' equirectangular camera centres the image on the camera's view direction, its up
    the camera's up: look down +x (glTF +x) with z up (glTF +y) to match the mapping."""
    camera.data.type = 'PANO'
    camera.data.cycles.panorama_type = 'EQUIRECTANGULAR'
    camera.location = (0, 0, 0)
    camera.rotation_mode = 'XYZ'
    camera.rotation_euler = (math.pi / 2, 0, -math.pi / 2)
    scene.render.resolution_x = PANORAMA_WIDTH
    scene.render.resolution_y = PANORAMA_WIDTH // 2


def set_sun_camera(scene, camera, toward):
    """A square perspective view of SUN_VIEW_FOV_DEG across, centred on `toward` (Blender axes)."""
    camera.data.type = 'PERSP'
    camera.data.sensor_fit = 'HORIZONTAL'
    camera.data.angle = math.radians(SUN_VIEW_FOV_DEG)
    camera.location = (0, 0, 0)
    camera.rotation_mode = 'QUATERNION'
    up_hint = 'Y' if abs(toward.z) < 0.999 else 'X'
    camera.rotation_quaternion = toward.to_track_quat('-Z', up_hint)
    scene.render.resolution_x = SUN_VIEW_SIZE
    scene.render.resolution_y = SUN_VIEW_SIZE
    bpy.context.view_layer.update()
    rotation = camera.matrix_world.to_3x3()
    return dict(forward=gltf_from_blender(rotation @ Vector((0, 0, -1))),
                right=gltf_from_blender(rotation @ Vector((1, 0, 0))),
                up=gltf_from_blender(rotation @ Vector((0, 1, 0))),
                fov_deg=SUN_VIEW_FOV_DEG, width=SUN_VIEW_SIZE, height=SUN_VIEW_SIZE)


def world_nodes(scene):
    world = bpy.data.worlds.new('world')
    scene.world = world
    world.use_nodes = True
    nodes = world.node_tree.nodes
    nodes.clear()
    output = nodes.new('ShaderNodeOutputWorld')
    background = nodes.new('ShaderNodeBackground')
    background.inputs['Strength'].default_value = 1.0
    world.node_tree.links.new(background.outputs['Background'], output.inputs['Surface'])
    return world.node_tree, background


def render(scene, path):
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)


def read_exr(path):
    """RGB rows from the top, as steadylight's Image holds them."""
    image = bpy.data.images.load(path)
    w, h = image.size
    pixels = np.array(image.pixels[:], dtype=np.float64).reshape(h, w, 4)[::-1, :, :3]
    bpy.data.images.remove(image)
    return pixels


def check_panorama_layout(scene, out_dir):
    """A world whose colour is (direction + 1)/2, the direction the world is looked up with,
    rendered through the panorama camera, against the mapping at each pixel's centre."""
    tree, background = world_nodes(scene)
    nodes = tree.nodes
    coords = nodes.new('ShaderNodeTexCoord')
    scale = nodes.new('ShaderNodeVectorMath')
    scale.operation = 'MULTIPLY_ADD'
    scale.inputs[1].default_value = (0.5, 0.5, 0.5)
    scale.inputs[2].default_value = (0.5, 0.5, 0.5)
    tree.links.new(coords.outputs['Generated'], scale.inputs[0])
    tree.links.new(scale.outputs['Vector'], background.inputs['Color'])
    set_panorama_camera(scene, scene.camera)
    path = os.path.join(out_dir, 'layout_check.exr')
    render(scene, path)
    pixels = read_exr(path)
    os.remove(path)
    h, w = pixels.shape[:2]
    worst = 0.0
    for row in range(h):
        v = 1 - (row + 0.5) / h
        for column in range(w):
            u = (column + 0.5) / w
            phi, elevation = (u - 0.5) * 2 * math.pi, (v - 0.5) * math.pi
            expected = np.array([math.cos(elevation) * math.cos(phi), math.sin(elevation),
                                 math.cos(elevation) * math.sin(phi)])  # glTF axes
            b = pixels[row, column] * 2 - 1  # Blender axes
            seen = np.array(gltf_from_blender(b))
            worst = max(worst, float(np.linalg.norm(seen / np.linalg.norm(seen) - expected)))
    # Each pixel averages directions over its area: 2pi/w across, so a few hundredths.
    limit = 2 * math.pi / w
    print(f'panorama layout check: largest direction error {worst:.4f} (limit {limit:.4f})')
    if not worst < limit:
        sys.exit(f'make_reference.py: the panorama is not laid out as expected ({worst})')
    return worst


def sun_direction(params):
    """Blender axes: Cycles turns the sun by sun_rotation clockwise seen from above, from +y."""
    e, r = params['sun_elevation'], params['sun_rotation']
    return Vector((math.cos(e) * math.sin(r), math.cos(e) * math.cos(r), math.sin(e)))


def main():
    out_dir = os.path.abspath(sys.argv[sys.argv.index('--') + 1])
    os.makedirs(out_dir, exist_ok=True)
    scene, camera = setup_scene()
    layout_error = check_panorama_layout(scene, out_dir)
    references = dict(blender_version=bpy.app.version_string, samples=SAMPLES,
                      pixel_filter='box, 1 pixel wide', panorama_layout_error=layout_error, sets={})
    for name, changes in PARAMETER_SETS.items():
        params = dict(DEFAULTS, **changes)
        tree, background = world_nodes(scene)
        sky = tree.nodes.new('ShaderNodeTexSky')
        sky.sky_type = 'NISHITA'
        for key, value in params.items():
            setattr(sky, key, value)
        tree.links.new(sky.outputs['Color'], background.inputs['Color'])
        entry = dict(params=params, panorama=name + '.exr')
        set_panorama_camera(scene, camera)
        render(scene, os.path.join(out_dir, name + '.exr'))
        half_angle = params['sun_size'] / 2
        if params['sun_disc'] and params['sun_elevation'] + half_angle > 0:
            entry['sun_view'] = name + '_sun.exr'
            entry['sun_camera'] = set_sun_camera(scene, camera, sun_direction(params))
            render(scene, os.path.join(out_dir, name + '_sun.exr'))
        references['sets'][name] = entry
    with open(os.path.join(out_dir, 'references.json'), 'w') as f:
        json.dump(references, f, indent=2)
        f.write('\n')


main()
