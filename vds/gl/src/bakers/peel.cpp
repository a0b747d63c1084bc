// The depth-peeling baker (Trapp & Döllner 2008, section 4.1; Everitt 2001,
// "Interactive Order-Independent Transparency"): one pass per layer, each
// keeping the nearest crossing behind the previous layer; an occlusion query
// finds d_S. Equal depths are ordered by triangle index, as in every baker.
// Each layer is read back and the columns are built on the host.
#include <vds/gl/detail/peel.h>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/mesh.h>
#include <vds/gl/shader.h>
#include <vds/gl/detail/bake_setup.h>
#include <vds/gl/detail/raster_state.h>

namespace vds::detail {

namespace {

/// The two ping-pong targets of the peel: each pass writes one pair of
/// colour images (depth, key) and reads the other pair, the previous layer.
struct PeelTargets {
    explicit PeelTargets(const SpriteGrid& grid)
        : depth{makeTexture2D(GL_R32F, grid), makeTexture2D(GL_R32F, grid)},
          key{makeTexture2D(GL_R32UI, grid), makeTexture2D(GL_R32UI, grid)},
          depthBuffer(makeTexture2D(GL_DEPTH_COMPONENT32F, grid)), fbo{Framebuffer::create(), Framebuffer::create()} {
        const GLenum drawBuffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        for (int i = 0; i < 2; ++i) {
            glNamedFramebufferTexture(fbo[i].id(), GL_COLOR_ATTACHMENT0, depth[i].id(), 0);
            glNamedFramebufferTexture(fbo[i].id(), GL_COLOR_ATTACHMENT1, key[i].id(), 0);
            glNamedFramebufferTexture(fbo[i].id(), GL_DEPTH_ATTACHMENT, depthBuffer.id(), 0);
            glNamedFramebufferDrawBuffers(fbo[i].id(), 2, drawBuffers);
            if (glCheckNamedFramebufferStatus(fbo[i].id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
                throw GlError("depth peeling framebuffer is incomplete");
        }
    }
    Texture depth[2], key[2];
    Texture depthBuffer;
    Framebuffer fbo[2];
};

/// Peeled layers (one image each, 2.0 where empty) into columns.
void layersToColumns(const std::vector<std::vector<float>>& layers, std::size_t pixels,
                     std::vector<std::uint32_t>& offsets, std::vector<float>& crossings) {
    offsets.assign(pixels + 1, 0);
    for (std::size_t p = 0; p < pixels; ++p) {
        std::uint32_t n = 0;
        while (n < layers.size() && layers[n][p] != 2.0f) ++n;
        offsets[p + 1] = offsets[p] + n;
    }
    crossings.resize(offsets.back());
    for (std::size_t p = 0; p < pixels; ++p)
        for (std::uint32_t k = 0; k < offsets[p + 1] - offsets[p]; ++k) crossings[offsets[p] + k] = layers[k][p];
}

} // namespace

void bakePeel(const GlContext& gl, MeshView mesh, const SpriteGrid& grid, const BakeOptions& options,
              GlPhaseClock& clock, std::vector<std::uint32_t>& offsets, std::vector<float>& crossings,
              const GpuMesh* uploaded) {
    clock.begin(BakePhase::Compile, false);
    const Program& program = gl.program("vds.peel", [&] {
        return buildProgram({{GL_VERTEX_SHADER, "vds/bake.vert", ""}, {GL_FRAGMENT_SHADER, "vds/peel.frag", ""}},
                            bakeDefines(gl));
    });
    clock.begin(BakePhase::Upload);
    std::optional<GpuMesh> own;
    if (!uploaded) own.emplace(mesh);
    const GpuMesh& draw = uploaded ? *uploaded : *own;
    const std::size_t pixels = std::size_t(grid.width) * grid.height;
    const PeelTargets targets(grid);
    const Texture* depth = targets.depth;
    const Texture* key = targets.key;
    const Framebuffer* fbo = targets.fbo;
    Query query = Query::create(GL_ANY_SAMPLES_PASSED);

    const BakeRasterState state(gl, grid, program.id());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    const GLint firstLayer = glGetUniformLocation(program.id(), "u_firstLayer");

    // Layer k's encoded crossings, one image per layer (padding where empty).
    std::vector<std::vector<float>> layers;
    std::vector<float> layerDepth(pixels);
    std::vector<std::uint32_t> layerKey(pixels);
    const float emptyDepth[4] = {2.0f, 0, 0, 0};
    const GLuint emptyKey[4] = {kNoNode, 0, 0, 0};
    const float farDepth = 1.0f;
    for (int pass = 0;; ++pass) {
        const int cur = pass & 1, prev = cur ^ 1;
        clock.begin(BakePhase::Raster);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo[cur].id());
        glClearNamedFramebufferfv(fbo[cur].id(), GL_COLOR, 0, emptyDepth);
        glClearNamedFramebufferuiv(fbo[cur].id(), GL_COLOR, 1, emptyKey);
        glClearNamedFramebufferfv(fbo[cur].id(), GL_DEPTH, 0, &farDepth);
        glBindTextureUnit(0, depth[prev].id());
        glBindTextureUnit(1, key[prev].id());
        glUniform1i(firstLayer, pass == 0 ? 1 : 0);
        glBeginQuery(GL_ANY_SAMPLES_PASSED, query.id());
        draw.draw();
        glEndQuery(GL_ANY_SAMPLES_PASSED);
        GLuint any = 0;
        glGetQueryObjectuiv(query.id(), GL_QUERY_RESULT, &any);
        checkGl("depth peeling pass");
        if (!any) break;
        clock.begin(BakePhase::ReadBack);
        glGetTextureImage(depth[cur].id(), 0, GL_RED, GL_FLOAT, GLsizei(pixels * sizeof(float)), layerDepth.data());
        glGetTextureImage(key[cur].id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(pixels * sizeof(std::uint32_t)),
                          layerKey.data());
        checkGl("reading a peeled layer");
        std::vector<float> layer(pixels, 2.0f);
        for (std::size_t p = 0; p < pixels; ++p)
            if (layerKey[p] != kNoNode) layer[p] = encodeKeyed(layerDepth[p], layerKey[p]);
        layers.push_back(std::move(layer));
        report(options, "peeled layer " + std::to_string(layers.size()));
    }
    glBindTextureUnit(0, 0);
    glBindTextureUnit(1, 0);

    clock.begin(BakePhase::Scan, false); // the layers into columns, on the host
    layersToColumns(layers, pixels, offsets, crossings);
    clock.end();
}

} // namespace vds::detail
