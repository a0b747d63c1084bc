// The .vds file: a sprite (Trapp & Döllner 2008, section 3.1: P_S, M_S, the
// LDI and d_S) as one OpenEXR deep scanline image; docs/format.md.
//
// OpenEXR only ever sees memory: the writer encodes into a byte buffer that is
// then written to a temporary file and renamed over the target, and the reader
// loads the whole file first. So every system-call failure is ours to report
// (IoError, with errno's reason) and everything OpenEXR rejects is the
// content's fault (FormatError).
#include <vds/vds_file.h>

#include <vds/atomic_file.h>

#include <vds/detail/file_bytes.h>
#include <vds/detail/vds_checksum.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfDeepFrameBuffer.h>
#include <ImfDeepScanLineInputFile.h>
#include <ImfDeepScanLineOutputFile.h>
#include <ImfFloatAttribute.h>
#include <ImfFloatVectorAttribute.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfIntAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfPartType.h>
#include <ImfStringAttribute.h>
#include <ImfVecAttribute.h>
#include <ImfVersion.h>

#include <Iex.h>

#include <vds/error.h>

namespace vds {
namespace {

using detail::errnoText;
using detail::readWholeFile;
using detail::spriteChecksum;

// Attribute names (docs/format.md lists types and meaning).
constexpr const char* kFormatVersionAttr = "vds.formatVersion";
constexpr const char* kAxisAttr = "vds.axis";
constexpr const char* kPositionAttr = "vds.position";
constexpr const char* kMatrixAttr = "vds.matrix";
constexpr const char* kBoxMinAttr = "vds.boxMin";
constexpr const char* kBoxMaxAttr = "vds.boxMax";
constexpr const char* kTexelSizeAttr = "vds.texelSize";
constexpr const char* kDepthComplexityAttr = "vds.depthComplexity";
constexpr const char* kSourceNameAttr = "vds.sourceName";
constexpr const char* kSourceTrianglesAttr = "vds.sourceTriangles";
constexpr const char* kStatusAttr = "vds.status";
constexpr const char* kValidationAttr = "vds.validation";
constexpr const char* kChecksumAttr = "vds.checksum";
constexpr const char* kBoundaryEdgesAttr = "vds.boundaryEdges"; // version 2
// Version 3, all three or none: the sprite's distance grid (SpriteDistance).
constexpr const char* kDistanceDimsAttr = "vds.distanceDims";
constexpr const char* kDistanceBoxAttr = "vds.distanceBox"; // six floats: lo, then hi
constexpr const char* kDistanceAttr = "vds.distance";
// The version a sprite without a distance grid is written as, so that
// readers of version 2 still read it.
constexpr int kPlainFormatVersion = 2;
// The oldest format version read (1: no boundary edges).
constexpr int kOldestFormatVersion = 1;

constexpr const char* kDepthChannel = "Z";
constexpr const char* kEnteringChannel = "entering";

// Bytes per stored sample: Z (FLOAT) + entering (UINT).
constexpr std::uint64_t kBytesPerSample = 8;
// Deflate expands data at most about 1032-fold (RLE 64-fold, NONE 1-fold), so
// a file of n bytes cannot hold more than this many times n bytes of sample
// counts and samples; larger claims are corrupt and refused before allocating.
constexpr std::uint64_t kMaxExpansion = 1100;
// Rows per OpenEXR call are capped so the per-pixel pointer tables the deep
// API needs stay near 20 MB.
constexpr std::uint64_t kPixelsPerBatch = std::uint64_t(1) << 20;

// ---------------------------------------------------------------- messages

std::string oneLine(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        const bool blank = c == '\n' || c == '\r' || c == '\t';
        if (blank && (out.empty() || out.back() == ' ')) continue;
        out += blank ? ' ' : c;
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    return out;
}

[[noreturn]] void formatFail(const std::string& path, const std::string& what) {
    throw FormatError(path + ": " + oneLine(what));
}

// ---------------------------------------------------------------- checksum

/// The format version `s` is written as: 3 with a distance grid, else 2.
int writtenVersion(const Sprite& s) { return s.distance.empty() ? kPlainFormatVersion : Sprite::kFormatVersion; }

std::string toHex(std::uint64_t v) {
    static const char digits[] = "0123456789abcdef";
    std::string s(16, '0');
    for (int k = 15; k >= 0; --k, v >>= 4) s[std::size_t(k)] = digits[v & 15];
    return s;
}

bool parseHex(const std::string& s, std::uint64_t& v) {
    if (s.size() != 16) return false;
    v = 0;
    for (char c : s) {
        const int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
        if (d < 0) return false;
        v = (v << 4) | std::uint64_t(d);
    }
    return true;
}

bool parseDecimal(const std::string& s, std::uint64_t& v) {
    if (s.empty() || s.size() > 20) return false;
    v = 0;
    for (char c : s) {
        if (c < '0' || c > '9') return false;
        const std::uint64_t d = std::uint64_t(c - '0');
        if (v > (std::numeric_limits<std::uint64_t>::max() - d) / 10) return false;
        v = v * 10 + d;
    }
    return true;
}

// ---------------------------------------------------------------- matrices

// The file stores M_S as Imath's M33f with x[i][j] = glm matrix[i][j]: the same
// nine floats in the same order, which in Imath's row-vector convention
// (T = (P - P_S) * M) is the same linear map as glm's T = M_S * (P - P_S).
Imath::V3f toImath(const glm::vec3& v) { return Imath::V3f(v.x, v.y, v.z); }
glm::vec3 toGlm(const Imath::V3f& v) { return glm::vec3(v.x, v.y, v.z); }

Imath::M33f toImath(const glm::mat3& m) {
    Imath::M33f out;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out.x[i][j] = m[i][j];
    return out;
}

glm::mat3 toGlm(const Imath::M33f& m) {
    glm::mat3 out;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out[i][j] = m.x[i][j];
    return out;
}

// ---------------------------------------------------------------- memory streams

/// Growable in-memory output stream for OpenEXR.
class MemoryOStream final : public Imf::OStream {
public:
    explicit MemoryOStream(const std::string& name) : Imf::OStream(name.c_str()) {}

