// common/scene.glsl: how a program sees the scene drawn by cg_gpu_scene_draw (cg/gpu_scene.h).
//
// Every program drawn with cg_gpu_scene_draw includes this file, so that uniform locations
// 0..2 mean the same in every such program (the draw sets those the program keeps active).
// A vertex stage defines
// CG_SCENE_VERTEX before the include to get the vertex inputs. Pass-specific uniforms
// start at location 8.
//
// Materials: glTF 2.0 metallic-roughness (cg/scene.h, struct cg_material) with KHR_texture_transform
// applied to every texture's TEXCOORD_0. The cg_material_* functions give a texel's values: base
// colour, alpha and MASK, emission, metallic and roughness, occlusion, transmission, the
// normal-mapped shading normal, and the BSDF (cg_bsdf_from_material, common/bsdf.glsl's model).
#ifndef CG_SCENE_GLSL
#define CG_SCENE_GLSL

#include "common/bsdf.glsl"

// cg_alpha_mode.
#define CG_ALPHA_OPAQUE 0
#define CG_ALPHA_MASK 1
#define CG_ALPHA_BLEND 2

// cg_material_texture: the index of a texture's uv transform.
#define CG_TEX_BASE_COLOR 0
#define CG_TEX_EMISSIVE 1
#define CG_TEX_METALLIC_ROUGHNESS 2
#define CG_TEX_NORMAL 3
#define CG_TEX_OCCLUSION 4
#define CG_TEX_TRANSMISSION 5

// CgMaterial.textures2.w bits (CG_GPU_MATERIAL_DOUBLE_SIDED).
#define CG_MATERIAL_DOUBLE_SIDED 1

// Floats per vertex of a mesh's vertex buffer (CG_GPU_VERTEX_FLOATS): position 3, normal 3,
// texcoord 2, tangent 4.
#define CG_VERTEX_FLOATS 12u

// Mirrors gpu_material in core/gl/gpu_scene.c (std430, 320 bytes).
struct CgMaterial {
    vec4 base_color;    // linear RGBA factor
    vec4 emissive;      // rgb = emissive factor x KHR_materials_emissive_strength, w = alpha cutoff
    ivec4 textures;     // base colour, emissive, metallicRoughness, normal texture (-1 = none)
    ivec4 textures2;    // x = occlusion, y = transmission texture (-1 = none), z = alpha mode, w = flags
    vec4 pbr;           // x = metallic, y = roughness, z = normal scale, w = occlusion strength
    vec4 specular;      // rgb = specular colour, a = specular factor (KHR_materials_specular)
    vec4 volume;        // x = ior, y = transmission factor, z = thickness (mesh units)
    vec4 attenuation;   // rgb = sigma = -ln(attenuationColor) / attenuationDistance (1/m)
    vec4 uv[12];        // per texture (CG_TEX_*): (m0, m1, m2, m3), (m4, m5, 0, 0) of its transform
};

layout(std430, binding = 0) readonly buffer CgMaterials {
    CgMaterial cg_materials[];
};

layout(location = 0) uniform mat4 cg_model;
layout(location = 1) uniform mat3 cg_normal_matrix;
layout(location = 2) uniform int cg_material_index;

// A 1x1 white texture is bound where a material has none, so sampling is always valid and gives
// the factors alone (CG_SCENE_UNIT_* of cg/gpu_scene.h).
layout(binding = 0) uniform sampler2D cg_base_color_texture;
layout(binding = 1) uniform sampler2D cg_emissive_texture;
layout(binding = 24) uniform sampler2D cg_metallic_roughness_texture;
layout(binding = 25) uniform sampler2D cg_normal_texture;
layout(binding = 26) uniform sampler2D cg_occlusion_texture;
layout(binding = 27) uniform sampler2D cg_transmission_texture;

#ifdef CG_SCENE_VERTEX
layout(location = 0) in vec3 cg_position;
layout(location = 1) in vec3 cg_normal;
layout(location = 2) in vec2 cg_texcoord;
layout(location = 3) in vec4 cg_tangent;   // xyz unit tangent, w = bitangent sign; 0: none
#endif

