/* Uniform buffers of the pass blocks (sdk/blocks.h). */
#include "sdk/blocks.h"

#include "sdk/pass.h"

GLuint
cgp_uniform_buffer(void *state, size_t bytes)
{
    return cgp_buffer(state, bytes, NULL, GL_DYNAMIC_STORAGE_BIT);
}

void
cgp_uniform_upload(GLuint buffer, GLuint binding, const void *block, size_t bytes)
{
    glNamedBufferSubData(buffer, 0, (GLsizeiptr)bytes, block);
    glBindBufferBase(GL_UNIFORM_BUFFER, binding, buffer);
}