    void write(const char c[], int n) override {
        if (n < 0) throw Iex::ArgExc("negative write size");
        const std::size_t end = position_ + std::size_t(n);
        if (end > bytes_.size()) bytes_.resize(end);
        if (n > 0) std::memcpy(bytes_.data() + position_, c, std::size_t(n));
        position_ = end;
    }
    std::uint64_t tellp() override { return position_; }
    void seekp(std::uint64_t pos) override { position_ = std::size_t(pos); }

    const std::vector<char>& bytes() const { return bytes_; }

private:
    std::vector<char> bytes_;
    std::size_t position_ = 0;
};

/// Read-only view of a file's bytes; every read past the end throws.
class MemoryIStream final : public Imf::IStream {
public:
    MemoryIStream(const std::string& name, const char* data, std::size_t size)
        : Imf::IStream(name.c_str()), data_(data), size_(size) {}

    bool isMemoryMapped() const override { return true; }
    bool read(char c[], int n) override {
        const char* p = take(n);
        if (n > 0) std::memcpy(c, p, std::size_t(n));
        return position_ < size_;
    }
    char* readMemoryMapped(int n) override { return take(n); }
    std::uint64_t tellg() override { return position_; }
    void seekg(std::uint64_t pos) override { position_ = pos; }
    void clear() override {}
    /// The end of the farthest bytes read: the file's size once every chunk was read.
    std::uint64_t farthest() const { return farthest_; }

private:
    // OpenEXR's memory-mapped reads hand out char* but only read through it.
    char* take(int n) {
        if (n < 0 || position_ > size_ || std::uint64_t(n) > size_ - position_)
            throw Iex::InputExc("unexpected end of file");
        char* p = const_cast<char*>(data_) + position_;
        position_ += std::uint64_t(n);
        farthest_ = std::max(farthest_, position_);
        return p;
    }

    const char* data_;
    std::size_t size_;
    std::uint64_t position_ = 0;
    std::uint64_t farthest_ = 0;
};

// ---------------------------------------------------------------- files

void writeFileAtomically(const std::string& path, const std::vector<char>& bytes) {
    AtomicFile tmp(path);
    const int fd = ::open(tmp.path().c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd < 0) throw IoError(path + ": cannot write: " + errnoText(errno));
    const char* p = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            const int e = errno;
            ::close(fd);
            throw IoError(path + ": cannot write: " + errnoText(e));
        }
        p += n;
        left -= std::size_t(n);
    }
    if (::close(fd) != 0) throw IoError(path + ": cannot write: " + errnoText(errno));
    tmp.commit();
}

// ---------------------------------------------------------------- encoding

/// Rows per OpenEXR call for an image `width` pixels wide.
int batchRows(std::uint32_t width) {
    return int(std::max<std::uint64_t>(1, kPixelsPerBatch / width));
}

/// OpenEXR addresses slice memory by absolute pixel position, base + y * yStride:
/// the base that puts row `y0` at `firstRow`.
char* sliceBase(void* firstRow, int y0, std::size_t yStride) {
    return reinterpret_cast<char*>(reinterpret_cast<std::uintptr_t>(firstRow) - std::uintptr_t(y0) * yStride);
}

/// The frame buffer of rows y0.. of a `width`-wide image: per pixel a sample
/// count and pointers to its first depth (float) and entering flag (unsigned).
Imf::DeepFrameBuffer batchFrameBuffer(unsigned* counts, char** depthPointers, char** enteringPointers, int y0,
                                      std::uint32_t width) {
    Imf::DeepFrameBuffer fb;
    fb.insertSampleCountSlice(Imf::Slice(Imf::UINT, sliceBase(counts, y0, sizeof(unsigned) * width),
                                         sizeof(unsigned), sizeof(unsigned) * width));
    fb.insert(kDepthChannel, Imf::DeepSlice(Imf::FLOAT, sliceBase(depthPointers, y0, sizeof(char*) * width),
                                            sizeof(char*), sizeof(char*) * width, sizeof(float)));
    fb.insert(kEnteringChannel, Imf::DeepSlice(Imf::UINT, sliceBase(enteringPointers, y0, sizeof(char*) * width),
                                               sizeof(char*), sizeof(char*) * width, sizeof(unsigned)));
    return fb;
}

