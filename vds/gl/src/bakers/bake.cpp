// The GL bakes of <vds/gl/bake.h>: `bakeOnGl`, and `bakeToGpu`, the
// fragment-list bake (lists.cpp) without the read-back.
#include <vds/gl/bake.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/shader.h>

#include <vds/gl/detail/bake_setup.h>
#include <vds/gl/detail/context.h>
#include <vds/gl/detail/dispatch.h>
#include <vds/gl/detail/lists.h>
#include <vds/gl/detail/sprite.h>

namespace vds {

namespace {

using detail::GlPhaseClock;
using detail::GpuBand;

// Crossing k of column (i, j) into texel (i, j, k) for every band.
Texture fillTexture(const GlContext& gl, const SpriteGrid& grid, const std::vector<GpuBand>& bands,
                    std::uint32_t depthComplexity) {
    const Program& program = gl.program("vds.columns.texture", [] {
        return buildProgram({{GL_COMPUTE_SHADER, "vds/columns_texture.comp", ""}});
    });
    Texture texture = detail::makeSpriteTexture({grid.width, grid.height, std::max<std::uint32_t>(1, depthComplexity)});
    const float padding = 1.0f;
    glClearTexImage(texture.id(), 0, GL_RED, GL_FLOAT, &padding);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glUseProgram(program.id());
    glBindImageTexture(0, texture.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32UI);
    glUniform1ui(glGetUniformLocation(program.id(), "u_width"), grid.width);
    for (const GpuBand& band : bands) {
        const std::uint64_t columns = std::uint64_t(grid.width) * (band.y1 - band.y0);
        glUniform1ui(glGetUniformLocation(program.id(), "u_columns"), GLuint(columns));
        glUniform1i(glGetUniformLocation(program.id(), "u_rowBegin"), GLint(band.y0));
        glUniform1ui(glGetUniformLocation(program.id(), "u_base"), GLuint(band.base));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, band.offsets);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, band.crossings);
        glDispatchCompute(detail::strideGroups(columns), 1, 1);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    glUseProgram(0);
    checkGl("filling the sprite texture");
    return texture;
}

// One CSR for the whole sprite from the bands' (offsets are global already).
void joinBands(const SpriteGrid& grid, std::vector<GpuBand>& bands, std::uint64_t total, Buffer& offsets,
               Buffer& crossings) {
    if (bands.size() == 1) {
        offsets = std::move(bands[0].ownOffsets);
        crossings = std::move(bands[0].ownCrossings);
        return;
    }
    offsets = Buffer::create();
    crossings = Buffer::create();
    glNamedBufferStorage(offsets.id(), GLsizeiptr((std::uint64_t(grid.width) * grid.height + 1) * 4), nullptr, 0);
    glNamedBufferStorage(crossings.id(), GLsizeiptr(std::max<std::uint64_t>(total, 1) * 4), nullptr, 0);
    checkGl("allocating the sprite's columns");
    for (const GpuBand& band : bands) {
        const std::uint64_t columns = std::uint64_t(grid.width) * (band.y1 - band.y0);
        glCopyNamedBufferSubData(band.offsets, offsets.id(), 0, GLintptr(std::uint64_t(band.y0) * grid.width * 4),
                                 GLsizeiptr((columns + 1) * 4));
        if (band.count)
            glCopyNamedBufferSubData(band.crossings, crossings.id(), 0, GLintptr(band.base * 4),
                                     GLsizeiptr(band.count * 4));
    }
    checkGl("joining the row bands");
}

GpuBake bakeListsToGpu(MeshView mesh, const BakeOptions& options, const GlBakeOptions& glOptions, const GlContext& gl,
                       GpuSpriteParts parts) {
    GlPhaseClock clock(options.timings);
    const detail::ValidatedMesh v = detail::prepareGlBake(gl, mesh, options, clock);
    detail::ListsBake lists(gl, v.setup.grid, options, glOptions, clock, true);
    std::vector<GpuBand> bands;
    lists.run(mesh, [&](GpuBand& band) { bands.push_back(std::move(band)); }, v.drawn ? &*v.drawn : nullptr);

    GpuBake out;
    out.grid = v.setup.grid;
    out.crossings = lists.crossings();
    out.depthComplexity = lists.depthComplexity();
    out.status = solidStatus(v.setup.report); // as bakeCpu marks it
    out.validation = v.setup.report.summary();
    Texture texture;
    if (parts != GpuSpriteParts::ColumnsOnly) {
        const GlPhaseClock::Scope phase(clock, BakePhase::TextureFill);
        texture = fillTexture(gl, v.setup.grid, bands, out.depthComplexity);
    }
    Buffer offsets, crossings;
    if (parts != GpuSpriteParts::TextureOnly) joinBands(v.setup.grid, bands, out.crossings, offsets, crossings);
    const glm::uvec3 size{v.setup.grid.width, v.setup.grid.height, std::max<std::uint32_t>(1, out.depthComplexity)};
    {
        // The GpuSprite: an open mesh's boundary edges found and packed with their chain tree.
        const GlPhaseClock::Scope phase(clock, BakePhase::Assembly, false);
        out.sprite = GpuSprite::adopt(std::move(texture), std::move(offsets), std::move(crossings),
                                                   out.crossings, size, v.setup.grid, out.status,
                                                   v.setup.report.oriented() ? std::vector<glm::vec3>{}
                                                                       : meshBoundaryEdges(mesh)); // as bakeCpu keeps them
    }
    clock.collect();
    if (options.timings) options.timings->crossings = out.crossings;
    return out;
}

} // namespace

