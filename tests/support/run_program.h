// Test support: run a program as a user would, through the shell, and keep
// its exit code and everything it printed (stdout and stderr together).
#pragma once

#include <cstdio>
#include <string>

#include <sys/wait.h>

namespace vds::test {

struct Result {
    int code = -1;      ///< exit status; -1 if it did not exit normally
    std::string output; ///< stdout and stderr together
};

inline Result run(const std::string& command) {
    Result r;
    std::FILE* p = ::popen((command + " 2>&1").c_str(), "r");
    if (!p) return r;
    char buffer[4096];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, p)) > 0) r.output.append(buffer, n);
    const int status = ::pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

} // namespace vds::test