/// Refuses what the reader would refuse, so every written file reads back.
void checkWritable(const Sprite& sprite, const std::string& path) {
    try {
        sprite.checkConsistent();
    } catch (const FormatError& e) {
        formatFail(path, std::string("not written: ") + e.what());
    }
    if (unsigned(sprite.grid.axis) > 2) formatFail(path, "not written: invalid axis");
    if (unsigned(sprite.status) > 1) formatFail(path, "not written: invalid solid status");
    if (sprite.depthComplexity > std::uint32_t(std::numeric_limits<int>::max()))
        formatFail(path, "not written: depth complexity too large");
    if (sprite.boundaryEdges.size() % 2 != 0) formatFail(path, "not written: boundary edges need two ends each");
    if (sprite.boundaryEdges.size() * 3 > std::size_t(std::numeric_limits<int>::max() / 4))
        formatFail(path, "not written: too many boundary edges");
    for (const glm::vec3& p : sprite.boundaryEdges)
        if (!std::isfinite(p.x + p.y + p.z)) formatFail(path, "not written: a boundary edge is not finite");
    if (!sprite.boundaryKnown)
        formatFail(path, "not written: the sprite's boundary is unknown (read from a version-1 file of an open mesh)");
    if (sprite.distance.cells.size() > std::size_t(std::numeric_limits<int>::max() / 4))
        formatFail(path, "not written: the distance grid is too large for one attribute");
}

Imf::Header makeHeader(const Sprite& sprite) {
    Imf::Header header(int(sprite.width()), int(sprite.height()));
    header.setType(Imf::DEEPSCANLINE);
    // ZIPS: zlib per scanline. OpenEXR 3.1 refuses ZIP (16-line chunks) for deep data.
    header.compression() = Imf::ZIPS_COMPRESSION;
    header.channels().insert(kDepthChannel, Imf::Channel(Imf::FLOAT));
    header.channels().insert(kEnteringChannel, Imf::Channel(Imf::UINT));

    const SpriteGrid& g = sprite.grid;
    header.insert(kFormatVersionAttr, Imf::IntAttribute(writtenVersion(sprite)));
    header.insert(kAxisAttr, Imf::IntAttribute(int(g.axis)));
    header.insert(kPositionAttr, Imf::V3fAttribute(toImath(g.position)));
    header.insert(kMatrixAttr, Imf::M33fAttribute(toImath(g.matrix)));
    header.insert(kBoxMinAttr, Imf::V3fAttribute(toImath(g.box.lo)));
    header.insert(kBoxMaxAttr, Imf::V3fAttribute(toImath(g.box.hi)));
    header.insert(kTexelSizeAttr, Imf::FloatAttribute(g.texelSize));
    header.insert(kDepthComplexityAttr, Imf::IntAttribute(int(sprite.depthComplexity)));
    header.insert(kSourceNameAttr, Imf::StringAttribute(sprite.sourceName));
    header.insert(kSourceTrianglesAttr, Imf::StringAttribute(std::to_string(sprite.sourceTriangles)));
    header.insert(kStatusAttr, Imf::IntAttribute(int(sprite.status)));
    header.insert(kValidationAttr, Imf::StringAttribute(sprite.validation));
    std::vector<float> ends(sprite.boundaryEdges.size() * 3);
    for (std::size_t k = 0; k < sprite.boundaryEdges.size(); ++k)
        for (int a = 0; a < 3; ++a) ends[3 * k + std::size_t(a)] = sprite.boundaryEdges[k][a];
    header.insert(kBoundaryEdgesAttr, Imf::FloatVectorAttribute(ends));
    if (!sprite.distance.empty()) {
        const Grid& field = sprite.distance.grid;
        const Imath::V3i dims(int(field.dims.x), int(field.dims.y), int(field.dims.z));
        header.insert(kDistanceDimsAttr, Imf::V3iAttribute(dims));
        const glm::vec3 &lo = field.box.lo, &hi = field.box.hi;
        header.insert(kDistanceBoxAttr, Imf::FloatVectorAttribute({lo.x, lo.y, lo.z, hi.x, hi.y, hi.z}));
        header.insert(kDistanceAttr, Imf::FloatVectorAttribute(sprite.distance.cells));
    }
    header.insert(kChecksumAttr, Imf::StringAttribute(toHex(spriteChecksum(sprite, writtenVersion(sprite)))));
    return header;
}

