# Renders a glTF exported by `conegraph export` with Blender Cycles, set up as the same
# physics as the path_trace pass, for an independent check of the reference:
#   blender -b --factory-startup -P render_cycles.py -- SCENE.gltf OUT.exr W H SAMPLES BOUNCES [SKY [FILTER]]
# - lights imported in COMPAT mode: sun strength = glTF intensity (irradiance, W/m^2),
#   point/spot power = 4 pi x intensity (Cycles' I = P / 4 pi); hard shadows (radius 0,
#   sun angle 0); KHR spot cones become Blender's spot size and blend (the falloff
#   shapes differ inside the penumbra);
# - every material becomes a Lambertian Diffuse BSDF (roughness 0) of the glTF base colour
#   plus an Emission of the glTF emissive, replacing the importer's Principled BSDF (whose
#   specular layer and Disney diffuse are not Lambertian);
# - the world: black, or with SKY = R,G,B a uniform sky of that radiance (the world's
#   Background colour at strength 1), as path_trace's uniform sky;
# - FILTER `area` (default): the box pixel filter, samples over the pixel (path_trace
#   jitter=true); `centre`: a Gaussian 0.01 px wide, rays through pixel centres (path_trace's
#   default; Cycles' box filter ignores its width, so it cannot be narrowed);
# - no clamping, no light threshold, no denoising, linear EXR with the Standard view transform;
# - diffuse bounces = BOUNCES (Cycles and path_trace count them alike: 0 = direct light of
#   every source, emissive surfaces included); glossy, transmission and volume bounces 0.
import sys

import bpy
import numpy

# Blender 3.4's glTF importer uses numpy.bool, which Debian 12's numpy 1.24 removed.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

argv = sys.argv[sys.argv.index("--") + 1:]
scene_path, out_path = argv[0], argv[1]
width, height, samples, bounces = int(argv[2]), int(argv[3]), int(argv[4]), int(argv[5])
sky = argv[6] if len(argv) > 6 else "none"
pixel_filter = argv[7] if len(argv) > 7 else "area"

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=scene_path, convert_lighting_mode='COMPAT')

scene = bpy.context.scene
for obj in scene.objects:
    if obj.type == 'CAMERA' and scene.camera is None:
        scene.camera = obj
    if obj.type == 'LIGHT':
        light = obj.data
        if light.type == 'SUN':
            light.angle = 0.0
        else:
            light.shadow_soft_size = 0.0

for mat in bpy.data.materials:
    if not mat.use_nodes:
        continue
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = next((n for n in nodes if n.type == 'BSDF_PRINCIPLED'), None)
    output = next((n for n in nodes if n.type == 'OUTPUT_MATERIAL'), None)
    if bsdf is None or output is None:
        continue
    diffuse = nodes.new('ShaderNodeBsdfDiffuse')
    diffuse.inputs['Roughness'].default_value = 0.0
    base = bsdf.inputs['Base Color']
    if base.is_linked:
        links.new(base.links[0].from_socket, diffuse.inputs['Color'])
    else:
        diffuse.inputs['Color'].default_value = base.default_value
    emission = nodes.new('ShaderNodeEmission')
    emit = bsdf.inputs['Emission']
    if emit.is_linked:
        links.new(emit.links[0].from_socket, emission.inputs['Color'])
    else:
        emission.inputs['Color'].default_value = emit.default_value
    emission.inputs['Strength'].default_value = bsdf.inputs['Emission Strength'].default_value
    add = nodes.new('ShaderNodeAddShader')
    links.new(diffuse.outputs['BSDF'], add.inputs[0])
    links.new(emission.outputs['Emission'], add.inputs[1])
    links.new(add.outputs['Shader'], output.inputs['Surface'])

world = bpy.data.worlds.new("sky")
world.use_nodes = True
background = world.node_tree.nodes['Background']
if sky == "none":
    background.inputs['Strength'].default_value = 0.0
else:
    rgb = [float(v) for v in sky.split(",")]
    background.inputs['Color'].default_value = (rgb[0], rgb[1], rgb[2], 1.0)
    background.inputs['Strength'].default_value = 1.0
scene.world = world

scene.render.engine = 'CYCLES'
cycles = scene.cycles
cycles.device = 'CPU'
cycles.samples = samples
cycles.use_adaptive_sampling = False
cycles.use_denoising = False
cycles.max_bounces = bounces
cycles.diffuse_bounces = bounces
cycles.glossy_bounces = 0
cycles.transmission_bounces = 0
cycles.volume_bounces = 0
cycles.transparent_max_bounces = 0
cycles.sample_clamp_direct = 0.0
cycles.sample_clamp_indirect = 0.0
cycles.light_sampling_threshold = 0.0
cycles.caustics_reflective = False
cycles.caustics_refractive = False
if pixel_filter == "centre":
    cycles.filter_type = 'GAUSSIAN'
    cycles.filter_width = 0.01
else:
    cycles.filter_type = 'BOX'
    cycles.filter_width = 1.0
cycles.seed = 1
scene.render.resolution_x = width
scene.render.resolution_y = height
scene.render.resolution_percentage = 100
scene.render.film_transparent = False
scene.view_settings.view_transform = 'Standard'
scene.view_settings.look = 'None'
scene.view_settings.exposure = 0.0
scene.view_settings.gamma = 1.0
scene.render.image_settings.file_format = 'OPEN_EXR'
scene.render.image_settings.color_depth = '32'
scene.render.image_settings.color_mode = 'RGBA'
scene.render.filepath = out_path
bpy.ops.render.render(write_still=True)
