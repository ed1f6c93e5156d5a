/* Uniform buffers of the pass blocks (sdk/blocks.h). */
#include "sdk/blocks.h"

GLuint
cgp_uniform_buffer(size_t bytes)
{
    GLuint buffer;
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, (GLsizeiptr)bytes, NULL, GL_DYNAMIC_STORAGE_BIT);
    return buffer;
}

void
cgp_uniform_upload(GLuint buffer, GLuint binding, const void *block, size_t bytes)
{
    glNamedBufferSubData(buffer, 0, (GLsizeiptr)bytes, block);
    glBindBufferBase(GL_UNIFORM_BUFFER, binding, buffer);
}