std::vector<char> encodeBytes(const Sprite& sprite, const std::string& path) {
    const std::uint32_t width = sprite.width(), height = sprite.height();
    MemoryOStream stream(path);
    {
        Imf::DeepScanLineOutputFile file(stream, makeHeader(sprite));
        const int rows = batchRows(width);
        std::vector<unsigned> counts;
        std::vector<char*> depthPointers, enteringPointers;
        std::vector<float> depths;
        std::vector<unsigned> entering;
        for (int y0 = 0; y0 < int(height); y0 += rows) {
            const int y1 = std::min(int(height), y0 + rows);
            const std::size_t first = std::size_t(y0) * width, last = std::size_t(y1) * width;
            const std::uint32_t base = sprite.offsets[first];
            const std::size_t samples = sprite.offsets[last] - base;

            counts.resize(last - first);
            depthPointers.resize(last - first);
            enteringPointers.resize(last - first);
            depths.resize(std::max<std::size_t>(1, samples));
            entering.resize(std::max<std::size_t>(1, samples));
            for (std::size_t k = 0; k < samples; ++k) {
                const float e = sprite.crossings[base + k];
                depths[k] = crossingDepth(e);
                entering[k] = crossingEnters(e) ? 1u : 0u;
            }
            for (std::size_t c = first; c < last; ++c) {
                counts[c - first] = sprite.offsets[c + 1] - sprite.offsets[c];
                depthPointers[c - first] = reinterpret_cast<char*>(depths.data() + (sprite.offsets[c] - base));
                enteringPointers[c - first] = reinterpret_cast<char*>(entering.data() + (sprite.offsets[c] - base));
            }

            file.setFrameBuffer(
                batchFrameBuffer(counts.data(), depthPointers.data(), enteringPointers.data(), y0, width));
            file.writePixels(y1 - y0);
        }
    } // the destructor writes the chunk offset table
    return stream.bytes();
}

// ---------------------------------------------------------------- decoding

const Imf::Attribute& requireAttribute(const Imf::Header& header, const char* name, const char* typeName,
                                       const std::string& path) {
    const auto it = header.find(name);
    if (it == header.end()) formatFail(path, std::string("missing attribute ") + name);
    if (std::strcmp(it.attribute().typeName(), typeName) != 0)
        formatFail(path, std::string("attribute ") + name + " has type " + it.attribute().typeName() + ", expected " +
                             typeName);
    return it.attribute();
}

template <class T>
const T& value(const Imf::Header& header, const char* name, const std::string& path) {
    using Attr = Imf::TypedAttribute<T>;
    const Imf::Attribute& a = requireAttribute(header, name, Attr::staticTypeName(), path);
    const Attr* typed = dynamic_cast<const Attr*>(&a);
    if (!typed) formatFail(path, std::string("attribute ") + name + " has an unexpected type");
    return typed->value();
}

void checkChannels(const Imf::Header& header, const std::string& path) {
    const Imf::ChannelList& channels = header.channels();
    int count = 0;
    for (auto it = channels.begin(); it != channels.end(); ++it) {
        ++count;
        const std::string name = it.name();
        const Imf::Channel& ch = it.channel();
        const Imf::PixelType expected = name == kDepthChannel      ? Imf::FLOAT
                                        : name == kEnteringChannel ? Imf::UINT
                                                                   : Imf::NUM_PIXELTYPES;
        if (expected == Imf::NUM_PIXELTYPES) formatFail(path, "unexpected channel \"" + name + "\"");
        if (ch.type != expected)
            formatFail(path, "channel \"" + name + "\" has the wrong type (expected " +
                                 (expected == Imf::FLOAT ? "FLOAT" : "UINT") + ")");
        if (ch.xSampling != 1 || ch.ySampling != 1) formatFail(path, "channel \"" + name + "\" is subsampled");
    }
    if (count != 2 || !channels.findChannel(kDepthChannel) || !channels.findChannel(kEnteringChannel))
        formatFail(path, "expected exactly the channels \"Z\" and \"entering\"");
}

/// Reads and checks everything up to the pixels: the OpenEXR version field,
/// the header, and the vds.* attributes into `sprite` (offsets, crossings and
/// the checksum excepted). Returns the stored checksum.
/// Bytes OpenEXR 3.1 reads for a value of each fixed-size attribute type,
/// whatever size the file declares.
std::size_t fixedValueSize(const std::string& type) {
    static const std::pair<const char*, std::size_t> sizes[] = {
        {"box2i", 16},  {"box2f", 16},     {"chromaticities", 32}, {"compression", 1}, {"double", 8},
        {"envmap", 1},  {"float", 4},      {"int", 4},             {"keycode", 28},    {"lineOrder", 1},
        {"m33f", 36},   {"m33d", 72},      {"m44f", 64},           {"m44d", 128},      {"rational", 8},
        {"tiledesc", 9}, {"timecode", 8},  {"v2i", 8},             {"v2f", 8},         {"v2d", 16},
        {"v3i", 12},    {"v3f", 12},       {"v3d", 24},            {"deepImageState", 1},
    };
    for (const auto& [name, size] : sizes)
        if (type == name) return size;
    return 0;
}

