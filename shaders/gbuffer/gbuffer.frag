// gbuffer: world position (w = 1 where a surface covers the pixel), shading normal facing the
// camera, emitted radiance and the glTF 2.0 BSDF's quantities (passes/gbuffer/gbuffer.c lists them).
#version 450 core
#include "common/scene.glsl"

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec2 texcoord;
layout(location = 3) in vec4 world_tangent;
layout(location = 4) in float thickness_scale;

// 1 while the pass draws the height-field meshes (gbuffer.c), 0 for the others.
layout(location = 9) uniform int cg_gbuffer_heightfield;

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_albedo;
layout(location = 3) out vec4 out_emissive;
layout(location = 4) out vec4 out_specular;
layout(location = 5) out vec4 out_transmission;
layout(location = 6) out vec4 out_material;
layout(location = 7) out vec4 out_attenuation;

void
main()
{
    int material = cg_material_index;
    // glTF doubleSided false: the camera does not see a back face (glTF 3.9.2); cg_gpu_scene_draw
    // turns the front face over for a mirroring instance.
    if (!gl_FrontFacing && !cg_material_double_sided(material))
        discard;
    vec4 base = cg_material_base_color(material, texcoord);
    int alpha_mode = cg_material_alpha_mode(material);
    // alphaMode MASK: nothing there below the cutoff (glTF 3.9.4).
    if (alpha_mode == CG_ALPHA_MASK && base.a < cg_materials[material].emissive.w)
        discard;

    // Surfaces are shaded on both sides (glTF meshes here are not closed): the normal
    // is turned towards the viewer. The normal map bends it in the front face's frame first; a
    // back face's frame is the front's turned over (N, T and B alike), so the result turns too.
    vec3 n = cg_material_normal(material, texcoord, world_normal, world_tangent);
    if (!gl_FrontFacing)
        n = -n;
    // A height field (hybrid eq. 5: one surface over the ground plane) is seen from above. At a
    // crest's silhouette the slope behind it, back-facing, meets the front slope at the crest
    // and can win the depth test at a pixel; turned to the viewer, its normal points into the
    // ground, and a cone gather from there reads the terrain's lit top from below (the hybrid's
    // 2D lightmap has no underside: 0.069 where the path tracer has 0.007, docs/hybrid.md).
    // Where the viewer sees a height field's triangle from below, its upper side is the one
    // shaded. The geometric normal towards the viewer is cross(dFdx, dFdy) in GL's window
    // coordinates; 0.01 keeps a vertical cliff, seen from either side, turned to the viewer.
    if (cg_gbuffer_heightfield != 0) {
        vec3 towards_viewer = normalize(cross(dFdx(world_position), dFdy(world_position)));
        if (towards_viewer.y < -0.01)
            n = -n;
    }

    vec2 metallic_roughness = cg_material_metallic_roughness(material, texcoord);
    CgBsdf b = cg_bsdf_from_material(material, base, metallic_roughness.x, metallic_roughness.y,
                                     cg_material_transmission(material, texcoord));
    // alphaMode BLEND: a see-through layer of coverage alpha (docs/gltf.md): the material's lobes
    // weigh alpha, and 1 - alpha goes straight through, a thin transmission of tint 1 and ior 1.
    // One ior per pixel: the material's where its own transmission outweighs the hole's.
    float coverage = alpha_mode == CG_ALPHA_BLEND ? clamp(base.a, 0.0, 1.0) : 1.0;
    vec3 tau = b.transmission;
    float ior = b.ior;
    if (alpha_mode == CG_ALPHA_BLEND) {
        tau = coverage * b.transmission + (1.0 - coverage);
        float own = coverage * (1.0 - metallic_roughness.x) * cg_material_transmission(material, texcoord);
        ior = own >= 1.0 - coverage ? b.ior : 1.0;
    }

    out_position = vec4(world_position, 1.0);
    out_normal = vec4(n, 1.0);
    out_albedo = vec4(b.diffuse * coverage, cg_material_occlusion(material, texcoord));
    out_emissive = vec4(cg_material_emissive(material, texcoord), 1.0);
    out_specular = vec4(b.f0 * coverage, b.f90 * coverage);
    out_transmission = vec4(tau, ior);
    // Thickness in world metres: KHR_materials_volume gives it in the mesh's units.
    out_material = vec4(b.roughness, metallic_roughness.x, b.thickness * thickness_scale, 1.0);
    out_attenuation = vec4(b.sigma, 1.0);
}
