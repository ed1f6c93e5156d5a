# Renders a glTF scene with Blender 3.4 Cycles, its materials rebuilt from Cycles' Diffuse, Glossy,
# Glass and Refraction BSDFs to match glTF 2.0's BSDF as closely as Cycles allows: an independent
# check of conegraph's path_trace pass on glossy and glass materials (docs/results/cycles/README.md).
#
#   blender -b --factory-startup -P tests/tools/cycles_reference.py -- SCENE.gltf OUT.exr [options]
#     --size WxH           image size (320x180)
#     --spp N              samples per pixel (1024)
#     --sky R,G,B          uniform sky radiance, W/(m^2 sr) (the world's Background colour at
#                          strength 1, as conegraph's --sky R,G,B); default black
#     --bounces D,G,T      diffuse, glossy and transmission bounces (1,1,4); max_bounces = their
#                          sum, caustics_reflective and caustics_refractive off, as path_trace's
#                          bounces, glossy_bounces, transmission_bounces and caustics=false
#     --fresnel MODE       schlick-nv (default): Schlick's F0 + (1 - F0)(1 - n.v)^5 on the shading
#                          normal (Cycles cannot evaluate it on the microfacet's v.h); exact: Cycles'
#                          Fresnel node (the exact dielectric Fresnel of n.v) for dielectrics and
#                          no Fresnel (colour = base) for metals
#     --ids                instead of the image, an object-id image: every material an Emission of
#                          (k + 1, 0, 0) for the glTF material k, black world, 1 sample through the
#                          pixel centre (the per-material masks of compare_materials.py)
#     --threads N          render threads (0 = all)
#
# Materials, from the glTF file's own numbers (not the importer's Principled BSDF, whose diffuse is
# Burley's, not Lambert's). glTF: f = (1-m)(1-T) base/pi (1-F) + F D V + (1-m) T base (1-F) btdf.
#   metallic 1:            Glossy BSDF (GGX: single scattering, as glTF's), Roughness = glTF
#                          roughness (Cycles squares it: alpha = roughness^2, as glTF), Color =
#                          base + (1 - base)(1 - n.v)^5 (Layer Weight's Facing to the 5th)
#   dielectric, opaque:    Mix Shader of Diffuse BSDF (base, roughness 0 = Lambert) and Glossy BSDF
#                          (white, GGX) by Fac = F0 + (1 - F0)(1 - n.v)^5, F0 = ((ior-1)/(ior+1))^2
#                          x specularFactor (specularFactor 0: Diffuse BSDF alone)
#   transmission 1, solid: Glass BSDF (GGX, IOR = glTF ior, Color = base): Cycles' exact Fresnel at
#                          both faces, total internal reflection; glTF's is Schlick's
#   transmission 1, thin:  Mix Shader of Refraction BSDF (IOR 1: the direction goes on unrefracted,
#                          GGX with the glTF roughness, Color = base) and Glossy BSDF (white) by the
#                          same Fac: one interface, as glTF's thin-walled model, and it stops shadow
#                          rays as path_trace's does (a Transparent BSDF would let the sun through)
#   emissive:              plus an Emission of emissive x strength
# Other combinations (0 < metallic < 1, 0 < transmission < 1, textures) are not used by the test
# scenes and are refused, so that no figure comes from a material this script does not model.
# Render: Cycles CPU, no adaptive sampling, no denoising, no clamping, no light threshold, Filter
# Glossy 0 (its default 1 blurs glossy lobes after the first bounce), glTF lights in COMPAT mode
# (sun strength = glTF intensity = irradiance W/m^2) with a hard sun (angle 0), pixel filter
# Gaussian of width 0.01 px (rays through pixel centres, as path_trace's default; Cycles' BOX
# filter ignores its width), Standard view transform, exposure 0, 32-bit linear OpenEXR.
import json
import sys

import bpy
import numpy

# Blender 3.4's glTF importer uses numpy.bool, which Debian 12's numpy 1.24 removed.
if not hasattr(numpy, "bool"):
    numpy.bool = bool


def parse(argv):
    args = {"size": (320, 180), "spp": 1024, "sky": None, "bounces": (1, 1, 4),
            "fresnel": "schlick-nv", "ids": False, "threads": 0}
    if len(argv) < 2:
        sys.exit("usage: blender -b -P cycles_reference.py -- SCENE.gltf OUT.exr [options]")
    args["scene"], args["out"] = argv[0], argv[1]
    i = 2
    while i < len(argv):
        a = argv[i]
        if a == "--ids":
            args["ids"] = True
            i += 1
            continue
        if i + 1 >= len(argv):
            sys.exit(f"cycles_reference.py: {a} needs a value")
        v = argv[i + 1]
        if a == "--size":
            w, h = v.lower().split("x")
            args["size"] = (int(w), int(h))
        elif a == "--spp":
            args["spp"] = int(v)
        elif a == "--sky":
            args["sky"] = tuple(float(c) for c in v.split(","))
            if len(args["sky"]) == 1:
                args["sky"] = args["sky"] * 3
        elif a == "--bounces":
            args["bounces"] = tuple(int(c) for c in v.split(","))
        elif a == "--fresnel":
            if v not in ("schlick-nv", "exact"):
                sys.exit("cycles_reference.py: --fresnel is schlick-nv or exact")
            args["fresnel"] = v
        elif a == "--threads":
            args["threads"] = int(v)
        else:
            sys.exit(f"cycles_reference.py: unknown option {a}")
        i += 2
    return args


