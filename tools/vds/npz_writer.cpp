#include "npz_writer.h"

#include <algorithm>
#include <limits>
#include <utility>

#include <sys/types.h>
#include <zlib.h>

#include <vds/error.h>

namespace cli {

namespace {

// ZIP's fixed values (APPNOTE 4.3, 4.4): signatures, versions, the ZIP64 extra field's id.
constexpr std::uint32_t kLocalSignature = 0x04034b50, kCentralSignature = 0x02014b50, kEndSignature = 0x06054b50,
                        kZip64EndSignature = 0x06064b50, kZip64LocatorSignature = 0x07064b50;
constexpr std::uint16_t kVersionPlain = 20, kVersionZip64 = 45, kZip64ExtraId = 0x0001;
constexpr std::uint16_t kDosDate1980 = (0 << 9) | (1 << 5) | 1; // 1980-01-01 00:00: files of equal content are equal
constexpr std::uint32_t kWideField = 0xFFFFFFFFu;               // "see the ZIP64 extra field"

/// `value`'s low `bytes` bytes, little-endian, appended to `out`.
void le(std::string& out, std::uint64_t value, int bytes) {
    for (int b = 0; b < bytes; ++b) out += char((value >> (8 * b)) & 0xff);
}

std::uint32_t crcOf(std::uint32_t crc, const void* data, std::size_t count) {
    const auto* bytes = static_cast<const Bytef*>(data);
    constexpr std::size_t kChunk = std::size_t(1) << 30; // zlib's crc32 takes an unsigned int length
    while (count > 0) {
        const std::size_t n = std::min(count, kChunk);
        crc = std::uint32_t(crc32(crc, bytes, uInt(n)));
        bytes += n;
        count -= n;
    }
    return crc;
}

} // namespace

NpzWriter::NpzWriter(std::FILE* file, std::string name, std::uint64_t zip64Above)
    : file_(file), name_(std::move(name)), zip64Above_(zip64Above) {}

std::string NpzWriter::localHeader(const Entry& e) const {
    const bool zip64 = wide(e.size);
    std::string h;
    le(h, kLocalSignature, 4);
    le(h, zip64 ? kVersionZip64 : kVersionPlain, 2);
    le(h, 0, 2); // flags
    le(h, 0, 2); // stored
    le(h, 0, 2); // time
    le(h, kDosDate1980, 2);
    le(h, e.crc, 4);
    le(h, zip64 ? kWideField : e.size, 4); // compressed size
    le(h, zip64 ? kWideField : e.size, 4); // uncompressed size
    le(h, e.name.size(), 2);
    le(h, zip64 ? 20 : 0, 2);
    h += e.name;
    if (zip64) { // a local header's ZIP64 field holds both sizes (APPNOTE 4.5.3)
        le(h, kZip64ExtraId, 2);
        le(h, 16, 2);
        le(h, e.size, 8);
        le(h, e.size, 8);
    }
    return h;
}

std::string NpzWriter::centralHeader(const Entry& e) const {
    const bool wideSize = wide(e.size), wideOffset = wide(e.offset);
    std::string extra; // the wide fields, in APPNOTE's order: sizes, then the offset
    if (wideSize) {
        le(extra, e.size, 8);
        le(extra, e.size, 8);
    }
    if (wideOffset) le(extra, e.offset, 8);
    const bool zip64 = !extra.empty();
    std::string h;
    le(h, kCentralSignature, 4);
    le(h, zip64 ? kVersionZip64 : kVersionPlain, 2); // made by (MS-DOS attributes)
    le(h, zip64 ? kVersionZip64 : kVersionPlain, 2); // needed
    le(h, 0, 2);
    le(h, 0, 2);
    le(h, 0, 2);
    le(h, kDosDate1980, 2);
    le(h, e.crc, 4);
    le(h, wideSize ? kWideField : e.size, 4);
    le(h, wideSize ? kWideField : e.size, 4);
    le(h, e.name.size(), 2);
    le(h, zip64 ? 4 + extra.size() : 0, 2);
    le(h, 0, 2); // comment
    le(h, 0, 2); // disk
    le(h, 0, 2); // internal attributes
    le(h, 0, 4); // external attributes
    le(h, wideOffset ? kWideField : e.offset, 4);
    h += e.name;
    if (zip64) {
        le(h, kZip64ExtraId, 2);
        le(h, extra.size(), 2);
        h += extra;
    }
    return h;
}

std::string NpzWriter::endRecords(std::uint64_t directoryOffset, std::uint64_t directorySize) const {
    const std::uint64_t count = entries_.size();
    const bool zip64 = wide(directoryOffset) || wide(directorySize);
    std::string r;
    if (zip64) {
        const std::uint64_t recordOffset = directoryOffset + directorySize;
        le(r, kZip64EndSignature, 4);
        le(r, 44, 8); // the record's size after this field
        le(r, kVersionZip64, 2);
        le(r, kVersionZip64, 2);
        le(r, 0, 4);
        le(r, 0, 4);
        le(r, count, 8);
        le(r, count, 8);
        le(r, directorySize, 8);
        le(r, directoryOffset, 8);
        le(r, kZip64LocatorSignature, 4);
        le(r, 0, 4);
        le(r, recordOffset, 8);
        le(r, 1, 4); // disks
    }
    le(r, kEndSignature, 4);
    le(r, 0, 2);
    le(r, 0, 2);
    le(r, count, 2);
    le(r, count, 2);
    le(r, wide(directorySize) ? kWideField : directorySize, 4);
    le(r, wide(directoryOffset) ? kWideField : directoryOffset, 4);
    le(r, 0, 2); // comment
    return r;
}

void NpzWriter::put(const void* data, std::size_t count) {
    if (count != 0 && std::fwrite(data, 1, count, file_) != count)
        throw vds::IoError(name_ + ": cannot write (disk full?)");
    position_ += count;
}

void NpzWriter::put(const std::string& bytes) { put(bytes.data(), bytes.size()); }

void NpzWriter::add(const std::string& member, const std::string& bytes) {
    begin(member, bytes.size());
    append(bytes.data(), bytes.size());
}

void NpzWriter::begin(const std::string& member, std::uint64_t size) {
    if (!entries_.empty() && entries_.back().written != entries_.back().size)
        throw vds::IoError(name_ + ": " + entries_.back().name + " not written whole");
    Entry entry;
    entry.name = member;
    entry.offset = position_;
    entry.size = size;
    put(localHeader(entry));
    entries_.push_back(std::move(entry));
}

void NpzWriter::append(const void* data, std::size_t count) {
    Entry& entry = entries_.back();
    if (entry.written + count > entry.size) throw vds::IoError(name_ + ": " + entry.name + " longer than its size");
    entry.crc = crcOf(entry.crc, data, count);
    put(data, count);
    entry.written += count;
}

// The CRC sits 14 bytes into the local header, written before the bytes it sums.
void NpzWriter::patchCrc(const Entry& entry) {
    constexpr std::uint64_t kCrcAt = 14;
    std::string crc;
    le(crc, entry.crc, 4);
    const auto at = entry.offset + kCrcAt;
    if (at > std::uint64_t(std::numeric_limits<off_t>::max()) || fseeko(file_, off_t(at), SEEK_SET) != 0 ||
        std::fwrite(crc.data(), 1, crc.size(), file_) != crc.size() || fseeko(file_, off_t(position_), SEEK_SET) != 0)
        throw vds::IoError(name_ + ": cannot write (not a seekable file?)");
}

void NpzWriter::finish() {
    for (const Entry& entry : entries_) {
        if (entry.written != entry.size) throw vds::IoError(name_ + ": " + entry.name + " not written whole");
        patchCrc(entry);
    }
    const std::uint64_t directoryOffset = position_;
    std::string directory;
    for (const Entry& entry : entries_) directory += centralHeader(entry);
    put(directory);
    put(endRecords(directoryOffset, directory.size()));
}

} // namespace cli
