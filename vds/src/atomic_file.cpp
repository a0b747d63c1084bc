#include <vds/atomic_file.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <sys/stat.h>
#include <unistd.h>

#include <vds/error.h>

namespace vds {

AtomicFile::AtomicFile(const std::string& target) : target_(target) {
    std::string pattern = target + ".tmp-XXXXXX";
    const int fd = ::mkstemp(pattern.data());
    if (fd < 0) throw IoError(target + ": cannot create a file there (" + std::strerror(errno) + ")");
    // mkstemp makes the file private; give it the permissions a plain create would.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);
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



} // namespace vds
