// Slicemaps: Eisemann & Décoret, "Fast Scene Voxelization and Applications",
// I3D 2006: section 2.2 (one pass, a slice mask ORed per fragment), 2.3
// (local slicing from near/far depth maps), 2.4 (more slices with multiple
// render targets), 3.3 (front/back slicemaps and the inner-voxel rule).
// Shaders: shaders/voxel/raster.vert, slicemap_range.frag, slicemap.frag and
// the lookup include slicemap.glsl.
#include <vds/voxel/slicemap.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/shader.h>

#include "detail/slicemap.h"
#include "raster.h"

namespace vds::voxel {

Slicing parseSlicing(const std::string& s) { return parseEnum<Slicing>(s); }
const char* toString(Slicing s) { return enumName(s); }

bool Slicemap::frontBit(std::uint32_t x, std::uint32_t y, std::uint32_t s) const {
    return (front[(std::size_t(y) * grid.dims.x + x) * words + (s >> 5)] >> (s & 31u)) & 1u;
}

bool Slicemap::backBit(std::uint32_t x, std::uint32_t y, std::uint32_t s) const {
    return (back[(std::size_t(y) * grid.dims.x + x) * words + (s >> 5)] >> (s & 31u)) & 1u;
}

bool Slicemap::locate(const glm::vec3& p, std::uint32_t& column, std::uint32_t& slice) const {
    const glm::vec3 v = grid.toCells(p);
    const float fx = std::floor(v.x), fy = std::floor(v.y);
    if (!(fx >= 0.0f && fx < float(grid.dims.x) && fy >= 0.0f && fy < float(grid.dims.y))) return false;
    const std::uint32_t c = std::uint32_t(fy) * grid.dims.x + std::uint32_t(fx);
    float near = 0.0f, far = float(grid.dims.z), perDepth = 1.0f;
    if (slicing == Slicing::Local) {
        near = nearDepth[c];
        far = farDepth[c];
        perDepth = slicesPerDepth[c];
    }
    if (!(v.z >= near && v.z <= far)) return false;
    const float s = std::floor((v.z - near) * perDepth);
    column = c;
    slice = std::min(std::uint32_t(s), grid.dims.z - 1);
    return true;
}

bool Slicemap::contains(const glm::vec3& p) const {
    std::uint32_t column, slice;
    if (!locate(p, column, slice)) return false;
    return slicemapInside(&front[std::size_t(column) * words], &back[std::size_t(column) * words], words, slice);
}

std::size_t Slicemap::memoryBytes() const {
    const std::size_t columns = std::size_t(grid.dims.x) * grid.dims.y;
    return (front.size() + back.size()) * sizeof(std::uint32_t) +
           (slicing == Slicing::Local ? columns * 3 * sizeof(float) : 0);
}

std::size_t Slicemap::gpuBytes() const {
    const std::size_t columns = std::size_t(grid.dims.x) * grid.dims.y;
    return columns * 2 * renderTargets * 16 + (slicing == Slicing::Local ? columns * 16 : 0);
}

bool slicemapInside(const std::uint32_t* front, const std::uint32_t* back, std::uint32_t words, std::uint32_t slice) {
    const std::uint32_t w0 = slice >> 5, bit = 1u << (slice & 31u);
    if ((front[w0] | back[w0]) & bit) return true; // a boundary voxel
    // The last boundary voxel in front of the slice.
    for (std::uint32_t w = w0 + 1; w-- > 0;) {
        const std::uint32_t m = (front[w] | back[w]) & (w == w0 ? bit - 1u : ~0u);
        if (!m) continue;
        const int k = 31 - __builtin_clz(m);
        const bool isFront = (front[w] >> k) & 1u, isBack = (back[w] >> k) & 1u;
        if (!isBack) return true;   // after a front voxel: inside
        if (!isFront) return false; // after a back voxel: outside
        // After an ambiguous voxel the next boundary voxel decides.
        for (std::uint32_t v = w0; v < words; ++v) {
            const std::uint32_t n = (front[v] | back[v]) & (v == w0 ? ~(bit | (bit - 1u)) : ~0u);
            if (!n) continue;
            const int j = __builtin_ctz(n);
            return ((back[v] >> j) & 1u) && !((front[v] >> j) & 1u);
        }
        return false;
    }
    return false; // nothing in front
}

namespace {

// The slices of `defaultSlices` over cubic `columns`: their cells along z,
// rounded up to whole words.
std::uint32_t slicesOver(const VoxelGrid& columns) {
    return std::min<std::uint32_t>((columns.dims.z + 31u) / 32u * 32u, kMaxSlices);
}

} // namespace

std::uint32_t defaultSlices(const Box& box, std::uint32_t resolution) {
    return slicesOver(makeVoxelGrid(box, resolution));
}

namespace {

Texture makeTexture(GLenum target, GLenum format, const VoxelGrid& grid, GLsizei layers, const char* what) {
    Texture t = Texture::create(target);
    if (target == GL_TEXTURE_2D_ARRAY)
        glTextureStorage3D(t.id(), 1, format, GLsizei(grid.dims.x), GLsizei(grid.dims.y), layers);
    else
        glTextureStorage2D(t.id(), 1, format, GLsizei(grid.dims.x), GLsizei(grid.dims.y));
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    if (glGetError() == GL_OUT_OF_MEMORY) throw OutOfMemory(std::string("GL cannot allocate ") + what);
    checkGl(what);
    return t;
}

void requireComplete(const Framebuffer& fbo, const char* what) {
    if (glCheckNamedFramebufferStatus(fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw GlError(std::string(what) + " framebuffer is incomplete");
}

// Local slicing, first pass: per-column near and far fragment depth, read
// back into `map` and kept as textures for the slicemap pass.
struct RangeMaps {
    Texture near, far;
};

RangeMaps renderRanges(const GlContext& gl, const detail::MeshBuffers& mesh, Slicemap& map, std::uint32_t viewport) {
    const Program& program = gl.program("voxel.slicemap.range", [] {
        return buildProgram(
            {{GL_VERTEX_SHADER, "voxel/raster.vert", ""}, {GL_FRAGMENT_SHADER, "voxel/slicemap_range.frag", ""}});
    });
    const VoxelGrid& grid = map.grid;
    RangeMaps maps{makeTexture(GL_TEXTURE_2D, GL_R32F, grid, 1, "the near depth map"),
                   makeTexture(GL_TEXTURE_2D, GL_R32F, grid, 1, "the far depth map")};
    const Texture& near = maps.near;
    const Texture& far = maps.far;
    Framebuffer fbo = Framebuffer::create();
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, near.id(), 0);
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT1, far.id(), 0);
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo.id(), 2, buffers);
    requireComplete(fbo, "near/far depth");
    const float empty[2][4] = {{1e30f, 0, 0, 0}, {-1e30f, 0, 0, 0}}; // near > far: no fragment
    glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, empty[0]);
    glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 1, empty[1]);
    detail::setGridUniform(program.id(), "u_grid", grid);
    glProgramUniform1f(program.id(), glGetUniformLocation(program.id(), "u_viewport"), float(viewport));
    {
        const detail::RasterState state(grid, viewport);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glUseProgram(program.id());
        glEnablei(GL_BLEND, 0);
        glEnablei(GL_BLEND, 1);
        glBlendFunc(GL_ONE, GL_ONE);
        glBlendEquationi(0, GL_MIN);
        glBlendEquationi(1, GL_MAX);
        mesh.draw();
    }
    const std::size_t columns = std::size_t(grid.dims.x) * grid.dims.y;
    map.nearDepth.resize(columns);
    map.farDepth.resize(columns);
    glGetTextureImage(near.id(), 0, GL_RED, GL_FLOAT, GLsizei(columns * sizeof(float)), map.nearDepth.data());
    glGetTextureImage(far.id(), 0, GL_RED, GL_FLOAT, GLsizei(columns * sizeof(float)), map.farDepth.data());
    checkGl("slicemap near/far depth pass");
    map.slicesPerDepth.resize(columns);
    for (std::size_t c = 0; c < columns; ++c)
        map.slicesPerDepth[c] =
            map.farDepth[c] > map.nearDepth[c] ? float(grid.dims.z) / (map.farDepth[c] - map.nearDepth[c]) : 0.0f;
    map.passes += 1;
    return maps;
}

