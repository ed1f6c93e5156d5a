/* cg/shader.h: GLSL 450 programs loaded from shaders/, with #include.
 *
 * Declares: cg_shader_dir, cg_shader_source_load, cg_program_compute, cg_program_graphics.
 *
 * `#include "common/foo.glsl"` is resolved against the shader directory and
 * expanded with #line directives; each file gets a source-string number, and
 * compile logs are rewritten so that "0:12(3)" reads "common/foo.glsl:12(3)".
 * The shader directory is $CONEGRAPH_SHADER_DIR if set, else the source tree's
 * shaders/ (a build run from its build dir), else the installed data directory.
 */
#ifndef CG_SHADER_H
#define CG_SHADER_H

#include <stdbool.h>
#include <glad/gl.h>

#include "cg/error.h"

/* The directory shader paths are relative to. */
const char *cg_shader_dir(void);

/* Reads `path` (relative to cg_shader_dir(), or absolute), expands includes, and
 * prepends `#version 450 core` plus `defines` (may be NULL; e.g. "#define CONES 6\n")
 * after the file's own #version line. The caller frees *out. */
bool cg_shader_source_load(const char *path, const char *defines, char **out, cg_error *err);

/* Compiles and links a compute program. */
bool cg_program_compute(const char *path, const char *defines, GLuint *out, cg_error *err);

/* Compiles and links vertex (+ optional geometry) + fragment. gs may be NULL; fs may be NULL (depth-only). */
bool cg_program_graphics(const char *vs, const char *gs, const char *fs, const char *defines,
                         GLuint *out, cg_error *err);

#endif