BakeMethod chooseBakeMethod(const GlContext& gl, std::string* why) {
    const std::string& renderer = gl.info().renderer;
    const bool software = gl.info().software;
    if (why)
        *why = software ? "bake method auto: cpu, because GL here is the software renderer " + renderer +
                              " (the CPU baker is faster for a one-shot bake there)"
                        : "bake method auto: lists (GL fragment lists) on the GPU " + renderer;
    return software ? BakeMethod::Cpu : BakeMethod::Lists;
}

Sprite bakeOnGl(const GlContext& gl, MeshView mesh, const BakeOptions& options, const GlBakeOptions& glOptions) {
    BakeOptions chosen = options;
    if (chosen.method == BakeMethod::Auto) chosen.method = chooseBakeMethod(gl);
    if (chosen.method == BakeMethod::Cpu) return bakeCpu(mesh, chosen);
    const detail::BakeClock clock(chosen.timings);
    // Validated as bakeToGpu validates: where the GPU counts the axis, while it counts.
    detail::ValidatedMesh v;
    {
        const CurrentContext current(gl);
        detail::GlPhaseClock phases(chosen.timings);
        v = detail::prepareGlBake(gl, mesh, chosen, phases);
        phases.collect();
    }
    // The axis count's upload (if any) is drawn again by the bake.
    return detail::bakePrepared(gl, v.setup, mesh, chosen, glOptions, v.drawn ? &*v.drawn : nullptr);
}

GpuBake bakeToGpu(const GlContext& gl, MeshView mesh, const BakeOptions& options, GpuSpriteParts parts,
                  const GlBakeOptions& glOptions) {
    const auto start = std::chrono::steady_clock::now();
    const CurrentContext restore(gl);
    if (options.timings) *options.timings = BakeTimings{};
    GpuBake out;
    // Auto is the fragment lists here: the point of baking to the GPU is that nothing comes back.
    if (options.method == BakeMethod::Lists || options.method == BakeMethod::Auto) {
        if (options.timings) options.timings->renderer = gl.info().renderer;
        out = bakeListsToGpu(mesh, options, glOptions, gl, parts);
    } else {
        const Sprite sprite = bakeOnGl(gl, mesh, options, glOptions);
        {
            GlPhaseClock clock(options.timings);
            clock.begin(BakePhase::TextureFill);
            out.sprite = GpuSprite(sprite, parts);
            clock.collect();
        }
        out.grid = sprite.grid;
        out.depthComplexity = sprite.depthComplexity;
        out.crossings = sprite.crossings.size();
        out.status = sprite.status;
        out.validation = sprite.validation;
    }
    if (options.timings)
        options.timings->wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

} // namespace vds
