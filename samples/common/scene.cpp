// Samples: scenes rendered through vds/styles.glsl (see scene.h).
//
// The exact reference: depth peeling writes the world position of every
// fragment layer of every pixel; the CPU classifies each against each solid
// with the exact classifier (<vds/exact.h>) into a per-layer bit mask; the
// same shading program, built with SCENE_LOOKUP_EXACT, then finds its
// fragment's layer by depth (gl_Position is invariant, so both programs
// rasterize identical depths) and reads the solids' answers from the mask.
#include "scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>

#include <GL/gl.h>
#include <GL/glext.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <vds/all.h>
#include <vds/distance.h>
#include <vds/bake.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/gl/objects.h>
#include <vds/gl/sprite.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>
#include <vds/gl/shader.h>
#include <vds/voxel/gpu_grid.h>
#include <vds/voxel/representation.h>

namespace vds::samples {
// shaders/samples/scene.* and the voxel lookups, embedded by vds_embed_shaders.
extern const vds::ShaderFile kSceneShaders[];
extern const std::size_t kSceneShadersCount;
} // namespace vds::samples

namespace vds::samples {

namespace {

constexpr std::size_t kMaxSolids = 8;
constexpr int kMaxLayers = 32;

const std::pair<const char*, Lookup> kLookupNames[] = {{"vds", Lookup::Vds},
                                                       {"slicemap", Lookup::Slicemap},
                                                       {"slicemap-local", Lookup::SlicemapLocal},
                                                       {"solid", Lookup::Solid},
                                                       {"exact", Lookup::Exact}};

/// Gives `sprite` the distance grid of `solid` for the distance effects:
/// the sprite's own, or one baked from the solid's mesh.
void addDistance(const Scene& scene, const SceneSolid& solid, Lookup lookup, std::optional<Sprite>& sprite) {
    if (lookup != Lookup::Vds)
        throw InvalidArgument("the distance band and lens edge read the sprites' distance grids: --with vds only");
    if (!(scene.distanceWidth < 1e30f)) throw InvalidArgument("the distance width is not finite");
    if (!sprite->distance.empty()) return;
    if (solid.mesh.triangles.empty())
        throw InvalidArgument("solid '" + solid.name + "' carries no distance grid (bake it with --distance N)");
    sprite->distance = bakeDistance(solid.mesh, sprite->grid.box, scene.distanceResolution, scene.rule);
}

const char* lookupDefine(Lookup lookup) {
    switch (lookup) {
    case Lookup::Vds: return "SCENE_LOOKUP_VDS";
    case Lookup::Slicemap: return "SCENE_LOOKUP_SLICEMAP";
    case Lookup::SlicemapLocal: return "SCENE_LOOKUP_SLICEMAP_LOCAL";
    case Lookup::Solid: return "SCENE_LOOKUP_SOLID";
    case Lookup::Exact: return "SCENE_LOOKUP_EXACT";
    }
    return "";
}

GLint location(GLuint program, const std::string& name) { return glGetUniformLocation(program, name.c_str()); }

std::string mib(std::size_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f MiB", double(bytes) / (1024.0 * 1024.0));
    return text;
}

// Area-weighted vertex normals, for Gouraud shading and X-ray rims.
std::vector<glm::vec3> vertexNormals(const TriangleMesh& mesh) {
    std::vector<glm::vec3> normals(mesh.positions.size(), glm::vec3(0.0f));
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::vec3 n = glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]);
        for (int k = 0; k < 3; ++k) normals[t[k]] += n;
    }
    for (glm::vec3& n : normals) n = glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 0, 1);
    return normals;
}

// Voxel resolution whose GPU bytes come closest to `budget` without passing it.
std::uint32_t equalMemoryResolution(const Box& box, voxel::Representation representation, std::size_t budget) {
    const auto bytes = [&](std::uint32_t r) {
        const voxel::VoxelGrid g = voxel::makeVoxelGrid(box, r);
        const std::size_t columns = std::size_t(g.dims.x) * g.dims.y;
        if (representation == voxel::Representation::Solid) return g.wordCount() * 4;
        const std::uint32_t targets = (voxel::defaultSlices(box, r) + 127u) / 128u;
        return columns * 2 * targets * 16 + (representation == voxel::Representation::SlicemapLocal ? columns * 16 : 0);
    };
    std::uint32_t lo = 1, hi = 4096;
    while (lo < hi) {
        const std::uint32_t mid = (lo + hi + 1) / 2;
        if (bytes(mid) <= budget) lo = mid;
        else hi = mid - 1;
    }
    return lo;
}

