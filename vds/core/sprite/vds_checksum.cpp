// The .vds file's checksum (docs/format.md, "Checksum"): FNV-1a over every
// field of the sprite as the file's format version lays them out.
#include <vds/detail/vds_checksum.h>

#include <cstring>
#include <string>

namespace vds::detail {

namespace {

/// 64-bit FNV-1a over a little-endian serialisation, independent of the host.
class Fnv1a64 {
public:
    void byte(std::uint8_t b) {
        hash_ ^= b;
        hash_ *= 0x100000001b3ull;
    }
    void u32(std::uint32_t v) {
        for (int k = 0; k < 4; ++k) byte(std::uint8_t(v >> (8 * k)));
    }
    void u64(std::uint64_t v) {
        for (int k = 0; k < 8; ++k) byte(std::uint8_t(v >> (8 * k)));
    }
    void f32(float f) {
        std::uint32_t bits;
        std::memcpy(&bits, &f, sizeof bits);
        u32(bits);
    }
    void str(const std::string& s) {
        u64(s.size());
        for (char c : s) byte(std::uint8_t(c));
    }
    std::uint64_t value() const { return hash_; }

private:
    std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

} // namespace

/// The checksum of docs/format.md: every field of the sprite, in this order,
/// as the file's format `version` lays them out.
std::uint64_t spriteChecksum(const Sprite& s, int version) {
    Fnv1a64 h;
    h.u32(std::uint32_t(version));
    h.u32(s.grid.width);
    h.u32(s.grid.height);
    h.u32(std::uint32_t(s.grid.axis));
    h.f32(s.grid.texelSize);
    for (int k = 0; k < 3; ++k) h.f32(s.grid.position[k]);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) h.f32(s.grid.matrix[c][r]);
    for (int k = 0; k < 3; ++k) h.f32(s.grid.box.lo[k]);
    for (int k = 0; k < 3; ++k) h.f32(s.grid.box.hi[k]);
    h.u32(s.depthComplexity);
    h.u64(s.sourceTriangles);
    h.u32(std::uint32_t(s.status));
    h.str(s.sourceName);
    h.str(s.validation);
    for (std::uint32_t o : s.offsets) h.u32(o);
    for (float c : s.crossings) h.f32(c);
    if (version >= 2) {
        h.u64(s.boundaryEdges.size() / 2);
        for (const glm::vec3& p : s.boundaryEdges)
            for (int k = 0; k < 3; ++k) h.f32(p[k]);
    }
    if (version >= 3) {
        for (int k = 0; k < 3; ++k) h.u32(s.distance.empty() ? 0u : s.distance.grid.dims[k]);
        if (!s.distance.empty()) {
            for (int k = 0; k < 3; ++k) h.f32(s.distance.grid.box.lo[k]);
            for (int k = 0; k < 3; ++k) h.f32(s.distance.grid.box.hi[k]);
        }
        for (float d : s.distance.cells) h.f32(d);
    }
    return h.value();
}

} // namespace vds::detail