// The slicemap on `grid` (slicemapGridOver's), 32 slices a word, four
// words a render target; nothing drawn yet.
Slicemap emptySlicemap(const VoxelGrid& grid, Slicing slicing) {
    Slicemap map;
    map.slicing = slicing;
    map.grid = grid;
    const std::uint32_t slices = grid.dims.z;
    map.words = slices / 32;
    map.renderTargets = (map.words + 3) / 4;
    return map;
}

// True when both maps fit one pass (twice the targets as draw buffers);
// throws where GL cannot draw even one, or the read-back would pass 2 GiB.
bool fitsOnePass(const Slicemap& map) {
    GLint maxDrawBuffers = 0, maxAttachments = 0;
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &maxDrawBuffers);
    glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &maxAttachments);
    const std::uint32_t maxTargets = std::uint32_t(std::min(maxDrawBuffers, maxAttachments));
    const std::uint32_t targets = map.renderTargets, slices = map.grid.dims.z;
    if (targets > maxTargets)
        throw InvalidArgument(std::to_string(slices) + " slices need " + std::to_string(targets) +
                              " render targets, more than GL allows here (" + std::to_string(maxTargets) + ")");
    const std::size_t columns = std::size_t(map.grid.dims.x) * map.grid.dims.y;
    if (columns * 2 * targets * 16 > std::size_t(std::numeric_limits<GLsizei>::max()))
        throw OutOfMemory("a slicemap of " + std::to_string(map.grid.dims.x) + "x" + std::to_string(map.grid.dims.y) +
                          "x" + std::to_string(slices) + " needs more than 2 GiB; lower the resolution");
    return 2 * targets <= maxTargets;
}

