// vds internal: write-to-temporary-then-rename, so outputs are never half-written.
#pragma once

#include <string>

namespace vds::detail {

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

} // namespace vds::detail
