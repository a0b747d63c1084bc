// A numpy .npz written member by member into a seekable file: a ZIP archive
// (PKWARE APPNOTE 6.3) of stored, uncompressed .npy members, as numpy.savez
// writes and numpy.load reads. Small members are added whole; the last one
// (a grid's values, gigabytes) is streamed: its size is known before its
// bytes, so its local header is written first and only its CRC-32, summed
// while the bytes pass, is patched in at the end. Sizes and offsets past the
// plain fields' 32 bits are written as ZIP64 records, which numpy reads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace cli {

/// The largest size or offset a plain ZIP field holds: from here on, ZIP64.
constexpr std::uint64_t kZip64Above = 0xFFFFFFFFull;

class NpzWriter {
public:
    /// Writes to `file`, open for writing and seekable, at its start (the
    /// caller closes it); `name` stands for the file in messages. A size or
    /// offset at or above `zip64Above` is written as a ZIP64 field (tests
    /// force a small one; numpy reads either).
    NpzWriter(std::FILE* file, std::string name, std::uint64_t zip64Above = kZip64Above);

    /// Adds member `member` (e.g. "lo.npy") holding `bytes` whole. Throws
    /// vds::IoError.
    void add(const std::string& member, const std::string& bytes);
    /// Starts member `member` of `size` bytes, which `append` then writes.
    void begin(const std::string& member, std::uint64_t size);
    /// The next `count` bytes of the member begun. Throws vds::IoError.
    void append(const void* data, std::size_t count);
    /// Patches the streamed member's CRC-32 and writes the central directory
    /// and the end records. Throws vds::IoError, also when a member begun
    /// did not get all its bytes.
    void finish();

private:
    struct Entry {
        std::string name;
        std::uint64_t offset = 0, size = 0, written = 0;
        std::uint32_t crc = 0;
    };
    bool wide(std::uint64_t value) const { return value >= zip64Above_; }
    std::string localHeader(const Entry& entry) const;
    std::string centralHeader(const Entry& entry) const;
    std::string endRecords(std::uint64_t directoryOffset, std::uint64_t directorySize) const;
    void put(const std::string& bytes);
    void put(const void* data, std::size_t count);
    void patchCrc(const Entry& entry);

    std::FILE* file_;
    std::string name_;
    std::uint64_t zip64Above_;
    std::uint64_t position_ = 0;
    std::vector<Entry> entries_;
};

} // namespace cli
