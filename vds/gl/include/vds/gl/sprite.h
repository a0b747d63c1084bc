// vds: sprites on the GPU, for the GLSL include shaders/vds/vpt.glsl, and the
// GPU classifier.
//
// `GpuSprite` holds a sprite in GL in up to two forms:
//  - the paper's texture: a width x height x d_S R32F 3D texture, nearest
//    filtering, border value 1, clamp to border (Trapp & Döllner 2008,
//    section 4.1 step 2), padded with 1.0 behind each column's crossings. A
//    shader needs the texture and the placement (P_S, M_S):
//      uniform sampler3D u_ldi; uniform VdsPlacement u_placement;
//  - the compact columns, as `Sprite` holds them (CSR: offsets + crossings)
//    in two shader storage buffers: what `GpuClassifier` reads, a column's
//    crossings side by side instead of one texture slice apart.
// and, for the generalized winding number of an open mesh, the baked mesh's
// boundary edges in a third storage buffer (vpt.glsl's VdsBoundaryEdges).
// `GpuClassifier` runs the test over many points in a compute shader, from
// host arrays or from GL buffers that stay on the GPU.
//
// The GL rule of <vds/gl/context.h> holds: a `GpuSprite` belongs to the
// context (and thread) it was made in, and refuses, with a one-line
// `GlError`, to be bound under another context, with none current, or on
// another thread that its context was not handed over to; destroyed while its context is not current, it leaves its
// GL names to that context instead of deleting another context's objects.
// `GpuClassifier` keeps the context it is given and makes it current for
// every call, restoring the caller's.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <vds/gl/context.h>
#include <vds/gl/objects.h>
#include <vds/classify.h>
#include <vds/sprite.h>

