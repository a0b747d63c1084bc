// STL, binary and ASCII (3D Systems, "Stereolithography Interface
// Specification", 1989). A binary file is 84 + 50 n bytes, n the little-endian
// count at byte 80; a file of any other size must be ASCII ("solid ...
// facet normal ... outer loop vertex ... endloop endfacet ... endsolid", one
// or more solids; keywords in any case). Normals and attribute bytes are read
// past. STL has no shared vertices: every corner is stored with each of its
// triangles, so corners are welded by exact position (+0 and -0 alike), in
// order of first appearance; a binary file and its ASCII twin load alike.
#include <vds/detail/mesh_readers.h>

#include <cmath>
#include <cstring>

#include <vds/detail/text_scanner.h>

#include <vds/error.h>

namespace vds::detail {
namespace {

constexpr std::uint64_t kBinaryHeader = 84;
constexpr std::uint64_t kBinaryTriangle = 50;

/// Corners to indices by exact position: an open-addressing table of vertex
/// indices, linear probing, kept at most half full; a slot holds the upper
/// half of the position's hash beside the index, so a probe compares
/// positions only when the hashes agree.
class Welder {
public:
    Welder(TriangleMesh& mesh, std::size_t expected) : mesh_(mesh) { resize(2 * expected); }

    /// Asks for the cache line of `p`'s slot, for an `add(p)` a little later.
    void prefetch(glm::vec3 p) const {
        p += glm::vec3(0.0f);
        std::uint32_t bits[3];
        std::memcpy(bits, &p, sizeof bits);
        __builtin_prefetch(&table_[std::size_t(hash(bits) >> shift_)]);
    }

    std::uint32_t add(glm::vec3 p) {
        p += glm::vec3(0.0f); // -0 becomes +0, so both weld to one vertex
        std::uint32_t bits[3];
        std::memcpy(bits, &p, sizeof bits);
        const std::uint64_t h = hash(bits);
        for (std::size_t slot = std::size_t(h >> shift_);; slot = (slot + 1) & mask_) {
            const std::uint64_t entry = table_[slot];
            if (entry == kEmpty) {
                if (2 * (mesh_.positions.size() + 1) > table_.size()) {
                    resize(2 * table_.size());
                    return add(p);
                }
                const auto index = std::uint32_t(mesh_.positions.size());
                table_[slot] = (h & kTag) | index;
                mesh_.positions.push_back(p);
                return index;
            }
            if ((entry & kTag) == (h & kTag) && std::memcmp(&mesh_.positions[std::uint32_t(entry)], bits, 12) == 0)
                return std::uint32_t(entry);
        }
    }

private:
    static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
    static constexpr std::uint64_t kTag = 0xFFFFFFFF00000000ull;

    static std::uint64_t hash(const std::uint32_t bits[3]) {
        const std::uint64_t h = ((std::uint64_t(bits[0]) << 32) | bits[1]) * 0x9E3779B97F4A7C15ull ^
                                std::uint64_t(bits[2]) * 0xC2B2AE3D27D4EB4Full;
        return (h ^ (h >> 31)) * 0xBF58476D1CE4E5B9ull;
    }

    /// A table of at least `slots` slots (a power of two) holding the vertices so far.
    void resize(std::size_t slots) {
        int bits = 4;
        while ((std::size_t(1) << bits) < slots) ++bits;
        shift_ = 64 - bits;
        mask_ = (std::size_t(1) << bits) - 1;
        table_.assign(mask_ + 1, kEmpty);
        for (std::size_t i = 0; i < mesh_.positions.size(); ++i) {
            std::uint32_t key[3];
            std::memcpy(key, &mesh_.positions[i], sizeof key);
            const std::uint64_t h = hash(key);
            std::size_t slot = std::size_t(h >> shift_);
            while (table_[slot] != kEmpty) slot = (slot + 1) & mask_;
            table_[slot] = (h & kTag) | i;
        }
    }

