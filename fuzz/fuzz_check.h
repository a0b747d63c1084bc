// What every harness checks besides "no crash, no hang, no leak": the
// library's error contract. A reader may only throw FormatError (or
// OutOfMemory), with a one-line message that names the input.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

#include <vds/error.h>

namespace vds::fuzz {

/// The name every harness passes for its input, so messages can be checked.
inline const std::string kName = "fuzz-input";

/// Aborts (a finding) unless `e` is a one-line message starting with the name.
inline void checkMessage(const vds::Error& e) {
    const std::string what = e.what();
    if (what.rfind(kName, 0) != 0 || what.find('\n') != std::string::npos) {
        std::fprintf(stderr, "bad error message: %s\n", what.c_str());
        std::abort();
    }
}

/// Aborts with `what` (a finding): a broken promise of the reader.
[[noreturn]] inline void broken(const char* what) {
    std::fprintf(stderr, "broken promise: %s\n", what);
    std::abort();
}

} // namespace vds::fuzz
