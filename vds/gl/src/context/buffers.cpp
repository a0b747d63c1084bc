#include <vds/gl/detail/buffers.h>

#include <algorithm>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/context.h>

namespace vds::detail {

Buffer uploadBuffer(const void* data, std::size_t bytes, const char* what) {
    Buffer b = Buffer::create();
    glNamedBufferStorage(b.id(), GLsizeiptr(std::max<std::size_t>(bytes, 4)), bytes ? data : nullptr, 0);
    checkGl(what);
    return b;
}

void requireStorageSize(std::size_t bytes, std::uint64_t limit, const std::string& what) {
    if (bytes > limit)
        throw OutOfMemory(what + " needs " + std::to_string(bytes) + " bytes, more than one GL storage buffer holds (" +
                          std::to_string(limit) + "); lower the resolution");
}

Buffer zeroedBuffer(std::size_t bytes, std::uint64_t limit, const char* what) {
    requireStorageSize(bytes, limit, what);
    Buffer b = Buffer::create();
    glNamedBufferStorage(b.id(), GLsizeiptr(std::max<std::size_t>(bytes, 4)), nullptr, GL_DYNAMIC_STORAGE_BIT);
    if (glGetError() == GL_OUT_OF_MEMORY) throw OutOfMemory(std::string("GL cannot allocate ") + what);
    const GLuint zero = 0;
    glClearNamedBufferData(b.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    checkGl(what);
    return b;
}

} // namespace vds::detail