// Draws the mesh into the front and back layers (one pass for both, or a
// pass each), OR-ing each fragment's slice bit.
void drawSlices(const detail::MeshBuffers& buffers, const Program& program, const Texture& layers,
                const RangeMaps& ranges, Slicemap& map, std::uint32_t viewport, bool onePass) {
    const std::uint32_t targets = map.renderTargets, outputs = onePass ? 2 * targets : targets;
    const GLint facing = glGetUniformLocation(program.id(), "u_facing");
    const detail::RasterState state(map.grid, viewport);
    glUseProgram(program.id());
    glBindTextureUnit(0, ranges.near.id());
    glBindTextureUnit(1, ranges.far.id());
    glEnable(GL_COLOR_LOGIC_OP);
    glLogicOp(GL_OR);
    const std::uint32_t passes = onePass ? 1 : 2;
    for (std::uint32_t pass = 0; pass < passes; ++pass) {
        Framebuffer fbo = Framebuffer::create();
        std::vector<GLenum> drawBuffers(outputs);
        for (std::uint32_t t = 0; t < outputs; ++t) {
            glNamedFramebufferTextureLayer(fbo.id(), GL_COLOR_ATTACHMENT0 + t, layers.id(), 0,
                                           GLint(pass * targets + t));
            drawBuffers[t] = GL_COLOR_ATTACHMENT0 + t;
        }
        glNamedFramebufferDrawBuffers(fbo.id(), GLsizei(outputs), drawBuffers.data());
        requireComplete(fbo, "slicemap");
        const GLuint zero[4] = {0, 0, 0, 0};
        for (std::uint32_t t = 0; t < outputs; ++t) glClearNamedFramebufferuiv(fbo.id(), GL_COLOR, GLint(t), zero);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glProgramUniform1i(program.id(), facing, onePass ? 0 : GLint(pass + 1));
        buffers.draw();
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    map.passes += passes;
}

// Layer-major texels (RGBA words) -> per-column words of each map.
void readSlices(const Texture& layers, Slicemap& map) {
    const std::size_t columns = std::size_t(map.grid.dims.x) * map.grid.dims.y;
    const std::uint32_t targets = map.renderTargets;
    std::vector<std::uint32_t> texels(columns * 4 * 2 * targets);
    glGetTextureImage(layers.id(), 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, GLsizei(texels.size() * sizeof(std::uint32_t)),
                      texels.data());
    checkGl("slicemap pass");
    map.front.assign(columns * map.words, 0u);
    map.back.assign(columns * map.words, 0u);
    for (std::size_t c = 0; c < columns; ++c)
        for (std::uint32_t w = 0; w < map.words; ++w) {
            const std::size_t layer = w / 4, channel = w % 4;
            map.front[c * map.words + w] = texels[(layer * columns + c) * 4 + channel];
            map.back[c * map.words + w] = texels[((targets + layer) * columns + c) * 4 + channel];
        }
}

} // namespace