/// Walks the header's attributes (name\0 type\0 int32 size, value; an empty
/// name ends the list) the way OpenEXR 3.1's Header::readFrom will, and
/// refuses what would make it allocate more than the file holds or read
/// something else than this walk does. OpenEXR sizes string and unknown
/// values as declared before reading them (2 GB for a 1 KB file, found by
/// fuzzing), reads fixed-size types by their own size, and channel lists,
/// string vectors and previews by their own structure, trusting the lengths
/// inside. So: every declared size must fit in the file, fixed-size types
/// must declare their size, structured values must end exactly where their
/// size says, and names must be terminated within what OpenEXR reads (31
/// bytes, 255 with the long-names flag; channel names 255).
void checkAttributes(std::string_view bytes, int version, const std::string& path) {
    const std::size_t maxName = (version & Imf::LONG_NAMES_FLAG) ? 255 : 31;
    std::size_t at = 8; // after the magic number and version
    const auto fail = [&](const std::string& what) {
        formatFail(path, "header at byte " + std::to_string(at) + ": " + what + " (truncated or corrupt)");
    };
    // A NUL-terminated name of at most `longest` bytes before `end`.
    const auto text = [&](std::size_t longest, std::size_t end, const std::string& what) {
        const std::size_t stop = std::min(end, at + longest + 1);
        const auto nul = std::find(bytes.begin() + std::ptrdiff_t(at), bytes.begin() + std::ptrdiff_t(stop), '\0');
        if (nul == bytes.begin() + std::ptrdiff_t(stop))
            fail(what + " is not terminated within " + std::to_string(longest) + " bytes");
        std::string s(bytes.begin() + std::ptrdiff_t(at), nul);
        at += s.size() + 1;
        return s;
    };
    // A little-endian 32-bit value before `end`.
    const auto word = [&](std::size_t end, const std::string& what) {
        if (end - at < 4) fail(what + " runs past its end");
        std::uint32_t v = 0;
        for (int k = 0; k < 4; ++k) v |= std::uint32_t(std::uint8_t(bytes[at + std::size_t(k)])) << (8 * k);
        at += 4;
        return v;
    };
    for (;;) {
        const std::string name = text(maxName, bytes.size(), "an attribute name");
        if (name.empty()) return;
        const std::string type = text(maxName, bytes.size(), "the type of attribute " + name);
        const std::uint32_t size = word(bytes.size(), "the size of attribute " + name);
        if (size > bytes.size() - at)
            fail("attribute " + name + " declares " + std::to_string(size) + " bytes, more than the " +
                 std::to_string(bytes.size() - at) + " left in the file");
        const std::size_t end = at + size;
        const std::string what = "attribute " + name + " of type " + type;
        if (const std::size_t fixed = fixedValueSize(type)) {
            if (size != fixed) fail(what + " declares " + std::to_string(size) + " bytes, not " + std::to_string(fixed));
        } else if (type == "chlist") {
            // Channels: name\0, int32 type, uint8 linear, 3 reserved, int32 x and y sampling; an empty name ends it.
            while (!text(255, end, "a channel name in " + what).empty()) {
                if (end - at < 16) fail(what + " runs past its size");
                at += 16;
            }
            if (at != end) fail(what + " ends before its size");
        } else if (type == "stringvector") {
            while (at < end) {
                const std::uint32_t length = word(end, what);
                if (length > end - at) fail("a string in " + what + " runs past its size");
                at += length;
            }
        } else if (type == "preview") {
            const std::uint64_t width = word(end, what), height = word(end, what);
            if (width * height > (end - at) / 4 || width * height * 4 != end - at)
                fail(what + ": a " + std::to_string(width) + "x" + std::to_string(height) + " image does not fill it");
        } else if (type == "idmanifest") {
            fail(what + ": a .vds file has no ID manifest");
        } // string, floatvector and types OpenEXR does not know: it reads exactly the declared size
        at = end;
    }
}

/// The OpenEXR magic, version field and header of a .vds file: a single
/// part deep scanline image, its attributes checked before OpenEXR reads them.
Imf::Header readExrHeader(MemoryIStream& stream, std::string_view bytes, const std::string& path) {
    const std::uint64_t fileSize = bytes.size();
    char head[8] = {};
    if (fileSize < 8) formatFail(path, "not a .vds file (too short for OpenEXR)");
    stream.read(head, 8);
    if (!Imf::isImfMagic(head)) formatFail(path, "not a .vds file (not OpenEXR)");
    const int version = int(std::uint32_t(std::uint8_t(head[4])) | std::uint32_t(std::uint8_t(head[5])) << 8 |
                            std::uint32_t(std::uint8_t(head[6])) << 16 | std::uint32_t(std::uint8_t(head[7])) << 24);
    if (Imf::getVersion(version) != Imf::EXR_VERSION || !Imf::supportsFlags(Imf::getFlags(version)))
        formatFail(path, "unsupported OpenEXR version field");
    if (Imf::isMultiPart(version)) formatFail(path, "not a .vds file (multi-part OpenEXR)");
    if (Imf::isTiled(version) || !Imf::isNonImage(version))
        formatFail(path, "not a .vds file (not a deep scanline OpenEXR image)");
    checkAttributes(bytes, version, path);

    Imf::Header header;
    int headerVersion = version;
    header.readFrom(stream, headerVersion);
    if (!header.hasType() || header.type() != Imf::DEEPSCANLINE)
        formatFail(path, "not a .vds file (not a deep scanline OpenEXR image)");
    return header;
}

