// vds internal: counts in words, for the mesh report and the mesh check's
// messages, so that both say "1 boundary edge" and "3 boundary edges" alike.
#pragma once

#include <cstddef>
#include <string>

namespace vds::detail {

/// "1 boundary edge", "3 boundary edges"; `many` where the plural is not
/// `one` + "s" ("vertices").
inline std::string counted(std::size_t n, const char* one, const char* many = nullptr) {
    return std::to_string(n) + " " + (n == 1 ? one : many ? many : std::string(one) + "s");
}

} // namespace vds::detail