struct Camera {
    glm::mat4 viewProjection;
    glm::vec3 towardsViewer;
};

// Orthographic, fitted to the box's bounding sphere along the picture's
// shorter side (a square picture sees exactly the sphere).
Camera camera(const Box& box, const Scene& scene, std::uint32_t width, std::uint32_t height) {
    const glm::vec3 centre = 0.5f * (box.lo + box.hi);
    const float radius = 0.5f * glm::length(box.hi - box.lo);
    const glm::vec3 direction = glm::normalize(scene.viewDirection);
    const glm::mat4 lookAt = glm::lookAt(centre + 3.0f * radius * direction, centre, scene.up);
    const float sx = width >= height ? float(width) / float(height) : 1.0f;
    const float sy = width >= height ? 1.0f : float(height) / float(width);
    const glm::mat4 ortho = glm::ortho(-radius * sx, radius * sx, -radius * sy, radius * sy, 0.5f * radius, 6.0f * radius);
    return {ortho * lookAt, direction};
}

struct Target {
    std::uint32_t width = 0, height = 0;
    Texture colour, depth;
    Framebuffer fbo;
};

Target makeTarget(std::uint32_t width, std::uint32_t height) {
    Target t;
    t.width = width;
    t.height = height;
    t.colour = Texture::create(GL_TEXTURE_2D);
    t.depth = Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(t.colour.id(), 1, GL_RGBA8, GLsizei(width), GLsizei(height));
    glTextureStorage2D(t.depth.id(), 1, GL_DEPTH_COMPONENT32F, GLsizei(width), GLsizei(height));
    t.fbo = Framebuffer::create();
    glNamedFramebufferTexture(t.fbo.id(), GL_COLOR_ATTACHMENT0, t.colour.id(), 0);
    glNamedFramebufferTexture(t.fbo.id(), GL_DEPTH_ATTACHMENT, t.depth.id(), 0);
    if (glCheckNamedFramebufferStatus(t.fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw GlError("offscreen framebuffer is incomplete");
    return t;
}

void nearest(const Texture& t) {
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

} // namespace

Lookup parseLookup(const std::string& name) {
    for (const auto& [text, lookup] : kLookupNames)
        if (name == text) return lookup;
    throw InvalidArgument("unknown lookup '" + name + "' (vds, slicemap, slicemap-local, solid or exact)");
}

const char* toString(Lookup lookup) {
    for (const auto& [text, l] : kLookupNames)
        if (l == lookup) return text;
    return "?";
}

// ---- Scenes ----------------------------------------------------------------------

TriangleMesh uvSphere(const glm::vec3& centre, float radius, int rings) {
    TriangleMesh m;
    const int segments = 2 * rings;
    m.positions.push_back(centre + glm::vec3(0, radius, 0));
    for (int i = 1; i < rings; ++i) {
        const float theta = glm::pi<float>() * float(i) / float(rings);
        for (int j = 0; j < segments; ++j) {
            const float phi = 2.0f * glm::pi<float>() * float(j) / float(segments);
            m.positions.push_back(centre + radius * glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                                              -std::sin(theta) * std::sin(phi)));
        }
    }
    m.positions.push_back(centre - glm::vec3(0, radius, 0));
    const auto ring = [&](int i, int j) { return std::uint32_t(1 + (i - 1) * segments + (j % segments)); };
    const std::uint32_t bottom = std::uint32_t(m.positions.size() - 1);
    for (int j = 0; j < segments; ++j) {
        m.triangles.push_back({0u, ring(1, j), ring(1, j + 1)});
        for (int i = 1; i + 1 < rings; ++i) {
            m.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
            m.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
        }
        m.triangles.push_back({ring(rings - 1, j), bottom, ring(rings - 1, j + 1)});
    }
    return m;
}

TriangleMesh box(const glm::vec3& lo, const glm::vec3& hi) {
    TriangleMesh m;
    for (int k = 0; k < 8; ++k) m.positions.push_back({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
    const std::uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces) {
        m.triangles.push_back({f[0], f[1], f[2]});
        m.triangles.push_back({f[0], f[2], f[3]});
    }
    return m;
}

Scene clipScene(const std::string& dataDir, Combine combine) {
    Scene s;
    s.name = combine == Combine::Union ? "clip" : "clip-intersection";
    s.model = loadMesh(dataDir + "/spot.obj");
    s.combineAway = combine;
    // Union: the bundled sphere over the body, a slab under the hooves and
    // a sphere at the head cut three holes. Intersection: the body sphere
    // and a half-space box, which overlap, cut the sphere's half on +x.
    s.solids.push_back({"body-sphere", loadMesh(dataDir + "/lens.obj"), {}, glm::mat4(1.0f), Role::ClipAway, Style::Shaded});
    if (combine == Combine::Union) {
        s.solids.push_back({"hoof-slab", box({-0.6f, -0.8f, -0.8f}, {0.6f, -0.55f, 1.1f}), {}, glm::mat4(1.0f),
                            Role::ClipAway, Style::Shaded});
        s.solids.push_back({"head-sphere", uvSphere({0.25f, 0.62f, -0.45f}, 0.2f, 24), {}, glm::mat4(1.0f),
                            Role::ClipAway, Style::Shaded});
    } else {
        s.solids.push_back({"half-box", box({0.05f, -0.8f, -0.8f}, {0.6f, 1.0f, 1.1f}), {}, glm::mat4(1.0f),
                            Role::ClipAway, Style::Shaded});
    }
    return s;
}

glm::mat4 lensPath(float t) {
    // From the head over the back to the tail, shrinking a little.
    const glm::vec3 from(0.0f, 0.3f, -0.55f), to(0.0f, 0.45f, 0.75f);
    const float scale = 1.0f - 0.25f * t;
    return glm::scale(glm::translate(glm::mat4(1.0f), from + t * (to - from)), glm::vec3(scale));
}

Scene lensScene(const std::string& dataDir) {
    Scene s;
    s.name = "lens";
    s.model = loadMesh(dataDir + "/spot.obj");
    s.baseStyle = Style::Gouraud;
    s.viewDirection = {1.0f, 0.45f, 0.35f};
    // A sphere of radius 0.42 around the origin, moved along lensPath.
    s.solids.push_back({"lens", uvSphere(glm::vec3(0.0f), 0.42f, 24), {}, lensPath(0.0f), Role::Lens, Style::XRay});
    return s;
}

Scene stylesScene(const std::string& dataDir) {
    Scene s;
    s.name = "styles";
    s.model = loadMesh(dataDir + "/spot.obj");
    s.baseStyle = Style::Gouraud;
    s.viewDirection = {1.0f, 0.45f, 0.35f};
    // Paper Figure 3: the head in blueprint, a sphere over the body in
    // X-ray, the rest Gouraud.
    s.solids.push_back({"head-box", box({-0.7f, -0.9f, -0.9f}, {0.7f, 1.2f, -0.15f}), {}, glm::mat4(1.0f), Role::Style,
                        Style::Blueprint});
    s.solids.push_back({"body-sphere", loadMesh(dataDir + "/lens.obj"), {}, glm::mat4(1.0f), Role::Style, Style::XRay});
    return s;
}

// ---- Rendering ----------------------------------------------------------------------

struct SceneRenderer::Impl {
    const GlContext* gl = nullptr;
    Scene scene;
    Lookup lookup;
    RepresentationSize size;
    Program shading, peel;
    Buffer positions, normals, indices;
    VertexArray vao;
    GLsizei indexCount = 0;
    Box bounds;
    Camera view;

    // Per solid, one of:
    std::vector<Sprite> baked;             // Vds: the sprite at its bake placement
    std::vector<GpuSprite> sprites;        // Vds
    std::vector<voxel::Model> models;      // voxel lookups
    std::vector<voxel::GpuBitGrid> bitGrids;   // Lookup::Solid, one a solid
    std::vector<voxel::GpuSlicemap> slicemaps; // Lookup::Slicemap(Local), one a solid
    std::vector<ExactClassifier> exact;    // Exact
    std::vector<std::uint32_t> resolutions;
    std::size_t bytes = 0;

    // Exact reference: peeled layers.
    Texture layerDepth, layerMask;
    int layerCount = 0;
    std::uint32_t peeledWidth = 0, peeledHeight = 0;
    bool peelStale = true; // a solid moved since the last peel
    std::optional<Target> window; // drawTo's picture, blitted to its framebuffer

    void buildPrograms();
    void uploadModel();
    void setUniforms(GLuint program);
    void setDistanceUniforms(GLuint program, std::size_t solid, GLuint unit);
    void peelAndClassify(std::uint32_t width, std::uint32_t height);
    void prepare(std::uint32_t width, std::uint32_t height, bool alwaysPeel);
    void draw(GLuint framebuffer, std::uint32_t width, std::uint32_t height);
};

SceneRenderer::SceneRenderer(const GlContext& gl, const Scene& scene, Lookup lookup, RepresentationSize size)
    : impl_(std::make_unique<Impl>()) {
    Impl& d = *impl_;
    d.gl = &gl;
    d.scene = scene;
    d.lookup = lookup;
    d.size = size;
    if (scene.solids.empty() || scene.solids.size() > kMaxSolids)
        throw InvalidArgument("a scene takes 1 to 8 solids, not " + std::to_string(scene.solids.size()));
    requireUsable(validateMesh(scene.model), scene.name);
    gl.makeCurrent();

    GlContext& context = const_cast<GlContext&>(gl); // buildModel takes the caller's context to make current
    for (const SceneSolid& solid : scene.solids) {
        if (lookup != Lookup::Vds && solid.mesh.triangles.empty())
            throw InvalidArgument("solid '" + solid.name + "' is a sprite only; --with " + toString(lookup) +
                                  " needs its mesh");
        std::optional<Sprite> sprite = solid.sprite;
        if (!sprite && (lookup == Lookup::Vds || size.equalMemory)) {
            BakeOptions options;
            options.resolution = size.resolution;
            options.axis = chooseViewAxis(solid.mesh, size.resolution).axis;
            sprite = bake(gl, solid.mesh, options);
        }
        if (scene.distanceWidth > 0.0f) addDistance(scene, solid, lookup, sprite);
        switch (lookup) {
        case Lookup::Vds:
            d.sprites.emplace_back(*sprite, GpuSpriteParts::TextureOnly);
            d.baked.push_back(*sprite);
            d.baked.back().distance = {}; // on the GPU; place() copies the rest
            d.bytes += sprite->denseBytes();
            d.resolutions.push_back(std::max(sprite->width(), sprite->height()));
            break;
        case Lookup::Exact:
            d.exact.emplace_back(solid.mesh);
            d.resolutions.push_back(0);
            break;
        default: {
            const voxel::Representation representation = lookup == Lookup::Slicemap ? voxel::Representation::Slicemap
                                                         : lookup == Lookup::SlicemapLocal
                                                             ? voxel::Representation::SlicemapLocal
                                                             : voxel::Representation::Solid;
            voxel::ModelOptions options;
            options.resolution = size.equalMemory
                                     ? equalMemoryResolution(meshBounds(solid.mesh), representation, sprite->denseBytes())
                                     : size.resolution;
            d.models.push_back(voxel::buildModel(context, solid.mesh, representation, options));
            gl.makeCurrent();
            d.resolutions.push_back(options.resolution);
            d.bytes += d.models.back().gpuBytes();
            break;
        }
        }
    }
    d.uploadModel();
    d.buildPrograms();
    for (std::size_t i = 0; i < scene.solids.size(); ++i) place(i, scene.solids[i].placement);
    d.bounds = meshBounds(scene.model);
}

SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::Impl::uploadModel() {
    const std::vector<glm::vec3> n = vertexNormals(scene.model);
    positions = Buffer::create();
    normals = Buffer::create();
    indices = Buffer::create();
    glNamedBufferStorage(positions.id(), GLsizeiptr(scene.model.positions.size() * sizeof(glm::vec3)),
                         scene.model.positions.data(), 0);
    glNamedBufferStorage(normals.id(), GLsizeiptr(n.size() * sizeof(glm::vec3)), n.data(), 0);
    glNamedBufferStorage(indices.id(), GLsizeiptr(scene.model.triangles.size() * sizeof(glm::uvec3)),
                         scene.model.triangles.data(), 0);
    indexCount = GLsizei(scene.model.triangles.size() * 3);
    vao = VertexArray::create();
    glVertexArrayVertexBuffer(vao.id(), 0, positions.id(), 0, sizeof(glm::vec3));
    glVertexArrayVertexBuffer(vao.id(), 1, normals.id(), 0, sizeof(glm::vec3));
    for (GLuint a = 0; a < 2; ++a) {
        glEnableVertexArrayAttrib(vao.id(), a);
        glVertexArrayAttribFormat(vao.id(), a, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vao.id(), a, a);
    }
    glVertexArrayElementBuffer(vao.id(), indices.id());

    // Voxel representations as the GLSL lookups read them (shaders/voxel/*.glsl).
    for (const voxel::Model& model : models) {
        if (const voxel::BitGrid* bits = model.solid()) bitGrids.emplace_back(*bits);
        else slicemaps.emplace_back(*model.slicemap());
    }
    checkGl("uploading the scene");
}

void SceneRenderer::Impl::buildPrograms() {
    registerShaders(kSceneShaders, kSceneShadersCount);
    std::string defines = "#define VDS_STYLE_SPRITES " + std::to_string(scene.solids.size()) + "\n";
    if (scene.distanceWidth > 0.0f) defines += "#define SCENE_DISTANCE\n";
    shading = buildProgram({{GL_VERTEX_SHADER, "samples/scene.vert", ""}, {GL_FRAGMENT_SHADER, "samples/scene.frag", ""}},
                           defines + "#define " + lookupDefine(lookup) + "\n");
    if (lookup == Lookup::Exact)
        peel = buildProgram({{GL_VERTEX_SHADER, "samples/scene.vert", ""}, {GL_FRAGMENT_SHADER, "samples/scene.frag", ""}},
                            defines + "#define SCENE_PEEL\n");
}

void SceneRenderer::replaceSprite(std::size_t index, const Sprite& sprite) {
    Impl& d = *impl_;
    if (index >= d.scene.solids.size()) throw InvalidArgument("no solid " + std::to_string(index));
    if (d.lookup != Lookup::Vds) throw InvalidArgument("replaceSprite: the scene's inside test is not the VDS");
    if (d.scene.distanceWidth > 0.0f && sprite.distance.empty())
        throw InvalidArgument("replaceSprite: the scene draws distances and the sprite carries no distance grid");
    d.sprites[index] = GpuSprite(sprite, GpuSpriteParts::TextureOnly);
    d.baked[index] = sprite;
    d.baked[index].distance = {}; // on the GPU; place() copies the rest
    place(index, d.scene.solids[index].placement);
}

void SceneRenderer::place(std::size_t index, const glm::mat4& placement) {
    Impl& d = *impl_;
    if (index >= d.scene.solids.size()) throw InvalidArgument("no solid " + std::to_string(index));
    d.scene.solids[index].placement = placement;
    d.peelStale = true;
    if (d.lookup == Lookup::Vds) {
        Sprite moved = d.baked[index]; // the placement of the bake, then the solid's: Sprite::transform
        moved.transform(placement);
        d.sprites[index].setPlacement(moved.grid);
    }
}

void SceneRenderer::Impl::setUniforms(GLuint p) {
    glUseProgram(p);
    glUniformMatrix4fv(location(p, "u_viewProjection"), 1, GL_FALSE, glm::value_ptr(view.viewProjection));
    glUniform3f(location(p, "u_lightDirection"), 0.40f, 0.58f, 0.71f);
    glUniform3fv(location(p, "u_viewDirection"), 1, glm::value_ptr(view.towardsViewer));
    glUniform3f(location(p, "u_frontColour"), 0.85f, 0.82f, 0.74f);
    glUniform3f(location(p, "u_cutColour"), 0.85f, 0.15f, 0.12f);
    glUniform1f(location(p, "u_gridSpacing"), 0.08f);
    glUniform1i(location(p, "u_baseStyle"), int(scene.baseStyle));
    const bool clips = std::any_of(scene.solids.begin(), scene.solids.end(), [](const SceneSolid& solid) {
        return solid.role == Role::ClipAway || solid.role == Role::ClipTo;
    });
    glUniform1i(location(p, "u_cutBackFaces"), clips ? 1 : 0);
    glUniform1i(location(p, "u_vdsSpriteCount"), GLint(scene.solids.size()));
    glUniform1i(location(p, "u_vdsCombineAway"), int(scene.combineAway));
    glUniform1i(location(p, "u_vdsCombineTo"), int(scene.combineTo));
    GLuint unit = 0;
    for (std::size_t i = 0; i < scene.solids.size(); ++i) {
        const std::string k = "[" + std::to_string(i) + "]";
        const SceneSolid& solid = scene.solids[i];
        glUniform1i(location(p, "u_vdsBinding" + k + ".role"), int(solid.role));
        glUniform1i(location(p, "u_vdsBinding" + k + ".style"), int(solid.style));
        glUniform1i(location(p, "u_vdsBinding" + k + ".rule"), scene.rule == Rule::Winding ? 1 : 0);
        const glm::mat4 toMesh = glm::inverse(solid.placement);
        glUniformMatrix4fv(location(p, "u_toMesh" + k), 1, GL_FALSE, glm::value_ptr(toMesh));
        switch (lookup) {
        case Lookup::Vds:
            sprites[i].setUniforms(p, "u_vdsLdi" + k, "u_vdsPlacement" + k, unit++);
            if (scene.distanceWidth > 0.0f) setDistanceUniforms(p, i, unit++);
            break;
        case Lookup::Solid: bitGrids[i].setUniforms(p, "u_voxels" + k, "u_voxelGrid" + k, unit++); break;
        case Lookup::Slicemap:
        case Lookup::SlicemapLocal:
            unit = slicemaps[i].setUniforms(p, "u_slicemap" + k, "u_ranges" + k, "u_map" + k, unit);
            break;
        case Lookup::Exact: break;
        }
    }
    if (lookup == Lookup::Exact) {
        glBindTextureUnit(unit, layerDepth.id());
        glUniform1i(location(p, "u_layerDepth"), GLint(unit++));
        glBindTextureUnit(unit, layerMask.id());
        glUniform1i(location(p, "u_layerMask"), GLint(unit++));
        glUniform1i(location(p, "u_layerCount"), layerCount);
    }
}

// Solid i's distance grid on `unit`, read at the inverse of its placement,
// scaled back to world units (exact for a uniform scale).
void SceneRenderer::Impl::setDistanceUniforms(GLuint p, std::size_t i, GLuint unit) {
    const std::string k = "[" + std::to_string(i) + "]";
    const glm::mat4& placement = scene.solids[i].placement;
    sprites[i].distanceGrid().setUniforms(p, "u_distance" + k, "u_distanceLo" + k, "u_distanceHi" + k, unit);
    const glm::mat4 toMesh = glm::inverse(placement);
    glUniformMatrix4fv(location(p, "u_distanceToMesh" + k), 1, GL_FALSE, glm::value_ptr(toMesh));
    glUniform1f(location(p, "u_distanceScale" + k), std::cbrt(std::abs(glm::determinant(glm::mat3(placement)))));
    glUniform1f(location(p, "u_distanceWidth"), scene.distanceWidth);
    glUniform3fv(location(p, "u_bandColour"), 1, glm::value_ptr(scene.bandColour));
}

// Peels every depth layer of the model (world position and depth per
// pixel), classifies each position against each solid exactly, and keeps
// the layers' depths and masks as 2D array textures.
void SceneRenderer::Impl::peelAndClassify(std::uint32_t width, std::uint32_t height) {
    const GLsizei s = GLsizei(width), sh = GLsizei(height);
    Texture position = Texture::create(GL_TEXTURE_2D), depthColour = Texture::create(GL_TEXTURE_2D),
            depth = Texture::create(GL_TEXTURE_2D), previous = Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(position.id(), 1, GL_RGBA32F, s, sh);
    glTextureStorage2D(depthColour.id(), 1, GL_R32F, s, sh);
    glTextureStorage2D(previous.id(), 1, GL_R32F, s, sh);
    glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, s, sh);
    nearest(previous);
    Framebuffer fbo = Framebuffer::create();
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, position.id(), 0);
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT1, depthColour.id(), 0);
    glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo.id(), 2, buffers);
    if (glCheckNamedFramebufferStatus(fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw GlError("peeling framebuffer is incomplete");

    const std::size_t pixels = std::size_t(width) * height;
    std::vector<float> depths, layerPositions(pixels * 4);
    std::vector<std::uint32_t> masks;
    Query samples = Query::create(GL_SAMPLES_PASSED);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, s, sh);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
    setUniforms(peel.id());
    glBindTextureUnit(15, previous.id());
    glUniform1i(location(peel.id(), "u_previousDepth"), 15);
    glBindVertexArray(vao.id());
    layerCount = 0;
    for (int layer = 0; layer < kMaxLayers; ++layer) {
        const float zero[4] = {0, 0, 0, 0}, one = 1.0f, none[4] = {2, 0, 0, 0};
        glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, zero);
        glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 1, none);
        glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &one);
        glUniform1i(location(peel.id(), "u_layer"), layer);
        glBeginQuery(GL_SAMPLES_PASSED, samples.id());
        glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
        glEndQuery(GL_SAMPLES_PASSED);
        GLuint passed = 0;
        glGetQueryObjectuiv(samples.id(), GL_QUERY_RESULT, &passed);
        if (passed == 0) break;
        glCopyImageSubData(depthColour.id(), GL_TEXTURE_2D, 0, 0, 0, 0, previous.id(), GL_TEXTURE_2D, 0, 0, 0, 0, s, sh, 1);
        depths.resize(depths.size() + pixels);
        glGetTextureImage(depthColour.id(), 0, GL_RED, GL_FLOAT, GLsizei(pixels * 4), &depths[depths.size() - pixels]);
        glGetTextureImage(position.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(pixels * 16), layerPositions.data());
        // Classify this layer's points against each solid, in its mesh coordinates.
        std::vector<std::size_t> covered;
        for (std::size_t q = 0; q < pixels; ++q)
            if (layerPositions[4 * q + 3] == 1.0f) covered.push_back(q);
        masks.resize(masks.size() + pixels, 0u);
        std::uint32_t* mask = &masks[masks.size() - pixels];
        std::vector<glm::vec3> points(covered.size());
        std::vector<std::uint8_t> labels(covered.size());
        for (std::size_t i = 0; i < exact.size(); ++i) {
            const glm::mat4 toMesh = glm::inverse(scene.solids[i].placement);
            for (std::size_t k = 0; k < covered.size(); ++k) {
                const float* w = &layerPositions[4 * covered[k]];
                points[k] = glm::vec3(toMesh * glm::vec4(w[0], w[1], w[2], 1.0f));
            }
            ClassifyOptions options;
            options.rule = scene.rule;
            exact[i].classify({points.data(), points.size()}, labels.data(), options);
            for (std::size_t k = 0; k < covered.size(); ++k)
                if (labels[k]) mask[covered[k]] |= 1u << i;
        }
        ++layerCount;
    }
    peeledWidth = width;
    peeledHeight = height;
    peelStale = false;
    if (layerCount == kMaxLayers) throw InvalidArgument("the model has more than 32 depth layers");
    const GLsizei layers = std::max(layerCount, 1);
    depths.resize(std::size_t(layers) * pixels, 2.0f);
    masks.resize(std::size_t(layers) * pixels, 0u);
    layerDepth = Texture::create(GL_TEXTURE_2D_ARRAY);
    layerMask = Texture::create(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(layerDepth.id(), 1, GL_R32F, s, sh, layers);
    glTextureStorage3D(layerMask.id(), 1, GL_R32UI, s, sh, layers);
    nearest(layerDepth);
    nearest(layerMask);
    glTextureSubImage3D(layerDepth.id(), 0, 0, 0, 0, s, sh, layers, GL_RED, GL_FLOAT, depths.data());
    glTextureSubImage3D(layerMask.id(), 0, 0, 0, 0, s, sh, layers, GL_RED_INTEGER, GL_UNSIGNED_INT, masks.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    checkGl("peeling the exact reference");
}

// The camera for this picture size, the exact lookup's layers (peeled again
// when the size changed or a solid moved, or always), and the uniforms.
void SceneRenderer::Impl::prepare(std::uint32_t width, std::uint32_t height, bool alwaysPeel) {
    view = camera(bounds, scene, width, height);
    if (lookup == Lookup::Exact && (alwaysPeel || peelStale || peeledWidth != width || peeledHeight != height))
        peelAndClassify(width, height);
    setUniforms(shading.id());
}

void SceneRenderer::Impl::draw(GLuint framebuffer, std::uint32_t width, std::uint32_t height) {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, GLsizei(width), GLsizei(height));
    const float white[4] = {1, 1, 1, 1}, far = 1.0f;
    glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, white);
    glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &far);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glBindVertexArray(vao.id());
    // Opaque styles, then X-ray multiplied into them (order independent).
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glUniform1i(location(shading.id(), "u_pass"), 0);
    glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_DST_COLOR, GL_ZERO);
    glUniform1i(location(shading.id(), "u_pass"), 1);
    glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
}