/// The image size, which bounds every allocation OpenEXR makes, the
/// compression, the channels and the format version: checked before any
/// of the image is read.
void checkImage(Imf::Header& header, std::uint64_t fileSize, const std::string& path, std::uint32_t& imageWidth,
                std::uint32_t& imageHeight, int& formatVersion) {
    const Imath::Box2i& window = header.dataWindow();
    const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
    const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
    if (window.min.x != 0 || window.min.y != 0)
        formatFail(path, "data window does not start at (0, 0)");
    if (width < 1 || height < 1 || width > kMaxResolution || height > kMaxResolution)
        formatFail(path, "image size " + std::to_string(width) + "x" + std::to_string(height) + " is out of range");
    if (std::uint64_t(width * height) * sizeof(std::uint32_t) > kMaxExpansion * fileSize)
        formatFail(path, "image size " + std::to_string(width) + "x" + std::to_string(height) +
                             " is too large for the file (truncated or corrupt)");
    header.sanityCheck(false, false);
    const Imf::Compression compression = header.compression();
    if (compression != Imf::NO_COMPRESSION && compression != Imf::RLE_COMPRESSION &&
        compression != Imf::ZIPS_COMPRESSION)
        formatFail(path, "unsupported compression for deep data");
    checkChannels(header, path);

    formatVersion = value<int>(header, kFormatVersionAttr, path);
    if (formatVersion < kOldestFormatVersion || formatVersion > Sprite::kFormatVersion)
        formatFail(path, "unsupported format version " + std::to_string(formatVersion) + " (this library reads " +
                             std::to_string(kOldestFormatVersion) + " to " + std::to_string(Sprite::kFormatVersion) +
                             ")");

    imageWidth = std::uint32_t(width);
    imageHeight = std::uint32_t(height);
}

/// The optional distance grid of a version-3 file: its three attributes or
/// none; their sizes are checked against each other here, the values by
/// `Sprite::checkConsistent`.
void readDistance(const Imf::Header& header, const std::string& path, SpriteDistance& distance) {
    const int present = int(header.find(kDistanceDimsAttr) != header.end()) +
                        int(header.find(kDistanceBoxAttr) != header.end()) +
                        int(header.find(kDistanceAttr) != header.end());
    if (present == 0) return;
    if (present != 3)
        formatFail(path, std::string("the distance grid needs all of ") + kDistanceDimsAttr + ", " + kDistanceBoxAttr +
                             " and " + kDistanceAttr);
    const Imath::V3i dims = value<Imath::V3i>(header, kDistanceDimsAttr, path);
    for (int a = 0; a < 3; ++a)
        if (dims[a] < 1 || std::uint32_t(dims[a]) > kMaxDistanceResolution)
            formatFail(path, std::string("attribute ") + kDistanceDimsAttr + " holds " + std::to_string(dims[a]) +
                                 ", expected 1 to " + std::to_string(kMaxDistanceResolution));
    const std::vector<float>& box = value<std::vector<float>>(header, kDistanceBoxAttr, path);
    if (box.size() != 6)
        formatFail(path, std::string("attribute ") + kDistanceBoxAttr + " holds " + std::to_string(box.size()) +
                             " floats, not six");
    distance.grid.dims = glm::uvec3(std::uint32_t(dims.x), std::uint32_t(dims.y), std::uint32_t(dims.z));
    distance.grid.box = {glm::vec3(box[0], box[1], box[2]), glm::vec3(box[3], box[4], box[5])};
    const std::vector<float>& cells = value<std::vector<float>>(header, kDistanceAttr, path);
    if (cells.size() != distance.grid.cellCount())
        formatFail(path, std::string("attribute ") + kDistanceAttr + " holds " + std::to_string(cells.size()) +
                             " floats, not the " + std::to_string(distance.grid.cellCount()) + " cells of " +
                             kDistanceDimsAttr);
    distance.cells = cells;
}

