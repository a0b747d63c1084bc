// The .vds file's checksum (docs/format.md, "Checksum"), apart from the
// reader and writer that use it.
#pragma once

#include <cstdint>

#include <vds/sprite.h>

namespace vds::detail {

/// The checksum of docs/format.md: every field of the sprite, in this order,
/// as the file's format `version` lays them out (1, 2 or 3).
std::uint64_t spriteChecksum(const Sprite& s, int version);

} // namespace vds::detail
