#include <vds/gl/detail/dispatch.h>

#include <algorithm>
#include <string>

#include <GL/glext.h>

#include <vds/error.h>

namespace vds::detail {

namespace {
constexpr std::uint64_t kMaxGroups = 65535; // per dimension, the least GL guarantees
} // namespace

void dispatchGroups(std::uint64_t groups) {
    if (groups <= kMaxGroups) {
        glDispatchCompute(GLuint(std::max<std::uint64_t>(groups, 1)), 1, 1);
        return;
    }
    const std::uint64_t rows = (groups + kMaxGroups - 1) / kMaxGroups;
    if (rows > kMaxGroups) throw OutOfMemory("a compute pass of " + std::to_string(groups) + " workgroups is too large");
    glDispatchCompute(GLuint(kMaxGroups), GLuint(rows), 1);
}

void dispatchItems(std::size_t items, std::uint32_t local) {
    if (items == 0) return;
    dispatchGroups((std::uint64_t(items) + local - 1) / local);
}

GLuint strideGroups(std::uint64_t items, std::uint32_t local) {
    return GLuint(std::clamp<std::uint64_t>((items + local - 1) / local, 1, kMaxGroups));
}

} // namespace vds::detail