/// The sprite's attributes: its grid, counts, source, status and (from
/// format version 2) boundary edges.
void readAttributes(const Imf::Header& header, const std::string& path, int formatVersion, Sprite& sprite) {
    SpriteGrid& g = sprite.grid;
    const int axis = value<int>(header, kAxisAttr, path);
    if (axis < 0 || axis > 2)
        formatFail(path, "attribute vds.axis is " + std::to_string(axis) + ", expected 0, 1 or 2");
    g.axis = Axis(axis);
    g.position = toGlm(value<Imath::V3f>(header, kPositionAttr, path));
    g.matrix = toGlm(value<Imath::M33f>(header, kMatrixAttr, path));
    g.box.lo = toGlm(value<Imath::V3f>(header, kBoxMinAttr, path));
    g.box.hi = toGlm(value<Imath::V3f>(header, kBoxMaxAttr, path));
    g.texelSize = value<float>(header, kTexelSizeAttr, path);

    const int depthComplexity = value<int>(header, kDepthComplexityAttr, path);
    if (depthComplexity < 0) formatFail(path, "attribute vds.depthComplexity is negative");
    sprite.depthComplexity = std::uint32_t(depthComplexity);
    sprite.sourceName = value<std::string>(header, kSourceNameAttr, path);
    if (!parseDecimal(value<std::string>(header, kSourceTrianglesAttr, path), sprite.sourceTriangles))
        formatFail(path, "attribute vds.sourceTriangles is not a decimal number");
    const int status = value<int>(header, kStatusAttr, path);
    if (status < 0 || status > 1)
        formatFail(path, "attribute vds.status is " + std::to_string(status) + ", expected 0 or 1");
    sprite.status = SolidStatus(status);
    sprite.validation = value<std::string>(header, kValidationAttr, path);
    if (formatVersion >= 2) {
        const std::vector<float>& ends = value<std::vector<float>>(header, kBoundaryEdgesAttr, path);
        if (ends.size() % 6 != 0)
            formatFail(path, "attribute vds.boundaryEdges holds " + std::to_string(ends.size()) +
                                 " floats, not six per edge");
        sprite.boundaryEdges.resize(ends.size() / 3);
        for (std::size_t k = 0; k < sprite.boundaryEdges.size(); ++k) {
            sprite.boundaryEdges[k] = glm::vec3(ends[3 * k], ends[3 * k + 1], ends[3 * k + 2]);
            if (!std::isfinite(ends[3 * k] + ends[3 * k + 1] + ends[3 * k + 2]))
                formatFail(path, "attribute vds.boundaryEdges holds a value that is not finite");
        }
    } else {
        sprite.boundaryKnown = sprite.status == SolidStatus::Closed;
    }
    if (formatVersion >= 3) readDistance(header, path, sprite.distance);
}

std::uint64_t readHeader(MemoryIStream& stream, std::string_view bytes, const std::string& path,
                         Sprite& sprite, int& formatVersion) {
    Imf::Header header = readExrHeader(stream, bytes, path);
    checkImage(header, bytes.size(), path, sprite.grid.width, sprite.grid.height, formatVersion);
    readAttributes(header, path, formatVersion, sprite);
    std::uint64_t checksum = 0;
    if (!parseHex(value<std::string>(header, kChecksumAttr, path), checksum))
        formatFail(path, "attribute vds.checksum is not 16 lowercase hex digits");
    return checksum;
}

/// Reads the sample counts into `sprite.offsets` as prefix sums and checks
/// them against d_S and the file size.
void readOffsets(Imf::DeepScanLineInputFile& file, std::uint64_t fileSize, const std::string& path, Sprite& sprite) {
    const std::uint32_t width = sprite.width(), height = sprite.height();
    const std::size_t columns = std::size_t(width) * height;
    sprite.offsets.assign(columns + 1, 0);

    // Counts land in offsets[1..]; the prefix sum then runs in place.
    Imf::DeepFrameBuffer fb;
    fb.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(sprite.offsets.data() + 1),
                                         sizeof(std::uint32_t), sizeof(std::uint32_t) * width));
    file.setFrameBuffer(fb);
    file.readPixelSampleCounts(0, int(height) - 1);

    std::uint64_t total = 0;
    std::uint32_t most = 0;
    for (std::size_t c = 0; c < columns; ++c) {
        const std::uint32_t count = sprite.offsets[c + 1];
        most = std::max(most, count);
        total += count;
        if (total > std::numeric_limits<std::uint32_t>::max())
            formatFail(path, "more than 2^32-1 crossings in total");
        sprite.offsets[c + 1] = std::uint32_t(total);
    }
    if (most != sprite.depthComplexity)
        formatFail(path, "the most crossings in a column is " + std::to_string(most) + " but vds.depthComplexity is " +
                             std::to_string(sprite.depthComplexity));
    if (total * kBytesPerSample > kMaxExpansion * fileSize)
        formatFail(path, std::to_string(total) + " crossings cannot fit in a file of " + std::to_string(fileSize) +
                             " bytes (corrupt sample counts)");
}

