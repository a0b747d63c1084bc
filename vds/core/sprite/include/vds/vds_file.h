// vds: the .vds file, one self-describing OpenEXR deep scanline image.
//
// The LDI is a deep image: pixel (i, j) holds one sample per crossing of
// column c = j * width + i, so only real crossings are stored, and the file is
// compressed losslessly (ZIPS: zlib per scanline). Channels: "Z" (FLOAT, depth
// in [0,1] along the view) and "entering" (UINT, 1 where the ray enters the
// solid). The sprite's metadata are header attributes named "vds.*", and a
// 64-bit FNV-1a checksum over all of it catches damage zlib cannot see and
// edited attributes; see docs/format.md.
//
// Calls on different files may run concurrently. Both hold the whole encoded
// file in memory while they run, and use OpenEXR's global thread pool as the
// program configured it (by default: no threads).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <vds/sprite.h>

namespace vds {

/// The bytes of `sprite`'s .vds file, exactly what `writeSprite` writes (to
/// learn a file's size, send it over a network, or keep it in a database).
/// `name` only names the sprite in messages. Throws `FormatError` if the
/// sprite is inconsistent, `OutOfMemory`, `IoError` if OpenEXR fails.
std::vector<char> encodeSprite(const Sprite& sprite, const std::string& name = "<memory>");

/// The sprite whose .vds file is the `size` bytes at `data` (caller-owned,
/// only read during the call). Throws exactly as `readSprite` does for a
/// file, with `name` in place of the path.
Sprite decodeSprite(const void* data, std::size_t size, const std::string& name = "<memory>");

/// Writes `sprite` to `path` atomically: to a temporary file beside it
/// (`path` + ".tmp-XXXXXX"), flushed to disk, then renamed over `path`, so an
/// interrupted write never leaves a half-written file; an existing file is
/// replaced whole, and the temporary is removed on any failure.
/// Throws `FormatError` if the sprite is inconsistent (`Sprite::checkConsistent`)
/// and so would not read back, `IoError` (naming `path` and the system's
/// reason) if the file cannot be created, written or renamed, `OutOfMemory`.
void writeSprite(const Sprite& sprite, const std::string& path);

/// Reads a .vds file; the result is bit-identical to the sprite written.
/// Throws `IoError` if it cannot be opened or read, `FormatError` (one line,
/// "<path>: <problem>") if it is not a .vds file, is truncated or corrupt, or
/// its parts disagree, and `OutOfMemory` if a valid file is too large to hold.
/// Never crashes on bad input, and refuses sizes the file cannot hold before
/// allocating for them.
Sprite readSprite(const std::string& path);

} // namespace vds
