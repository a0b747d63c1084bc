// One entry point over the voxel representations: build, point queries on
// the CPU and, with the GLSL lookups, on the GPU.
#include <vds/voxel/representation.h>

#include <algorithm>
#include <optional>
#include <thread>
#include <vector>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/detail/parallel.h>
#include <vds/gl/shader.h>
#include <vds/voxel/solid.h>

#include "gl_util.h"
#include "slicemap_texture.h"

namespace vds::voxel {

Representation parseRepresentation(const std::string& name) { return parseEnum<Representation>(name); }
const char* toString(Representation r) { return enumName(r); }

Model::Model(Representation representation, Slicemap slicemap, double buildSeconds)
    : representation_(representation), data_(std::move(slicemap)), buildSeconds_(buildSeconds) {}

Model::Model(Representation representation, BitGrid solid, double buildSeconds)
    : representation_(representation), data_(std::move(solid)), buildSeconds_(buildSeconds) {}

bool Model::contains(const glm::vec3& p) const {
    if (const Slicemap* map = slicemap()) return map->contains(p);
    return std::get<BitGrid>(data_).contains(p);
}

void Model::classify(const glm::vec3* points, std::size_t count, std::uint8_t* labels, unsigned threads) const {
    parallelFor(threads, count, std::size_t(1) << 16, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) labels[k] = contains(points[k]) ? 1 : 0;
    });
}

std::size_t Model::memoryBytes() const {
    if (const Slicemap* map = slicemap()) return map->memoryBytes();
    return std::get<BitGrid>(data_).memoryBytes();
}

std::size_t Model::gpuBytes() const {
    if (const Slicemap* map = slicemap()) return map->gpuBytes();
    return std::get<BitGrid>(data_).memoryBytes();
}

glm::uvec3 Model::cells() const {
    if (const Slicemap* map = slicemap()) return map->grid.size;
    return std::get<BitGrid>(data_).grid.size;
}

float Model::cellSize() const {
    if (const Slicemap* map = slicemap()) return map->grid.cellSize;
    return std::get<BitGrid>(data_).grid.cellSize;
}

std::string Model::summary() const {
    const glm::uvec3 c = cells();
    return std::string(toString(representation_)) + ": " + std::to_string(c.x) + "x" + std::to_string(c.y) + "x" +
           std::to_string(c.z) + (slicemap() ? " slices" : " voxels") + ", " + std::to_string(memoryBytes()) + " bytes";
}

Model buildModel(MeshView mesh, Representation representation, const ModelOptions& options, GlContext* gl) {
    requireClosed(mesh, "mesh");
    const Box box = meshBounds(mesh);
    const bool isSlicemap =
        representation == Representation::Slicemap || representation == Representation::SlicemapLocal;
    // Grid checks before any GL work, so bad arguments fail fast.
    const VoxelGrid grid = makeVoxelGrid(box, options.resolution, isSlicemap ? ~std::uint64_t(0) : kMaxCells);
    const CurrentContext restore; // the caller's context is current again on return
    std::optional<GlContext> own;
    if (!gl) {
        gl = &own.emplace();
    }
    gl->makeCurrent();
    const std::uint64_t start = detail::nowNanoseconds();
    switch (representation) {
    case Representation::Slicemap:
    case Representation::SlicemapLocal: {
        SlicemapOptions o;
        o.slicing = representation == Representation::Slicemap ? Slicing::Uniform : Slicing::Local;
        o.slices = options.slices;
        Slicemap map = buildSlicemap(*gl, mesh, box, options.resolution, o);
        return Model(representation, std::move(map), detail::secondsSince(start));
    }
    case Representation::Solid:
    case Representation::SolidCompute: {
        BitGrid bits = voxelizeSolid(
            *gl, mesh, grid, representation == Representation::Solid ? SolidMethod::Raster : SolidMethod::Compute);
        return Model(representation, std::move(bits), detail::secondsSince(start));
    }
    }
    throw InvalidArgument("unknown voxel representation");
}

