#include <vds/detail/atomic_file.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <fcntl.h>
#include <unistd.h>

#include <vds/error.h>

namespace vds {

AtomicFile::AtomicFile(const std::string& target) : target_(target) {
    // A unique name beside the target, made with O_EXCL and mode 0666, so the
    // umask applies as for any new file (mkstemp would make it private).
    static std::atomic<std::uint64_t> counter{0};
    const std::uint64_t seed = std::uint64_t(::getpid()) * 0x9e3779b97f4a7c15ull ^
                               std::uint64_t(std::chrono::steady_clock::now().time_since_epoch().count());
    for (int attempt = 0; attempt < 100; ++attempt) {
        std::uint64_t z = seed + (counter.fetch_add(1) + 1) * 0x9e3779b97f4a7c15ull; // splitmix64
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        z ^= z >> 31;
        std::string name = target + ".tmp-";
        for (int k = 0; k < 6; ++k, z /= 36) name += "0123456789abcdefghijklmnopqrstuvwxyz"[z % 36];
        const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            ::close(fd);
            temporary_ = name;
            return;
        }
        if (errno != EEXIST) throw IoError(target + ": cannot create a file beside it: " + std::strerror(errno));
    }
    throw IoError(target + ": cannot create a file beside it: no free temporary name");
}

AtomicFile::~AtomicFile() {
    if (!committed_) ::unlink(temporary_.c_str());
}

void AtomicFile::commit() {
    // Flush to disk before the rename, so a crash cannot leave an empty file under the name.
    const int fd = ::open(temporary_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0 || ::fsync(fd) != 0) {
        const int e = errno;
        if (fd >= 0) ::close(fd);
        throw IoError(target_ + ": cannot write: " + std::strerror(e));
    }
    ::close(fd);
    if (std::rename(temporary_.c_str(), target_.c_str()) != 0)
        throw IoError(target_ + ": cannot rename the finished file into place: " + std::strerror(errno));
    committed_ = true;
}

} // namespace vds
