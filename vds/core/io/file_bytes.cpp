#include <vds/detail/file_bytes.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

#include <vds/error.h>

namespace vds::detail {
namespace {

class FileDescriptor {
public:
    explicit FileDescriptor(int fd) : fd_(fd) {}
    ~FileDescriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    FileDescriptor(const FileDescriptor&) = delete;
    FileDescriptor& operator=(const FileDescriptor&) = delete;
    int get() const { return fd_; }

private:
    int fd_;
};

} // namespace

std::string errnoText(int error) { return std::error_code(error, std::generic_category()).message(); }

std::vector<char> readWholeFile(const std::string& path) {
    FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
    if (fd.get() < 0) throw IoError(path + ": cannot open: " + errnoText(errno));
    struct stat st;
    if (::fstat(fd.get(), &st) != 0) throw IoError(path + ": cannot read: " + errnoText(errno));
    if (S_ISDIR(st.st_mode)) throw IoError(path + ": cannot read: is a directory");

    // One byte more than the size, so reaching the end needs no reallocation.
    std::vector<char> bytes(S_ISREG(st.st_mode) ? std::size_t(st.st_size) + 1 : std::size_t(1) << 16);
    std::size_t size = 0;
    for (;;) {
        if (size == bytes.size()) bytes.resize(bytes.size() * 2);
        const ssize_t n = ::read(fd.get(), bytes.data() + size, bytes.size() - size);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw IoError(path + ": cannot read: " + errnoText(errno));
        }
        if (n == 0) break;
        size += std::size_t(n);
    }
    bytes.resize(size);
    return bytes;
}

} // namespace vds::detail
