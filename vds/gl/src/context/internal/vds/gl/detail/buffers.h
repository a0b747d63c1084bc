// vds::gl internal: GL buffers made in one call, for every room of vds::gl
// and for vds::voxel (buffers.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <vds/gl/objects.h>

namespace vds::detail {

/// An immutable buffer holding `bytes` of `data` (at least 4 bytes: GL
/// refuses empty storage; `data` may be null for contents left undefined).
/// Throws `GlError` naming `what`.
Buffer uploadBuffer(const void* data, std::size_t bytes, const char* what);

/// Throws `OutOfMemory` if `bytes` exceed `limit`, what one shader storage
/// block may hold (`GlLimits::maxStorageBlockBytes`); `what` names the buffer.
void requireStorageSize(std::size_t bytes, std::uint64_t limit, const std::string& what);

/// A storage buffer of `bytes` (at most `limit`, as `requireStorageSize`),
/// zeroed, for GPU reads and writes. Throws `OutOfMemory` naming `what`.
Buffer zeroedBuffer(std::size_t bytes, std::uint64_t limit, const char* what);

} // namespace vds::detail