void classifyOnGpu(const GlContext& gl, const Model& model, const glm::vec3* points, std::size_t count,
                   std::uint8_t* labels) {
    gl.makeCurrent();
    const Slicemap* map = model.slicemap();
    const char* define = !map                               ? "VDS_CLASSIFY_SOLID"
                         : map->slicing == Slicing::Uniform ? "VDS_CLASSIFY_SLICEMAP"
                                                            : "VDS_CLASSIFY_SLICEMAP_LOCAL";
    const Program& program = gl.program(std::string("voxel.classify.") + define, [&] {
        return detail::buildVoxelProgram({{GL_COMPUTE_SHADER, "voxel/classify.comp", ""}}, std::string("#define ") + define + "\n");
    });
    const GLuint id = program.id();
    Buffer words;
    Texture wordTexture;
    detail::SlicemapTextures slicemapTextures;
    if (!map) {
        const BitGrid& bits = *model.solid();
        GLint maxTexels = 0;
        glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
        if (bits.words.size() > std::size_t(maxTexels))
            throw OutOfMemory("the voxel grid exceeds GL's texture buffer size; lower the resolution");
        words = Buffer::create();
        glNamedBufferStorage(words.id(), GLsizeiptr(bits.memoryBytes()), bits.words.data(), 0);
        wordTexture = Texture::create(GL_TEXTURE_BUFFER);
        glTextureBuffer(wordTexture.id(), GL_R32UI, words.id());
        glBindTextureUnit(0, wordTexture.id());
        glProgramUniform1i(id, glGetUniformLocation(id, "u_voxels"), 0);
        detail::setGridUniform(id, "u_voxelGrid", bits.grid);
    } else {
        slicemapTextures = detail::uploadSlicemap(*map);
        glBindTextureUnit(0, slicemapTextures.maps.id());
        glProgramUniform1i(id, glGetUniformLocation(id, "u_slicemap"), 0);
        if (map->slicing == Slicing::Local) {
            glBindTextureUnit(1, slicemapTextures.ranges.id());
            glProgramUniform1i(id, glGetUniformLocation(id, "u_ranges"), 1);
        }
        detail::setGridUniform(id, "u_map.grid", map->grid);
        glProgramUniform1i(id, glGetUniformLocation(id, "u_map.backLayer"), GLint(map->renderTargets));
    }
    checkGl("binding a voxel representation");

    const std::size_t batch = std::size_t(1) << 22;
    Buffer pointBuffer = Buffer::create(), labelBuffer = Buffer::create();
    const std::size_t capacity = std::max<std::size_t>(1, std::min(count, batch));
    glNamedBufferStorage(pointBuffer.id(), GLsizeiptr(capacity * sizeof(glm::vec3)), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(labelBuffer.id(), GLsizeiptr(capacity * sizeof(GLuint)), nullptr, 0);
    std::vector<GLuint> out(capacity);
    glUseProgram(id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, pointBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, labelBuffer.id());
    for (std::size_t begin = 0; begin < count; begin += batch) {
        const std::size_t n = std::min(batch, count - begin);
        glNamedBufferSubData(pointBuffer.id(), 0, GLsizeiptr(n * sizeof(glm::vec3)), points + begin);
        glProgramUniform1ui(id, glGetUniformLocation(id, "u_count"), GLuint(n));
        detail::dispatchLinear(n, 256);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glGetNamedBufferSubData(labelBuffer.id(), 0, GLsizeiptr(n * sizeof(GLuint)), out.data());
        for (std::size_t k = 0; k < n; ++k) labels[begin + k] = std::uint8_t(out[k]);
    }
    glUseProgram(0);
    glBindTextureUnit(0, 0);
    glBindTextureUnit(1, 0);
    checkGl("classifying on the GPU");
}

} // namespace vds::voxel
