#include <vds/atomic_file.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <vds/error.h>

namespace vds {

namespace {

/// Symbolic links followed at most, as the kernel's own limit (ELOOP).
constexpr int kMaxSymlinks = 40;

/// The file `target` names once its symbolic links are followed (a missing
/// last one is where a new file goes), and its `lstat` (st_mode 0: none).
std::string followLinks(const std::string& target, struct stat& st) {
    std::string path = target;
    for (int hop = 0; hop <= kMaxSymlinks; ++hop) {
        if (::lstat(path.c_str(), &st) != 0) {
            if (errno != ENOENT) throw IoError(target + ": cannot write: " + std::strerror(errno));
            st.st_mode = 0;
            return path;
        }
        if (!S_ISLNK(st.st_mode)) return path;
        std::string link(std::size_t(st.st_size > 0 ? st.st_size : 255) + 1, '\0');
        const ssize_t n = ::readlink(path.c_str(), &link[0], link.size());
        if (n < 0 || std::size_t(n) >= link.size())
            throw IoError(target + ": cannot read the symbolic link " + path);
        link.resize(std::size_t(n));
        const std::size_t slash = path.rfind('/');
        path = link[0] == '/' || slash == std::string::npos ? link : path.substr(0, slash + 1) + link;
    }
    throw IoError(target + ": not written: too many levels of symbolic links");
}

/// A fresh name beside `file`, made with O_EXCL and mode 0666, so the umask
/// applies as for any new file (mkstemp would make it private).
std::string createBeside(const std::string& file, const std::string& target) {
    static std::atomic<std::uint64_t> counter{0};
    const std::uint64_t seed = std::uint64_t(::getpid()) * 0x9e3779b97f4a7c15ull ^
                               std::uint64_t(std::chrono::steady_clock::now().time_since_epoch().count());
    for (int attempt = 0; attempt < 100; ++attempt) {
        std::uint64_t z = seed + (counter.fetch_add(1) + 1) * 0x9e3779b97f4a7c15ull; // splitmix64
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        z ^= z >> 31;
        std::string name = file + ".tmp-";
        for (int k = 0; k < 6; ++k, z /= 36) name += "0123456789abcdefghijklmnopqrstuvwxyz"[z % 36];
        const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            ::close(fd);
            return name;
        }
        if (errno != EEXIST) throw IoError(target + ": cannot create a file beside it: " + std::strerror(errno));
    }
    throw IoError(target + ": cannot create a file beside it: no free temporary name");
}

} // namespace

AtomicFile::AtomicFile(const std::string& target) : target_(target) {
    struct stat st {};
    final_ = followLinks(target, st);
    if (S_ISDIR(st.st_mode)) throw IoError(target + ": is a directory, not written");
    if (st.st_mode != 0 && !S_ISREG(st.st_mode)) {
        // A device, FIFO or socket: replacing it with a regular file would
        // break what it is for (/dev/null, a reader on a pipe).
        direct_ = true;
        return;
    }
    temporary_ = createBeside(final_, target);
    // The replaced file's permissions are kept (the rename would give the new file the umask's).
    if (st.st_mode != 0) ::chmod(temporary_.c_str(), st.st_mode & 07777);
}

AtomicFile::~AtomicFile() {
    if (!committed_ && !direct_) ::unlink(temporary_.c_str());
}

void AtomicFile::commit() {
    if (direct_) { // written in place by the caller; nothing to rename
        committed_ = true;
        return;
    }
    // Flush to disk before the rename, so a crash cannot leave an empty file under the name.
    const int fd = ::open(temporary_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0 || ::fsync(fd) != 0) {
        const int e = errno;
        if (fd >= 0) ::close(fd);
        throw IoError(target_ + ": cannot write: " + std::strerror(e));
    }
    ::close(fd);
    if (std::rename(temporary_.c_str(), final_.c_str()) != 0)
        throw IoError(target_ + ": cannot rename the finished file into place: " + std::strerror(errno));
    committed_ = true;
}

} // namespace vds
