// vds internal: the table generated from shaders/ by cmake/embed_shaders.cmake.
#pragma once

#include <cstddef>

namespace vds::detail {
struct EmbeddedShader {
    const char* path;
    const char* text;
    std::size_t size;
};
extern const EmbeddedShader kEmbeddedShaders[];
extern const std::size_t kEmbeddedShaderCount;
} // namespace vds::detail
