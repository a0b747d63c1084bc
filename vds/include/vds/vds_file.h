// vds: the .vds file, one self-describing OpenEXR deep scanline image.
//
// The LDI is a deep image: pixel (i, j) holds one sample per crossing of its
// column, so only real crossings are stored, and the file is compressed
// losslessly (ZIP). Channels: "Z" (FLOAT, depth in [0,1] along the view) and
// "entering" (UINT, 1 where the ray enters the solid). The sprite's metadata
// are header attributes named "vds.*"; see docs/format.md.
#pragma once

#include <string>

#include <vds/sprite.h>

namespace vds {

/// Writes `sprite` to `path` atomically: to a temporary file beside it, then
/// renamed, so an interrupted write never leaves a half-written file.
/// Throws `IoError`.
void writeSprite(const Sprite& sprite, const std::string& path);

/// Reads a .vds file. Throws `IoError` if it cannot be opened and
/// `FormatError` (one line naming the problem) if it is not a .vds file, is
/// truncated or corrupt, or its parts disagree. Never crashes on bad input.
Sprite readSprite(const std::string& path);

} // namespace vds