eval::Image SceneRenderer::render(std::uint32_t size) { return render(size, size); }

eval::Image SceneRenderer::render(std::uint32_t width, std::uint32_t height) {
    Impl& d = *impl_;
    d.gl->makeCurrent();
    d.prepare(width, height, true);
    const Target target = makeTarget(width, height);
    d.draw(target.fbo.id(), width, height);
    checkGl("rendering the scene");

    eval::Image image(width, height);
    std::vector<std::uint8_t> pixels(image.rgba.size());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(target.colour.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
    const std::size_t row = std::size_t(width) * 4;
    for (std::uint32_t y = 0; y < height; ++y) // GL rows run bottom to top, PNG rows top to bottom
        std::memcpy(image.at(0, y), &pixels[(height - 1 - y) * row], row);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    return image;
}

double SceneRenderer::frameMilliseconds(std::uint32_t size, int repeats) {
    Impl& d = *impl_;
    d.gl->makeCurrent();
    d.prepare(size, size, false);
    const Target target = makeTarget(size, size);
    d.draw(target.fbo.id(), size, size); // warm up: first use compiles state on some drivers
    Query timer = Query::create(GL_TIME_ELAPSED);
    std::vector<double> ms;
    for (int r = 0; r < std::max(repeats, 1); ++r) {
        glBeginQuery(GL_TIME_ELAPSED, timer.id());
        d.draw(target.fbo.id(), size, size);
        glEndQuery(GL_TIME_ELAPSED);
        GLuint64 ns = 0;
        glGetQueryObjectui64v(timer.id(), GL_QUERY_RESULT, &ns);
        ms.push_back(double(ns) * 1e-6);
    }
    std::sort(ms.begin(), ms.end());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    checkGl("timing the scene");
    return ms[ms.size() / 2];
}

void SceneRenderer::drawTo(unsigned framebuffer, std::uint32_t width, std::uint32_t height) {
    Impl& d = *impl_;
    d.gl->requireCurrent("SceneRenderer::drawTo");
    d.prepare(width, height, false);
    // Drawn offscreen with a 32-bit float depth, then copied: the exact
    // lookup matches fragments to peeled layers by depth, which a window's
    // 24-bit depth buffer would round (llvmpipe rounds gl_FragCoord.z to it).
    if (!d.window || d.window->width != width || d.window->height != height) d.window = makeTarget(width, height);
    d.draw(d.window->fbo.id(), width, height);
    glBlitNamedFramebuffer(d.window->fbo.id(), framebuffer, 0, 0, GLint(width), GLint(height), 0, 0, GLint(width),
                           GLint(height), GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glUseProgram(0);
    checkGl("drawing the scene");
}

glm::mat4 SceneRenderer::viewProjection(std::uint32_t width, std::uint32_t height) const {
    return camera(impl_->bounds, impl_->scene, width, height).viewProjection;
}

void SceneRenderer::setRole(std::size_t index, Role role, Style style) {
    if (index >= impl_->scene.solids.size()) throw InvalidArgument("no solid " + std::to_string(index));
    impl_->scene.solids[index].role = role;
    impl_->scene.solids[index].style = style;
}

void SceneRenderer::setStyles(Style baseStyle, Combine combineAway, Combine combineTo) {
    impl_->scene.baseStyle = baseStyle;
    impl_->scene.combineAway = combineAway;
    impl_->scene.combineTo = combineTo;
}

const Scene& SceneRenderer::scene() const { return impl_->scene; }

std::size_t SceneRenderer::memoryBytes() const { return impl_->bytes; }

std::vector<std::string> SceneRenderer::describe() const {
    const Impl& d = *impl_;
    std::vector<std::string> lines;
    for (std::size_t i = 0; i < d.scene.solids.size(); ++i) {
        std::string line = d.scene.solids[i].name + ": ";
        if (d.lookup == Lookup::Vds) {
            const glm::uvec3 s = d.sprites[i].size();
            line += "vds " + std::to_string(s.x) + "x" + std::to_string(s.y) + "x" + std::to_string(s.z) +
                    " texels, " + mib(d.baked[i].denseBytes());
        } else if (d.lookup == Lookup::Exact) {
            line += "exact classifier, " + std::to_string(d.scene.solids[i].mesh.triangles.size()) + " triangles";
        } else {
            line += d.models[i].summary() + " (resolution " + std::to_string(d.resolutions[i]) + "), GPU " +
                    mib(d.models[i].gpuBytes());
        }
        lines.push_back(line);
    }
    return lines;
}

ImageDifference compareImages(const eval::Image& image, const eval::Image& reference, int threshold) {
    if (image.width != reference.width || image.height != reference.height)
        throw InvalidArgument("pictures of different sizes cannot be compared");
    ImageDifference d;
    d.picture = eval::Image(image.width, image.height);
    double sum = 0.0;
    for (std::uint32_t y = 0; y < image.height; ++y)
        for (std::uint32_t x = 0; x < image.width; ++x) {
            const std::uint8_t* a = image.at(x, y);
            const std::uint8_t* b = reference.at(x, y);
            int pixelMax = 0;
            bool background = true;
            for (int c = 0; c < 3; ++c) {
                const int delta = std::abs(int(a[c]) - int(b[c]));
                pixelMax = std::max(pixelMax, delta);
                sum += delta;
                background = background && a[c] == 255 && b[c] == 255;
            }
            d.max = std::max(d.max, pixelMax);
            d.covered += !background;
            const bool differs = pixelMax > threshold;
            d.pixels += differs;
            std::uint8_t* out = d.picture.at(x, y);
            const std::uint8_t grey = std::uint8_t(215 + (int(b[0]) + b[1] + b[2]) / 3 * 40 / 255);
            out[0] = differs ? 220 : grey;
            out[1] = differs ? 20 : grey;
            out[2] = differs ? 30 : grey;
            out[3] = 255;
        }
    d.mean = image.rgba.empty() ? 0.0 : sum / (3.0 * double(image.width) * image.height);
    return d;
}

} // namespace vds::samples
