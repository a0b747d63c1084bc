// vds: numpy's .npy files, for points in and labels out (version 1.0 and
// 2.0 headers; C order; little- or big-endian scalars).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace vds {

/// A whole .npy array as read: numpy's dtype string (e.g. "<f4", "|b1"),
/// its shape, and the raw bytes in file order.
struct NpyArray {
    std::string descr;
    std::vector<std::uint64_t> shape;
    bool fortranOrder = false;
    std::vector<char> data;
};

/// Reads a .npy file. Throws `IoError` if it cannot be read and
/// `FormatError` ("<path>: ...") for a bad magic, header or a data size that
/// disagrees with the shape; sizes are checked before anything is allocated.
NpyArray readNpy(const std::string& path);

/// `readNpy` on a file's content already in memory: `size` bytes at `data`
/// (caller-owned, only read during the call), `name` standing for the file
/// in messages (e.g. "<stdin>"). Throws as `readNpy` does.
NpyArray parseNpy(const char* data, std::size_t size, const std::string& name);

/// The points of an N x 3 array of float32 or float64 (any byte order, C
/// order). Throws `FormatError` naming `name` for another shape or type and
/// for a non-finite coordinate (naming its row).
std::vector<glm::vec3> npyPoints(const NpyArray& array, const std::string& name);

/// The preamble and header (version 1.0, padded to 64 bytes) of a C-order
/// array: what precedes its data in a .npy file, for writing one to a stream
/// (stdout). Throws `InvalidArgument` for a header numpy could not hold.
std::string npyHeader(const std::string& descr, const std::vector<std::uint64_t>& shape);

/// Writes a C-order array atomically (temporary file, then rename): `descr`
/// numpy's dtype string, `shape` its dimensions, `bytes` bytes of data at
/// `data` (the product of the shape times the item size). Throws `IoError`.
void writeNpy(const std::string& path, const std::string& descr, const std::vector<std::uint64_t>& shape,
              const void* data, std::size_t bytes);

} // namespace vds
