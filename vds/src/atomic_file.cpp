#include "atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <unistd.h>

#include <vds/error.h>

namespace vds {

namespace detail {

AtomicFile::AtomicFile(const std::string& target) : target_(target) {
    std::string pattern = target + ".tmp-XXXXXX";
    const int fd = ::mkstemp(pattern.data());
    if (fd < 0) throw IoError(target + ": cannot create a file there (" + std::strerror(errno) + ")");
    ::close(fd);
    temporary_ = pattern;
}

AtomicFile::~AtomicFile() {
    if (!committed_) std::remove(temporary_.c_str());
}

void AtomicFile::commit() {
    if (std::rename(temporary_.c_str(), target_.c_str()) != 0)
        throw IoError(target_ + ": cannot rename the finished file into place (" + std::strerror(errno) + ")");
    committed_ = true;
}

} // namespace detail

} // namespace vds