def gltf_material(m):
    """The glTF numbers of material m (spec defaults where absent)."""
    pbr = m.get("pbrMetallicRoughness", {})
    ext = m.get("extensions", {})
    for key in ("baseColorTexture", "metallicRoughnessTexture"):
        if key in pbr:
            sys.exit(f"cycles_reference.py: material '{m.get('name')}' has a {key}: not modelled")
    for key in ("normalTexture", "emissiveTexture", "occlusionTexture"):
        if key in m:
            sys.exit(f"cycles_reference.py: material '{m.get('name')}' has a {key}: not modelled")
    r = {"base": pbr.get("baseColorFactor", [1.0, 1.0, 1.0, 1.0])[:3],
         "metallic": pbr.get("metallicFactor", 1.0),
         "roughness": pbr.get("roughnessFactor", 1.0),
         "ior": ext.get("KHR_materials_ior", {}).get("ior", 1.5),
         "specular": ext.get("KHR_materials_specular", {}).get("specularFactor", 1.0),
         "transmission": ext.get("KHR_materials_transmission", {}).get("transmissionFactor", 0.0),
         "thickness": ext.get("KHR_materials_volume", {}).get("thicknessFactor", 0.0),
         "emissive": [c * ext.get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
                      for c in m.get("emissiveFactor", [0.0, 0.0, 0.0])]}
    if "specularColorFactor" in ext.get("KHR_materials_specular", {}):
        sys.exit(f"cycles_reference.py: material '{m.get('name')}' has a specularColorFactor: not modelled")
    if r["metallic"] not in (0.0, 1.0) or r["transmission"] not in (0.0, 1.0):
        sys.exit(f"cycles_reference.py: material '{m.get('name')}': metallic and transmission must be 0 or 1")
    if r["metallic"] == 1.0 and r["transmission"] == 1.0:
        r["transmission"] = 0.0  # (1 - m) T: a metal does not transmit
    return r


def fresnel_fac(nodes, links, f0, mode):
    """A socket of F0 + (1 - F0)(1 - n.v)^5 (schlick-nv) or the Fresnel node (exact, dielectric)."""
    if mode == "exact":
        return None
    lw = nodes.new("ShaderNodeLayerWeight")
    lw.inputs["Blend"].default_value = 0.5  # Facing = 1 - |n.v| exactly at blend 0.5
    p = nodes.new("ShaderNodeMath")
    p.operation = "POWER"
    links.new(lw.outputs["Facing"], p.inputs[0])
    p.inputs[1].default_value = 5.0
    if f0 is None:
        return p.outputs[0]
    lerp = nodes.new("ShaderNodeMath")
    lerp.operation = "MULTIPLY_ADD"  # (1 - F0) x t + F0
    links.new(p.outputs[0], lerp.inputs[0])
    lerp.inputs[1].default_value = 1.0 - f0
    lerp.inputs[2].default_value = f0
    return lerp.outputs[0]


def dielectric_mix(nodes, links, g, other, mode):
    """Mix Shader of `other` (weight 1 - F) and a white GGX Glossy (weight F)."""
    f0 = ((g["ior"] - 1.0) / (g["ior"] + 1.0)) ** 2 * g["specular"]
    glossy = nodes.new("ShaderNodeBsdfGlossy")
    glossy.distribution = "GGX"
    glossy.inputs["Roughness"].default_value = g["roughness"]
    glossy.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    mix = nodes.new("ShaderNodeMixShader")
    if mode == "exact":
        if g["specular"] != 1.0:
            sys.exit("cycles_reference.py: --fresnel exact needs specularFactor 1")
        fr = nodes.new("ShaderNodeFresnel")
        fr.inputs["IOR"].default_value = g["ior"]
        links.new(fr.outputs["Fac"], mix.inputs["Fac"])
    else:
        links.new(fresnel_fac(nodes, links, f0, mode), mix.inputs["Fac"])
    links.new(other, mix.inputs[1])
    links.new(glossy.outputs["BSDF"], mix.inputs[2])
    return mix.outputs["Shader"]