namespace vds {

/// Which forms of a sprite a `GpuSprite` keeps in GL.
enum class GpuSpriteParts : std::uint8_t {
    Both,        ///< the texture and the columns (the default)
    TextureOnly, ///< for shaders; the classifier then reads the texture
    ColumnsOnly, ///< for the classifier, without the dense texture's memory
};

/// A GpuSprite's boundary, for Rule::GeneralizedWinding (`GpuSprite::boundary`):
/// the baked mesh's boundary edges and a tree over them in one shader storage
/// buffer, with what the shader's VdsBoundary uniform needs. Belongs to the
/// context its sprite was made in, as the sprite does.
class GpuBoundary {
public:
    GpuBoundary() = default;
    /// The buffer: 2 * edgeCount() vec4 (16 bytes each, at least one), edge k
    /// from entry 2k to 2k+1, xyz the endpoint in the baked mesh's
    /// coordinates in the sprite's (s, t, r) order, loop by loop where the
    /// edges close into loops; then 14 vec4 for each of nodeCount() nodes of
    /// a tree over the loops and chains of their edges: its ball, its fan's
    /// moments, its chord and its children or edges (see
    /// shaders/vds/vpt.glsl). Empty only on a default-made sprite.
    const Buffer& buffer() const { return buffer_; }
    std::uint32_t edgeCount() const { return edgeCount_; }
    std::uint32_t nodeCount() const { return nodeCount_; }
    /// False for a sprite of an open mesh read from a version-1 .vds file:
    /// its boundary is unknown, and Rule::GeneralizedWinding refuses it.
    bool known() const { return known_; }
    /// Binds the buffer to shader storage binding `binding` (the shader's
    /// VDS_BOUNDARY_BINDING) and sets, in `program` (in use or not), the
    /// VdsBoundary uniform `name` (e.g. "u_boundary"). Throws
    /// `InvalidArgument` when `known()` is false, and `GlError` unless the
    /// sprite's context is current on its thread.
    void setUniforms(GLuint program, const std::string& name, GLuint binding) const;

private:
    friend class GpuSprite;
    /// Uploads `edges` (as `Sprite::boundaryEdges`) to the context current now.
    GpuBoundary(const SpriteGrid& grid, const std::vector<glm::vec3>& edges, bool known);
    ContextStamp context_;
    Buffer buffer_;
    std::uint32_t edgeCount_ = 0;
    std::uint32_t nodeCount_ = 0; ///< tree node records after the edges (vpt.glsl)
    bool known_ = true;
    glm::vec3 lo_{0.0f};   ///< the baked box's low corner, (s, t, r) order
    glm::vec3 step_{0.0f}; ///< (texel, texel, extent along r)
};

/// A GpuSprite's distance grid (`Sprite::distance`, `GpuSprite::distanceGrid`)
/// as `uploadDistanceTexture` makes it, uploaded with the sprite whatever its
/// parts; empty when the sprite carries none.
class GpuDistanceGrid {
public:
    GpuDistanceGrid() = default;
    explicit operator bool() const { return bool(texture_); }
    const Texture& texture() const { return texture_; }
    /// Its box, in the mesh coordinates of the bake: the `lo`, `hi` of
    /// `vdsDistance(field, lo, hi, world)` once a world point is taken back
    /// there (the inverse of the solid's placement).
    const Box& box() const { return box_; }
    /// Binds the texture to `unit` and sets the program's sampler `sampler`
    /// and the vec3 uniforms `lo` and `hi` to its box (unknown names are
    /// ignored, as GL does). Throws `InvalidArgument` when empty, and
    /// `GlError` unless the sprite's context is current on its thread.
    void setUniforms(GLuint program, const std::string& sampler, const std::string& lo, const std::string& hi,
                     GLuint unit) const;

private:
    friend class GpuSprite;
    /// Uploads `distance` to the context current now.
    explicit GpuDistanceGrid(const SpriteDistance& distance);
    ContextStamp context_;
    Texture texture_;
    Box box_;
};

class GpuSprite {
public:
    GpuSprite() = default;
    /// Uploads `sprite` to `gl` (made current for the call; the caller's
    /// context is current again on return). Throws `InvalidArgument` if
    /// the texture is asked for and exceeds GL_MAX_3D_TEXTURE_SIZE (bake at a
    /// lower resolution) and `OutOfMemory` if GL cannot hold it.
    GpuSprite(const GlContext& gl, const Sprite& sprite, GpuSpriteParts parts = GpuSpriteParts::Both);
    /// Uploads `sprite` to the context current on the calling thread, of any
    /// origin. Throws `GlError` "no GL context current" when there is none.
    explicit GpuSprite(const Sprite& sprite, GpuSpriteParts parts = GpuSpriteParts::Both);
    /// A sprite of GL objects made elsewhere in the context current on the
    /// calling thread (`bakeToGpu` builds its sprites so), which it takes
    /// over: the 3D texture and the columns, laid out as `texture()`,
    /// `offsets()` and `crossings()` say (either form may be empty),
    /// `crossingCount` crossings, `size` as `size()`, placed as `grid` says;
    /// the baked mesh's `status` and boundary edges (as
    /// `Sprite::boundaryEdges`, uploaded here). Throws `GlError` "no GL
    /// context current" when there is none.
    static GpuSprite adopt(Texture texture, Buffer offsets, Buffer crossings, std::uint64_t crossingCount,
                           glm::uvec3 size, const SpriteGrid& grid, SolidStatus status,
                           const std::vector<glm::vec3>& boundaryEdges);
    ~GpuSprite();
    GpuSprite(GpuSprite&&) noexcept = default;
    GpuSprite& operator=(GpuSprite&&) noexcept;
    GpuSprite(const GpuSprite&) = delete;
    GpuSprite& operator=(const GpuSprite&) = delete;

    /// Throws a one-line `GlError` naming `what` unless the context this
    /// sprite was made in is current on the thread it was made on.
    void requireContext(const char* what) const;