Slicemap buildSlicemap(const GlContext& gl, MeshView mesh, const Box& box, std::uint32_t resolution,
                       const SlicemapOptions& options) {
    requireClosed(mesh, "mesh");
    return detail::sliceClosed(gl, mesh, box, makeVoxelGrid(box, resolution), options);
}

namespace detail {

Slicemap sliceClosed(const GlContext& gl, MeshView mesh, const Box& box, const VoxelGrid& columns,
                     const SlicemapOptions& options) {
    const std::uint32_t slices = options.slices ? options.slices : slicesOver(columns);
    if (slices % 32 != 0 || slices < 32 || slices > kMaxSlices)
        throw InvalidArgument("slicemap slices " + std::to_string(slices) + " must be a multiple of 32 in [32, " +
                              std::to_string(kMaxSlices) + "]");
    const CurrentContext current(gl); // the caller's context is current again on return
    Slicemap map = emptySlicemap(slicemapGridOver(columns, box, slices), options.slicing);
    const VoxelGrid& grid = map.grid;
    const std::uint32_t viewport = detail::rasterViewport(grid);
    const bool onePass = fitsOnePass(map);
    const std::uint32_t targets = map.renderTargets, outputs = onePass ? 2 * targets : targets;

    const detail::MeshBuffers buffers(gl, mesh);
    RangeMaps ranges;
    if (options.slicing == Slicing::Local) ranges = renderRanges(gl, buffers, map, viewport);

    const std::string defines = "#define VDS_SLICEMAP_TARGETS " + std::to_string(targets) +
                                "\n#define VDS_SLICEMAP_OUTPUTS " + std::to_string(outputs) + "\n" +
                                (options.slicing == Slicing::Local ? "#define VDS_SLICEMAP_LOCAL\n" : "");
    const Program& program = gl.program("voxel.slicemap." + std::to_string(targets) + "." + std::to_string(outputs) +
                                            (options.slicing == Slicing::Local ? ".local" : ".uniform"),
                                        [&] {
                                            return buildProgram({{GL_VERTEX_SHADER, "voxel/raster.vert", ""},
                                                                 {GL_FRAGMENT_SHADER, "voxel/slicemap.frag", ""}},
                                                                defines);
                                        });
    const Texture layers =
        makeTexture(GL_TEXTURE_2D_ARRAY, GL_RGBA32UI, grid, GLsizei(2 * targets), "the slicemap targets");
    detail::setGridUniform(program.id(), "u_grid", grid);
    glProgramUniform1f(program.id(), glGetUniformLocation(program.id(), "u_viewport"), float(viewport));
    glProgramUniform1i(program.id(), glGetUniformLocation(program.id(), "u_slices"), GLint(slices));
    glProgramUniform1i(program.id(), glGetUniformLocation(program.id(), "u_near"), 0);
    glProgramUniform1i(program.id(), glGetUniformLocation(program.id(), "u_far"), 1);
    drawSlices(buffers, program, layers, ranges, map, viewport, onePass);
    glBindTextureUnit(0, 0);
    glBindTextureUnit(1, 0);
    readSlices(layers, map);
    return map;
}

} // namespace detail

} // namespace vds::voxel