// KHR_texture_transform: uv' = (m0, m1) u + (m2, m3) v + (m4, m5).
vec2
cg_material_uv(int material, int texture_slot, vec2 uv)
{
    vec4 a = cg_materials[material].uv[2 * texture_slot];
    vec4 b = cg_materials[material].uv[2 * texture_slot + 1];
    return a.xy * uv.x + a.zw * uv.y + b.xy;
}

// baseColorFactor x baseColorTexture (sRGB-decoded by GL), linear RGBA.
vec4
cg_material_base_color(int material, vec2 uv)
{
    return cg_materials[material].base_color *
           texture(cg_base_color_texture, cg_material_uv(material, CG_TEX_BASE_COLOR, uv));
}

// metallic (x) and perceptual roughness (y): the factors x the metallicRoughness texture's B and G.
vec2
cg_material_metallic_roughness(int material, vec2 uv)
{
    // No texture: the factors, without a read of the white texture (llvmpipe pays for each).
    if (cg_materials[material].textures.z < 0)
        return clamp(cg_materials[material].pbr.xy, 0.0, 1.0);
    vec4 t = texture(cg_metallic_roughness_texture, cg_material_uv(material, CG_TEX_METALLIC_ROUGHNESS, uv));
    return clamp(cg_materials[material].pbr.xy * t.bg, 0.0, 1.0);
}

// KHR_materials_transmission: the factor x the texture's R.
float
cg_material_transmission(int material, vec2 uv)
{
    if (cg_materials[material].textures2.y < 0)
        return clamp(cg_materials[material].volume.y, 0.0, 1.0);
    float t = texture(cg_transmission_texture, cg_material_uv(material, CG_TEX_TRANSMISSION, uv)).r;
    return clamp(cg_materials[material].volume.y * t, 0.0, 1.0);
}

// glTF occlusionTexture: 1 + strength (R - 1); 1 where there is none. It darkens indirect light only.
float
cg_material_occlusion(int material, vec2 uv)
{
    if (cg_materials[material].textures2.x < 0)
        return 1.0;
    float occ = texture(cg_occlusion_texture, cg_material_uv(material, CG_TEX_OCCLUSION, uv)).r;
    return 1.0 + cg_materials[material].pbr.w * (occ - 1.0);
}

int
cg_material_alpha_mode(int material)
{
    return cg_materials[material].textures2.z;
}

bool
cg_material_double_sided(int material)
{
    return (cg_materials[material].textures2.w & CG_MATERIAL_DOUBLE_SIDED) != 0;
}

// alphaMode MASK: the surface is not there where its alpha is below alphaCutoff (glTF 3.9.4),
// for the camera, the shadows and the voxels alike. The base colour texture is read only for
// MASK materials.
bool
cg_material_masked_out(int material, vec2 uv)
{
    if (cg_material_alpha_mode(material) != CG_ALPHA_MASK)
        return false;
    return cg_material_base_color(material, uv).a < cg_materials[material].emissive.w;
}

// The BSDF of `material` at a point whose base colour, metallic, roughness and transmission
// (factors x textures) are given: the mirror of cg_bsdf_from_material (cg/bsdf.h; the same
// clamps). sigma was computed at upload as the C side computes it.
CgBsdf
cg_bsdf_from_material(int material, vec4 base_color, float metallic, float roughness, float transmission)
{
    float metal = clamp(metallic, 0.0, 1.0), trans = clamp(transmission, 0.0, 1.0);
    float rough = clamp(roughness, 0.0, 1.0);
    vec4 volume = cg_materials[material].volume, specular = cg_materials[material].specular;
    float ior = volume.x > 0.0 ? volume.x : 1.5;
    // KHR_materials_ior, KHR_materials_specular; glTF Appendix B.3.5's mix by metallic.
    float r = (ior - 1.0) / (ior + 1.0);
    vec3 f0_dielectric = min(vec3(r * r) * specular.rgb, vec3(1.0)) * specular.a;
    CgBsdf b;
    b.f0 = f0_dielectric + (base_color.rgb - f0_dielectric) * metal;
    b.diffuse = (1.0 - metal) * (1.0 - trans) * base_color.rgb;
    b.transmission = (1.0 - metal) * trans * base_color.rgb;
    b.sigma = cg_materials[material].attenuation.rgb;
    b.f90 = specular.a + (1.0 - specular.a) * metal;
    b.roughness = rough;
    b.alpha = rough * rough;
    b.ior = ior;
    b.thickness = max(volume.z, 0.0);
    return b;
}

