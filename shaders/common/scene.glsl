// common/scene.glsl: how a program sees the scene drawn by cg_gpu_scene_draw (cg/gpu_scene.h).
//
// Every program drawn with cg_gpu_scene_draw includes this file, so that uniform locations
// 0..2 mean the same in every such program (the draw sets those the program keeps active).
// A vertex stage defines
// CG_SCENE_VERTEX before the include to get the vertex inputs. Pass-specific uniforms
// start at location 8.
#ifndef CG_SCENE_GLSL
#define CG_SCENE_GLSL

// Mirrors gpu_material in core/gl/gpu_scene.c (std430, 64 bytes).
struct CgMaterial {
    vec4 base_color;    // linear RGBA factor
    vec4 emissive;      // rgb = emissive factor x KHR_materials_emissive_strength
    ivec4 textures;     // x = base colour texture, y = emissive texture (-1 = none)
    vec4 pbr;           // x = metallic, y = roughness
};

layout(std430, binding = 0) readonly buffer CgMaterials {
    CgMaterial cg_materials[];
};

layout(location = 0) uniform mat4 cg_model;
layout(location = 1) uniform mat3 cg_normal_matrix;
layout(location = 2) uniform int cg_material_index;

// A 1x1 white texture is bound where a material has none, so sampling is always valid.
layout(binding = 0) uniform sampler2D cg_base_color_texture;
layout(binding = 1) uniform sampler2D cg_emissive_texture;

#ifdef CG_SCENE_VERTEX
layout(location = 0) in vec3 cg_position;
layout(location = 1) in vec3 cg_normal;
layout(location = 2) in vec2 cg_texcoord;
#endif

// Lambertian albedo = baseColorFactor x baseColorTexture (the texture is sRGB-decoded by GL).
vec4 cg_material_albedo(int material, vec2 uv)
{
    return cg_materials[material].base_color * texture(cg_base_color_texture, uv);
}

// Emitted radiance = emissiveFactor x emissiveTexture x emissive strength (DESIGN.md units).
vec3 cg_material_emissive(int material, vec2 uv)
{
    return cg_materials[material].emissive.rgb * texture(cg_emissive_texture, uv).rgb;
}

#endif