    /// The 3D texture; empty (false) where the sprite was uploaded without
    /// it (GpuSpriteParts::ColumnsOnly).
    const Texture& texture() const { return texture_; }
    /// The columns; empty (false) where the sprite was uploaded without them
    /// (GpuSpriteParts::TextureOnly): `offsets` holds at least
    /// width * height + 1 uint32 (column c = j * width + i has crossings
    /// [offsets[c], offsets[c+1])), `crossings` holds `crossingCount()`
    /// encoded crossings as floats (see `encodeCrossing`), each column sorted.
    const Buffer& offsets() const { return offsets_; }
    const Buffer& crossings() const { return crossings_; }
    std::uint64_t crossingCount() const { return crossingCount_; }
    glm::uvec3 size() const { return size_; }          ///< width, height, layers (d_S, at least 1)
    const glm::mat3& matrix() const { return matrix_; } ///< M_S
    const glm::vec3& position() const { return position_; } ///< P_S
    /// Whether the baked mesh bounded a solid (as `Sprite::status`).
    SolidStatus status() const { return status_; }
    /// Moves the sprite on the GPU without re-uploading (see Sprite::transform).
    void setPlacement(const SpriteGrid& grid);

    /// The boundary edges and their tree, for Rule::GeneralizedWinding.
    const GpuBoundary& boundary() const { return boundary_; }

    /// Binds the texture to texture unit `unit`.
    void bind(GLuint unit) const;
    /// Binds to `unit` and sets, in `program` (in use or not: the uniforms
    /// are set with glProgramUniform), the sampler uniform `sampler` and the
    /// VdsPlacement uniform `placement` (e.g. "u_ldi[2]" and "u_placement[2]").
    /// Unknown names are ignored, as GL does; leaves no GL error behind.
    void setUniforms(GLuint program, const std::string& sampler, const std::string& placement, GLuint unit) const;

    /// The sprite's distance grid; empty when the sprite carries none.
    const GpuDistanceGrid& distanceGrid() const { return distance_; }

private:
    void upload(const Sprite& sprite, GpuSpriteParts parts);
    void releaseIfForeign() noexcept;
    ContextStamp context_;
    Texture texture_;
    Buffer offsets_;
    Buffer crossings_;
    std::uint64_t crossingCount_ = 0;
    glm::uvec3 size_{0};
    glm::mat3 matrix_{1.0f};
    glm::vec3 position_{0.0f};
    SolidStatus status_ = SolidStatus::Closed;
    GpuBoundary boundary_;
    GpuDistanceGrid distance_;
};

/// Classifies points against a GpuSprite with a compute shader. Answers are
/// identical to `classify()` on the CPU for the same sprite and points: the
/// same arithmetic, in the same order (shaders/vds/vpt.glsl).
///
/// Reads the sprite's columns when it has them (and they fit one shader
/// storage block), else its 3D texture. Owns its programs and, for the host
/// array call, persistently mapped staging buffers that grow to the largest
/// batch and are kept between calls. Belongs to `gl`, given at
/// construction, which it makes current for every call (restoring the
/// caller's) and at destruction. Refuses other threads and sprites of
/// other contexts with a one-line `GlError`. Not thread safe.
/// How `GpuClassifier`'s host arrays reach the GPU. Both stage the points
/// in persistently mapped host buffers; then
///  - `Mapped`: the shader reads them there and writes the labels there
///    (no copy: right where the GPU shares the host's memory, as llvmpipe);
///  - `Copied`: GL copies them to GPU memory, the shader runs there, and
///    the labels are copied back (the bus crossed by the copy engine, in
///    large transfers, rather than by the shader's scattered reads: right
///    for discrete GPUs);
///  - `Auto`: `Copied` on a hardware renderer, `Mapped` on a software one.
enum class HostTransfer : std::uint8_t { Auto, Mapped, Copied };

class GpuClassifier {
public:
    /// Takes the compute programs from `gl`'s cache (built there on first
    /// use); `gl` must outlive the classifier. Host batches go to the GPU `batchPoints` at a time (rounded down to a
    /// multiple of 4, at least 1024), by `transfer`. Throws `GlError`.
    explicit GpuClassifier(const GlContext& gl, std::size_t batchPoints = std::size_t(1) << 22,
                           HostTransfer transfer = HostTransfer::Auto);
    ~GpuClassifier();
    GpuClassifier(GpuClassifier&&) noexcept;
    GpuClassifier& operator=(GpuClassifier&&) noexcept;
    GpuClassifier(const GpuClassifier&) = delete;
    GpuClassifier& operator=(const GpuClassifier&) = delete;