def build_material(mat, g, mode):
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    base = (*g["base"], 1.0)
    if g["metallic"] == 1.0:
        glossy = nodes.new("ShaderNodeBsdfGlossy")
        glossy.distribution = "GGX"
        glossy.inputs["Roughness"].default_value = g["roughness"]
        if mode == "exact":
            glossy.inputs["Color"].default_value = base
        else:
            col = nodes.new("ShaderNodeMixRGB")  # base + t (1 - base), t = (1 - n.v)^5
            col.blend_type = "MIX"
            links.new(fresnel_fac(nodes, links, None, mode), col.inputs["Fac"])
            col.inputs["Color1"].default_value = base
            col.inputs["Color2"].default_value = (1.0, 1.0, 1.0, 1.0)
            links.new(col.outputs["Color"], glossy.inputs["Color"])
        shader = glossy.outputs["BSDF"]
    elif g["transmission"] == 1.0 and g["thickness"] > 0.0:
        gl = nodes.new("ShaderNodeBsdfGlass")
        gl.distribution = "GGX"
        gl.inputs["Roughness"].default_value = g["roughness"]
        gl.inputs["IOR"].default_value = g["ior"]
        gl.inputs["Color"].default_value = base
        shader = gl.outputs["BSDF"]
    elif g["transmission"] == 1.0:
        rf = nodes.new("ShaderNodeBsdfRefraction")
        rf.distribution = "GGX"
        rf.inputs["Roughness"].default_value = g["roughness"]
        rf.inputs["IOR"].default_value = 1.0
        rf.inputs["Color"].default_value = base
        shader = dielectric_mix(nodes, links, g, rf.outputs["BSDF"], mode)
    else:
        diffuse = nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Roughness"].default_value = 0.0
        diffuse.inputs["Color"].default_value = base
        shader = diffuse.outputs["BSDF"]
        if g["specular"] > 0.0:
            shader = dielectric_mix(nodes, links, g, shader, mode)
    if any(c > 0.0 for c in g["emissive"]):
        em = nodes.new("ShaderNodeEmission")
        em.inputs["Color"].default_value = (*g["emissive"], 1.0)
        em.inputs["Strength"].default_value = 1.0
        add = nodes.new("ShaderNodeAddShader")
        links.new(shader, add.inputs[0])
        links.new(em.outputs["Emission"], add.inputs[1])
        shader = add.outputs["Shader"]
    links.new(shader, out.inputs["Surface"])


def build_id_material(mat, k):
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    em = nodes.new("ShaderNodeEmission")
    em.inputs["Color"].default_value = (float(k + 1), 0.0, 0.0, 1.0)
    em.inputs["Strength"].default_value = 1.0
    links.new(em.outputs["Emission"], out.inputs["Surface"])


def main():
    args = parse(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
    with open(args["scene"]) as f:
        doc = json.load(f)
    materials = doc.get("materials", [])
    names = [m.get("name", f"material{k}") for k, m in enumerate(materials)]
    if len(set(names)) != len(names):
        sys.exit("cycles_reference.py: material names must be unique")

    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=args["scene"], convert_lighting_mode="COMPAT")
    scene = bpy.context.scene
    for obj in scene.objects:
        if obj.type == "CAMERA" and scene.camera is None:
            scene.camera = obj
        if obj.type == "LIGHT":
            if obj.data.type == "SUN":
                obj.data.angle = 0.0
            else:
                obj.data.shadow_soft_size = 0.0
            if args["ids"]:
                obj.data.energy = 0.0
    if scene.camera is None:
        sys.exit("cycles_reference.py: the scene has no camera")

    # the importer names each Blender material after its glTF material; one no primitive uses (a
    # file's spare default) is not imported
    used = {p["material"] for m in doc.get("meshes", []) for p in m["primitives"] if "material" in p}
    for k, name in enumerate(names):
        mat = bpy.data.materials.get(name)
        if mat is None and k not in used:
            continue
        if mat is None:
            sys.exit(f"cycles_reference.py: material '{name}' was not imported")
        if args["ids"]:
            build_id_material(mat, k)
        else:
            build_material(mat, gltf_material(materials[k]), args["fresnel"])
            print(f"cycles_reference.py: material {k} '{name}' rebuilt")

    world = bpy.data.worlds.new("sky")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    if args["sky"] is None or args["ids"]:
        bg.inputs["Strength"].default_value = 0.0
    else:
        bg.inputs["Color"].default_value = (*args["sky"], 1.0)
        bg.inputs["Strength"].default_value = 1.0
    scene.world = world

    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = 1 if args["ids"] else args["spp"]
    c.use_adaptive_sampling = False
    c.use_denoising = False
    d, g, t = (0, 0, 0) if args["ids"] else args["bounces"]
    c.diffuse_bounces, c.glossy_bounces, c.transmission_bounces = d, g, t
    c.max_bounces = d + g + t
    c.volume_bounces = 0
    c.transparent_max_bounces = 0
    c.caustics_reflective = False
    c.caustics_refractive = False
    c.blur_glossy = 0.0
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.filter_type = "GAUSSIAN"
    c.filter_width = 0.01
    c.seed = 1
    if args["threads"] > 0:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = args["threads"]
    scene.render.resolution_x, scene.render.resolution_y = args["size"]
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    s = scene.render.image_settings
    s.file_format = "OPEN_EXR"
    s.color_depth = "32"
    s.color_mode = "RGBA"
    s.exr_codec = "ZIP"
    scene.render.filepath = args["out"]
    bpy.ops.render.render(write_still=True)


main()
