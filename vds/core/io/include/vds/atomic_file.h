// vds: outputs written whole or not at all: to a temporary file beside the target, then renamed into place,
// so an output is never left half-written (a crash leaves the old file or none).
// What the target already is decides how: a regular file (or none) is
// replaced by the rename; a symbolic link is written through, its final
// target replaced the same way, the link kept; a device, FIFO or socket is
// written to directly (renaming over it would put a regular file in its
// place); a directory is refused.
#pragma once

#include <string>

namespace vds {

/// A temporary file beside `target` (beside the file a symlink names);
/// `commit()` renames it over that file, the destructor removes it if not
/// committed. For a target that is neither a regular file nor missing (a
/// device, a FIFO), `path()` is the target itself and `commit()` does
/// nothing. Throws `IoError`: a directory, a symlink loop or one whose
/// directory is missing, no temporary file beside it.
class AtomicFile {
public:
    explicit AtomicFile(const std::string& target);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    /// Where to write: the temporary file, or the target itself when `direct()`.
    const std::string& path() const { return direct_ ? target_ : temporary_; }
    /// True when the target is written in place (a device, FIFO or socket).
    bool direct() const { return direct_; }
    void commit();

private:
    std::string target_;    ///< the name given (for messages; written to when direct)
    std::string final_;     ///< the file renamed over: the target, or what its symlinks name
    std::string temporary_;
    bool direct_ = false;
    bool committed_ = false;
};

} // namespace vds