    /// Every rule of `Rule`: Rule::GeneralizedWinding on a sprite with
    /// boundary edges adds the boundary term in float (vpt.glsl says where
    /// that can change a label against the CPU's double), O(boundary edges)
    /// a point; with none it reads as Winding. Throws `InvalidArgument` for
    /// it on a sprite whose boundary is unknown (`GpuBoundary::known()`).
    ///
    /// Host arrays to host arrays, the contract of <vds/classify.h>:
    /// `labels` holds `points.count` bytes (caller-owned), 1 inside, 0
    /// outside; `options.rule` is answered, `threads` ignored. Points go in
    /// batches (see the constructor), three in flight: while the GPU takes
    /// one batch across and classifies it, the next is copied (converted
    /// from strided or double points) into another staging buffer and an
    /// earlier one's labels out. Returns when every label is written.
    void classify(const GpuSprite& sprite, const PointsView& points, std::uint8_t* labels,
                  const ClassifyOptions& options = {});

    /// GL buffers to GL buffers, with no host transfer: for renderers, and
    /// for CUDA or other APIs that share buffers with GL. The buffers are
    /// names of the classifier's context.
    ///  - `points`: a buffer of at least 12 * count bytes from offset 0,
    ///    point k's x, y, z as floats at bytes 12k, 12k+4, 12k+8 (tightly
    ///    packed vec3, the layout of glm::vec3 and CUDA's float3 arrays);
    ///  - `labels`: a buffer of at least 4 * ceil(count / 4) bytes; byte k
    ///    receives point k's label, 1 inside or 0 outside (one byte a point,
    ///    like the host call's uint8 array), written as 32-bit words, four
    ///    labels each (the word's low byte first: bytes on little-endian
    ///    hosts, which every supported platform is); the tail word's unused
    ///    bytes become 0.
    /// Only queues GL commands, does not wait: a glMemoryBarrier before the
    /// dispatch makes earlier shader writes to `points` visible, one after
    /// it (all bits) makes the labels visible to every later GL command.
    /// Mapping the buffer into CUDA afterwards (cudaGraphicsMapResources)
    /// waits for them.
    void classify(const GpuSprite& sprite, GLuint points, std::size_t count, GLuint labels,
                  const ClassifyOptions& options = {});

private:
    struct Slot {
        Buffer points, labels;             // staging, mapped
        Buffer gpuPoints, gpuLabels;       // HostTransfer::Copied: in GPU memory
        void* pointsMap = nullptr;
        const void* labelsMap = nullptr;
        Fence done;
        std::size_t first = 0, count = 0;
    };
    void dispatch(const GpuSprite& sprite, GLuint points, GLintptr pointsOffset, GLuint labels,
                  GLintptr labelsOffset, std::size_t count, Rule rule);
    void reserve(std::size_t points);
    void finish(Slot& slot, std::uint8_t* labels);
    void send(Slot& slot, const GpuSprite& sprite, Rule rule);
    void copy(void* dst, const void* src, std::size_t bytes);
    void enter(const char* what) const;

    const GlContext* gl_ = nullptr;
    ContextStamp stamp_;
    std::size_t batch_ = std::size_t(1) << 22;
    std::uint64_t maxBlock_ = 0;
    std::size_t maxDispatch_ = 0;
    // Three batches in flight: one being staged by the host, one crossing
    // or classified on the GPU, one's labels being copied out.
    std::array<Slot, 3> slots_;
    std::size_t capacity_ = 0;
    bool copied_ = false; // HostTransfer::Copied, Auto resolved
};

} // namespace vds
