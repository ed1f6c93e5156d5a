// common/reads.glsl: the texture reads of a pass's cone marches, counted for the frame (the
// figure `render --report`, `--pass-costs`, bench and the demo print beside the pass's time:
// fg_pass_report_reads in cg/fg.h). A count does not depend on the machine's speed or load, so a
// GPU's cost can be estimated from an llvmpipe run and two settings compared on a busy machine.
//
// CG_READ(n) adds n reads to this invocation's count, cg_reads: one a textureLod or texelFetch
// call of the 3D or 2D lightmap, whatever its filter reads. cg_reads_commit(traced), once at the end
// of an invocation, adds that count, and 1 when `traced` (the invocation traced the pixel's or
// voxel's own diffuse cones), to the pass's counter at CG_BINDING_READS. The reads are 64 bits,
// low word first with its carry: at 1065-1560 reads a traced pixel (the built-in scenes, 26 cones),
// a 1920x1080 frame traced at every pixel reads 2.2-3.2 x 10^9, within a factor 2 of 2^32.
// One atomic a counter an invocation: against its thousands of reads, nothing on llvmpipe.
#ifndef CG_READS_GLSL
#define CG_READS_GLSL

layout(std430, binding = CG_BINDING_READS) buffer CgReads {
    uint cg_reads_low, cg_reads_high, cg_reads_traced, cg_reads_unused;
};

uint cg_reads = 0u;
#define CG_READ(n) cg_reads += uint(n)

void
cg_reads_commit(bool traced)
{
    if (cg_reads != 0u) {
        uint before = atomicAdd(cg_reads_low, cg_reads);
        if (before > 0xffffffffu - cg_reads)
            atomicAdd(cg_reads_high, 1u);
    }
    if (traced)
        atomicAdd(cg_reads_traced, 1u);
}

#endif
