// common/world_vertex.glsl: the vertex stage of the passes that rasterize the scene and shade
// in world space (gbuffer, heightmap_raster, voxelize): the world position, normal and texture
// coordinates handed on at locations 0, 1 and 2, which the next stage reads under its own names
// (stages match by location). Includes common/scene.glsl with its vertex inputs.
#ifndef CG_WORLD_VERTEX_GLSL
#define CG_WORLD_VERTEX_GLSL

#define CG_SCENE_VERTEX
#include "common/scene.glsl"

layout(location = 0) out vec3 cg_world_position;
layout(location = 1) out vec3 cg_world_normal;
layout(location = 2) out vec2 cg_world_texcoord;

// Writes the three outputs and returns the world position (w = 1), for the pass's projection.
vec4
cg_world_vertex()
{
    vec4 world = cg_model * vec4(cg_position, 1.0);
    cg_world_position = world.xyz;
    cg_world_normal = cg_normal_matrix * cg_normal;
    cg_world_texcoord = cg_texcoord;
    return world;
}

#endif