// The BSDF of `material` at texture coordinate uv, its textures read.
CgBsdf
cg_material_bsdf(int material, vec2 uv)
{
    vec2 mr = cg_material_metallic_roughness(material, uv);
    return cg_bsdf_from_material(material, cg_material_base_color(material, uv), mr.x, mr.y,
                                 cg_material_transmission(material, uv));
}

// The diffuse albedo: rgb = the Lambertian lobe's weight rho = (1 - metallic)(1 - transmission)
// baseColor (glTF Appendix B.3.5: metals and transmission have no diffuse lobe), a = base alpha.
// For a Lambertian material (metallic 0, no transmission) baseColorFactor x baseColorTexture, as
// before the material model grew.
vec4
cg_material_albedo(int material, vec2 uv)
{
    vec4 base = cg_material_base_color(material, uv);
    float metallic = cg_material_metallic_roughness(material, uv).x;
    float transmission = cg_material_transmission(material, uv);
    return vec4((1.0 - metallic) * (1.0 - transmission) * base.rgb, base.a);
}

// What the diffuse lobe reflects, as voxels store it: rho x its hemispherical (1 - F)
// (cg_bsdf_diffuse_hemispherical), x the coverage alpha of a BLEND layer (whose 1 - alpha is a hole
// the light goes straight through). rho exactly for a Lambertian material (F0 = F90 = 0).
vec3
cg_material_diffuse(int material, vec2 uv)
{
    CgBsdf b = cg_material_bsdf(material, uv);
    vec3 diffuse = b.f90 == 0.0 && all(equal(b.f0, vec3(0.0))) ? b.diffuse : cg_bsdf_diffuse_hemispherical(b);
    if (cg_material_alpha_mode(material) == CG_ALPHA_BLEND)
        diffuse *= clamp(cg_material_base_color(material, uv).a, 0.0, 1.0);
    return diffuse;
}

// Emitted radiance = emissiveFactor x emissiveTexture x emissive strength (DESIGN.md units).
vec3
cg_material_emissive(int material, vec2 uv)
{
    return cg_materials[material].emissive.rgb *
           texture(cg_emissive_texture, cg_material_uv(material, CG_TEX_EMISSIVE, uv)).rgb;
}

// The shading normal (glTF 3.9.3, normalTexture): the tangent-space normal (2 x texel - 1, x and y
// scaled by normalTexture.scale) in the frame (T, B = w N x T, N) of the interpolated world normal n
// and world tangent t (xyz, w the bitangent sign). n unchanged where the material has no normal
// texture or the mesh no tangents (t = 0). n and t need not be unit.
vec3
cg_material_normal(int material, vec2 uv, vec3 n, vec4 t)
{
    vec3 nn = normalize(n);
    if (cg_materials[material].textures.w < 0 || dot(t.xyz, t.xyz) == 0.0)
        return nn;
    // Gram-Schmidt: interpolation leaves t off the plane of the interpolated normal.
    vec3 tt = t.xyz - nn * dot(nn, t.xyz);
    if (dot(tt, tt) <= 1e-12 * dot(t.xyz, t.xyz))
        return nn;
    tt = normalize(tt);
    vec3 bb = (t.w < 0.0 ? -1.0 : 1.0) * cross(nn, tt);
    vec3 m = texture(cg_normal_texture, cg_material_uv(material, CG_TEX_NORMAL, uv)).rgb * 2.0 - 1.0;
    m.xy *= cg_materials[material].pbr.z;
    vec3 shaded = m.x * tt + m.y * bb + m.z * nn;
    return dot(shaded, shaded) > 0.0 ? normalize(shaded) : nn;
}

#endif
