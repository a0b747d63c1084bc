// vds: write to a temporary file beside the target, then rename it into place,
// so an output is never left half-written (a crash leaves the old file or none).
#pragma once

#include <string>

namespace vds {

/// A temporary file beside `target`; `commit()` renames it over the target,
/// the destructor removes it if not committed. Throws `IoError`.
class AtomicFile {
public:
    explicit AtomicFile(const std::string& target);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    const std::string& path() const { return temporary_; }
    void commit();

private:
    std::string target_;
    std::string temporary_;
    bool committed_ = false;
};

} // namespace vds