    TriangleMesh& mesh_;
    std::vector<std::uint64_t> table_;
    int shift_ = 60;
    std::size_t mask_ = 15;
};

std::uint32_t loadLittle32(const char* p) {
    const auto* b = reinterpret_cast<const unsigned char*>(p);
    return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
}

float loadLittleFloat(const char* p) {
    const std::uint32_t bits = loadLittle32(p);
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

TriangleMesh readBinary(const char* data, std::uint64_t count, const std::string& name) {
    TriangleMesh mesh;
    mesh.triangles.reserve(count);
    Welder welder(mesh, count / 2); // a closed mesh has about half as many vertices as triangles
    const auto cornerAt = [&](std::uint64_t t, int k) {
        const char* p = data + kBinaryHeader + t * kBinaryTriangle + 12 + 12 * k;
        return glm::vec3(loadLittleFloat(p), loadLittleFloat(p + 4), loadLittleFloat(p + 8));
    };
    constexpr std::uint64_t kAhead = 4; // triangles whose slots are fetched while this one is welded
    for (std::uint64_t t = 0; t < count; ++t) {
        if (t + kAhead < count)
            for (int k = 0; k < 3; ++k) welder.prefetch(cornerAt(t + kAhead, k));
        const std::uint64_t at = kBinaryHeader + t * kBinaryTriangle + 12; // after the normal
        std::uint32_t corner[3];
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 v = cornerAt(t, k);
            if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)))
                failAtByte(name, at + 12 * k,
                           "triangle " + std::to_string(t) + ", corner " + std::to_string(k) + " is not finite");
            corner[k] = welder.add(v);
        }
        mesh.triangles.emplace_back(corner[0], corner[1], corner[2]);
    }
    return mesh;
}

class AsciiStlReader {
public:
    AsciiStlReader(const char* data, std::size_t size, const std::string& name) : text_(data, size), name_(name) {}

    TriangleMesh read() {
        std::string_view token;
        text_.nextToken(token); // "solid", checked by the caller
        text_.restOfLine();     // its name
        for (;;) {
            if (!text_.nextToken(token)) fail("file ends before 'endsolid' (truncated?)");
            if (equalsKeyword(token, "facet")) {
                facet();
            } else if (equalsKeyword(token, "endsolid")) {
                text_.restOfLine();
                if (!text_.nextToken(token)) break;
                if (!equalsKeyword(token, "solid")) fail("expected 'solid' or the end of the file, found " + quoted(token));
                text_.restOfLine();
            } else {
                fail("expected 'facet' or 'endsolid', found " + quoted(token));
            }
        }
        return std::move(mesh_);
    }

private:
    [[noreturn]] void fail(const std::string& what) const { failAtLine(name_, text_.line(), what); }

    void expect(const char* keyword) {
        std::string_view token;
        if (!text_.nextToken(token)) fail(std::string("file ends where '") + keyword + "' belongs (truncated?)");
        if (!equalsKeyword(token, keyword)) fail(std::string("expected '") + keyword + "', found " + quoted(token));
    }

    std::string_view nextToken(const char* what) {
        std::string_view token;
        if (!text_.nextToken(token)) fail(std::string("file ends inside ") + what + " (truncated?)");
        return token;
    }

    void facet() {
        expect("normal");
        for (int k = 0; k < 3; ++k) { // read past; exporters write NaN normals for slivers
            const std::string_view token = nextToken("a normal");
            double ignored = 0.0;
            const NumberStatus status = parseNumber(token, ignored);
            if (status == NumberStatus::Malformed) fail("normal " + numberProblem(status, token, "a number"));
        }
        expect("outer");
        expect("loop");
        corners_.clear();
        for (;;) {
            const std::string_view token = nextToken("a facet");
            if (equalsKeyword(token, "endloop")) break;
            if (!equalsKeyword(token, "vertex")) fail("expected 'vertex' or 'endloop', found " + quoted(token));
            float xyz[3];
            for (float& c : xyz) {
                const std::string_view number = nextToken("a vertex");
                c = parseCoordinate(number, name_, text_.line());
            }
            corners_.push_back(welder_.add({xyz[0], xyz[1], xyz[2]}));
        }
        appendFan(mesh_, corners_);
        expect("endfacet");
    }

    TextScanner text_;
    const std::string& name_;
    TriangleMesh mesh_;
    Welder welder_{mesh_, 64};
    std::vector<std::uint32_t> corners_;
};

bool startsWithSolid(const char* data, std::size_t size) {
    std::size_t i = 0;
    while (i < size && (isBlank(data[i]) || data[i] == '\n')) ++i;
    return size - i >= 5 && equalsKeyword(std::string_view(data + i, 5), "solid");
}

} // namespace

TriangleMesh readStl(const char* data, std::size_t size, const std::string& name) {
    if (size >= kBinaryHeader) {
        const std::uint64_t count = loadLittle32(data + 80);
        if (kBinaryHeader + count * kBinaryTriangle == size) return readBinary(data, count, name);
    }
    if (startsWithSolid(data, size)) return AsciiStlReader(data, size, name).read();
    if (size < kBinaryHeader)
        throw FormatError(name + ": not an STL file: not ASCII (no 'solid' first) and shorter than the 84 bytes of a "
                                 "binary header");
    const std::uint64_t count = loadLittle32(data + 80);
    failAtByte(name, 80,
               "binary STL header declares " + std::to_string(count) + " triangles, which take " +
                   std::to_string(kBinaryHeader + count * kBinaryTriangle) + " bytes; the file has " +
                   std::to_string(size));
}

} // namespace vds::detail
