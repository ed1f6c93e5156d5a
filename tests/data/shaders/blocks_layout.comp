#version 450 core
// tests/data/shaders/blocks_layout.comp: declares every block of common/blocks.h as the passes'
// shaders do, so that tests/test_pass_sdk.c can ask GL for their sizes and member offsets and
// compare them with the C structs. Each block is read, so that the linker keeps it.
#include "common/blocks.h"

layout(local_size_x = 1) in;

CG_UNIFORM_BLOCK(CgShadow, cg_shadow_block, CG_BINDING_SHADOW, CG_SHADOW_BLOCK);
CG_UNIFORM_BLOCK(CgVolumeBlock, cg_volume_block, CG_BINDING_VOLUME, CG_VOLUME_BLOCK);
CG_UNIFORM_BLOCK(CgHeightmapBlock, cg_heightmap_block, CG_BINDING_HEIGHTMAP, CG_HEIGHTMAP_BLOCK);
CG_UNIFORM_BLOCK(CgConeSet, cg_cone_set_block, CG_BINDING_CONES, CG_CONE_SET_BLOCK);
CG_UNIFORM_BLOCK(CgConeGather, cg_cone_gather_block, CG_BINDING_GATHER, CG_CONE_GATHER_BLOCK);
CG_UNIFORM_BLOCK(CgHybridGather, cg_hybrid_gather_block, 9, CG_HYBRID_GATHER_BLOCK);
CG_UNIFORM_BLOCK(CgSkyBlock, cg_sky_block, CG_BINDING_SKY, CG_SKY_BLOCK);
CG_STORAGE_BLOCK(readonly, CgHsatInfo, cg_hsat_info, CG_BINDING_HSAT, CG_HSAT_INFO_BLOCK);

layout(std430, binding = 0) writeonly buffer Sink { vec4 sink; };

void
main()
{
    sink = cg_shadow_block.view[0] + cg_volume_block.info + cg_heightmap_block.info + cg_cone_set_block.march +
           cg_cone_gather_block.camera + vec4(cg_hybrid_gather_block.switches) + cg_sky_block.info +
           cg_hsat_info.params;
}