/// Reads the samples into `sprite.crossings`, checking each one.
void readCrossings(Imf::DeepScanLineInputFile& file, const std::string& path, Sprite& sprite) {
    const std::uint32_t width = sprite.width(), height = sprite.height();
    const std::vector<std::uint32_t>& offsets = sprite.offsets;
    sprite.crossings.assign(std::max<std::size_t>(1, offsets.back()), 0.0f);

    const int rows = batchRows(width);
    std::vector<unsigned> counts;
    std::vector<char*> depthPointers, enteringPointers;
    std::vector<unsigned> entering;
    for (int y0 = 0; y0 < int(height); y0 += rows) {
        const int y1 = std::min(int(height), y0 + rows);
        const std::size_t first = std::size_t(y0) * width, last = std::size_t(y1) * width;
        const std::uint32_t base = offsets[first];
        const std::size_t samples = offsets[last] - base;

        counts.assign(last - first, 0);
        depthPointers.resize(last - first);
        enteringPointers.resize(last - first);
        entering.assign(std::max<std::size_t>(1, samples), 0);
        for (std::size_t c = first; c < last; ++c) {
            depthPointers[c - first] = reinterpret_cast<char*>(sprite.crossings.data() + offsets[c]);
            enteringPointers[c - first] = reinterpret_cast<char*>(entering.data() + (offsets[c] - base));
        }

        file.setFrameBuffer(batchFrameBuffer(counts.data(), depthPointers.data(), enteringPointers.data(), y0, width));
        // setFrameBuffer forgets the counts; they are read again and must not
        // have changed, since the pointers above were laid out for them.
        file.readPixelSampleCounts(y0, y1 - 1);
        for (std::size_t c = first; c < last; ++c)
            if (counts[c - first] != offsets[c + 1] - offsets[c])
                formatFail(path, "sample counts changed between reads");
        file.readPixels(y0, y1 - 1);

        for (std::size_t c = first; c < last; ++c) {
            float previous = 0.0f;
            for (std::uint32_t k = offsets[c]; k < offsets[c + 1]; ++k) {
                const float depth = sprite.crossings[k];
                const unsigned enters = entering[k - base];
                const auto where = [&] {
                    return " at texel (" + std::to_string(c % width) + ", " + std::to_string(c / width) + ")";
                };
                if (!(depth >= 0.0f && depth <= 1.0f) || std::signbit(depth))
                    formatFail(path, "depth outside [0, 1]" + where());
                if (enters > 1) formatFail(path, "\"entering\" is neither 0 nor 1" + where());
                if (depth < previous) formatFail(path, "crossings not sorted by depth" + where());
                previous = depth;
                sprite.crossings[k] = encodeCrossing(depth, enters == 1);
            }
        }
    }
    sprite.crossings.resize(offsets.back());
}

Sprite decodeBytes(const char* data, std::size_t size, const std::string& path) {
    const std::uint64_t fileSize = size;
    MemoryIStream stream(path, data, size);
    Sprite sprite;
    int formatVersion = 0;
    const std::uint64_t storedChecksum = readHeader(stream, std::string_view(data, size), path, sprite, formatVersion);

    stream.seekg(0);
    Imf::DeepScanLineInputFile file(stream);
    readOffsets(file, fileSize, path, sprite);
    readCrossings(file, path, sprite);
    // Bytes no chunk holds: appended data, or two sprites joined (read as the first, silently, before).
    if (const std::uint64_t extra = fileSize - stream.farthest(); extra > 0)
        formatFail(path, std::to_string(extra) + (extra == 1 ? " byte follows" : " bytes follow") +
                             " the sprite's last chunk (" +
                             std::to_string(stream.farthest()) + " bytes): data appended, or files joined");

    if (spriteChecksum(sprite, formatVersion) != storedChecksum) formatFail(path, "checksum mismatch (corrupt or edited file)");
    try {
        sprite.checkConsistent();
    } catch (const FormatError& e) {
        formatFail(path, e.what());
    }
    return sprite;
}

/// Runs `read`; what OpenEXR and the allocator throw becomes the library's errors.
template <class Read> auto readGuarded(const std::string& name, const Read& read) -> decltype(read()) {
    try {
        return read();
    } catch (const Error&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw OutOfMemory(name + ": not enough memory to read the sprite");
    } catch (const Iex::BaseExc& e) {
        formatFail(name, e.what());
    } catch (const std::exception& e) {
        formatFail(name, e.what());
    }
}

} // namespace

std::vector<char> encodeSprite(const Sprite& sprite, const std::string& name) {
    checkWritable(sprite, name);
    try {
        return encodeBytes(sprite, name);
    } catch (const std::bad_alloc&) {
        throw OutOfMemory(name + ": not enough memory to encode the sprite");
    } catch (const std::exception& e) { // Iex::BaseExc derives from std::exception
        throw IoError(name + ": cannot encode: " + oneLine(e.what()));
    }
}

Sprite decodeSprite(const void* data, std::size_t size, const std::string& name) {
    return readGuarded(name, [&] { return decodeBytes(static_cast<const char*>(data), size, name); });
}

void writeSprite(const Sprite& sprite, const std::string& path) {
    writeFileAtomically(path, encodeSprite(sprite, path));
}

Sprite readSprite(const std::string& path) {
    const std::vector<char> bytes = readGuarded(path, [&] { return readWholeFile(path); });
    return decodeSprite(bytes.data(), bytes.size(), path);
}

} // namespace vds
