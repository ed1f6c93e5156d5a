// shadow_map (scenes with an alphaMode MASK material): a texel below the material's alphaCutoff is
// not there, for the light as for the camera (glTF 3.9.4); every other fragment writes its depth.
#version 450 core
#include "common/scene.glsl"

layout(location = 0) in vec2 texcoord;

void
main()
{
    if (cg_material_masked_out(cg_material_index, texcoord))
        discard;
}
