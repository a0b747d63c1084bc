// Reading a whole file into memory, for the readers that parse from memory
// (the mesh and point loaders, the .vds reader).
#pragma once

#include <string>
#include <vector>

namespace vds::detail {

/// The file's bytes, all of them. Throws `IoError` naming `path` and the
/// system's reason if it cannot be opened or read, or is a directory; lets
/// `std::bad_alloc` through (the caller names what did not fit).
std::vector<char> readWholeFile(const std::string& path);

/// The system's text for an errno value ("No such file or directory").
std::string errnoText(int error);

} // namespace vds::detail
