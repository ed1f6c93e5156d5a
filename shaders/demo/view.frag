// demo view: one level of one 2D texture, 3D slice or array layer of a graph resource, nearest
// texel per target pixel, mapped to display values: (value - offset) x scale, clamped to 0..1
// (the target's sRGB encoding, when on, is the framebuffer's). Defines: VIEW_3D or VIEW_ARRAY
// (else 2D); VIEW_UINT, VIEW_INT or VIEW_DEPTH (else a float colour).
#version 450 core

#if defined(VIEW_UINT)
#  if defined(VIEW_3D)
layout(binding = 0) uniform usampler3D source;
#  elif defined(VIEW_ARRAY)
layout(binding = 0) uniform usampler2DArray source;
#  else
layout(binding = 0) uniform usampler2D source;
#  endif
#elif defined(VIEW_INT)
#  if defined(VIEW_3D)
layout(binding = 0) uniform isampler3D source;
#  elif defined(VIEW_ARRAY)
layout(binding = 0) uniform isampler2DArray source;
#  else
layout(binding = 0) uniform isampler2D source;
#  endif
#else
#  if defined(VIEW_3D)
layout(binding = 0) uniform sampler3D source;
#  elif defined(VIEW_ARRAY)
layout(binding = 0) uniform sampler2DArray source;
#  else
layout(binding = 0) uniform sampler2D source;
#  endif
#endif

layout(location = 0) uniform ivec2 source_size;   // texels of the level
layout(location = 1) uniform ivec2 target_size;   // pixels
layout(location = 2) uniform int level;
layout(location = 3) uniform int layer;           // 3D slice or array layer
layout(location = 4) uniform int channel;         // 0: RGB; 1..4: R, G, B or A as grey
layout(location = 5) uniform float offset;
layout(location = 6) uniform float scale;

layout(location = 0) out vec4 colour;

void
main()
{
    ivec2 texel = min(ivec2(gl_FragCoord.xy) * source_size / target_size, source_size - 1);
#if defined(VIEW_3D) || defined(VIEW_ARRAY)
    vec4 value = vec4(texelFetch(source, ivec3(texel, layer), level));
#else
    vec4 value = vec4(texelFetch(source, texel, level));
#endif
    value = (value - offset) * scale;
#if defined(VIEW_DEPTH)
    vec3 shown = value.rrr;
#else
    vec3 shown = channel == 0 ? value.rgb : vec3(value[channel - 1]);
#endif
    colour = vec4(clamp(shown, 0.0, 1.0), 1.0);
}
