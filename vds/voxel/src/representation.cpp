// One entry point over the voxel representations: build, point queries on
// the CPU and, with the GLSL lookups, on the GPU.
#include <vds/voxel/representation.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <thread>
#include <vector>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/detail/parallel.h>
#include <vds/gl/shader.h>
#include <vds/voxel/gpu_grid.h>
#include <vds/voxel/solid.h>

#include <vds/gl/detail/dispatch.h>

#include "detail/slicemap.h"
#include "detail/solid.h"

#include "plane_targets.h"

namespace vds::voxel {

Representation parseRepresentation(const std::string& name) { return parseEnum<Representation>(name); }
const char* toString(Representation r) { return enumName(r); }

Model::Model(Representation representation, Slicemap slicemap, double buildSeconds)
    : representation_(representation), data_(std::move(slicemap)), buildSeconds_(buildSeconds) {}

Model::Model(Representation representation, BitGrid solid, double buildSeconds)
    : representation_(representation), data_(std::move(solid)), buildSeconds_(buildSeconds) {}

bool Model::inside(const glm::vec3& p) const {
    if (const Slicemap* map = slicemap()) return map->contains(p);
    return std::get<BitGrid>(data_).contains(p);
}

Method methodOf(Representation representation) {
    switch (representation) {
    case Representation::Slicemap: return Method::Slicemap;
    case Representation::SlicemapLocal: return Method::SlicemapLocal;
    case Representation::Solid: return Method::Solid;
    case Representation::SolidCompute: return Method::SolidCompute;
    }
    throw InvalidArgument("unknown voxel representation");
}

Representation representationOf(Method method) {
    for (const auto& entry : EnumNames<Representation>::table)
        if (methodOf(entry.value) == cpuForm(method)) return entry.value;
    throw InvalidArgument(std::string("method '") + enumName(method) + "' is not a voxel representation");
}

void Model::classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                           const ClassifyOptions& options) const {
    const char* base = reinterpret_cast<const char*>(xyz);
    vds::detail::parallelFor(options.threads, count, std::size_t(1) << 16, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            glm::vec3 p;
            std::memcpy(&p, base + k * strideBytes, sizeof p);
            labels[k] = inside(p) ? 1 : 0;
        }
    });
}

std::size_t modelMemoryBytes(const Box& box, Representation representation, const ModelOptions& options) {
    const VoxelGrid grid = makeVoxelGrid(box, options.resolution);
    if (representation == Representation::Solid || representation == Representation::SolidCompute)
        return grid.wordCount() * sizeof(std::uint32_t); // BitGrid::memoryBytes
    // Slicemap::memoryBytes: front and back, a bit a slice; local slicing adds 3 floats a column.
    const std::size_t columns = std::size_t(grid.dims.x) * grid.dims.y;
    const std::size_t slices = options.slices ? options.slices : defaultSlices(box, options.resolution);
    return columns * 2 * (slices / 32) * sizeof(std::uint32_t) +
           (representation == Representation::SlicemapLocal ? columns * 3 * sizeof(float) : 0);
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
    if (const Slicemap* map = slicemap()) return map->grid.dims;
    return std::get<BitGrid>(data_).grid.dims;
}

float Model::cellSize() const {
    if (const Slicemap* map = slicemap()) return map->grid.cellSize();
    return std::get<BitGrid>(data_).grid.cellSize();
}

std::string Model::summary() const {
    const glm::uvec3 c = cells();
    return std::string(toString(representation_)) + ": " + std::to_string(c.x) + "x" + std::to_string(c.y) + "x" +
           std::to_string(c.z) + (slicemap() ? " slices" : " voxels") + ", " + std::to_string(memoryBytes()) + " bytes";
}

Model buildModel(const GlContext& gl, MeshView mesh, Representation representation, const ModelOptions& options) {
    requireClosed(mesh, "mesh"); // once: the builders below take the mesh as checked
    const Box box = meshBounds(mesh);
    const bool isSlicemap =
        representation == Representation::Slicemap || representation == Representation::SlicemapLocal;
    // Grid checks before any GL work, so bad arguments fail fast.
    const VoxelGrid grid = makeVoxelGrid(box, options.resolution);
    if (!isSlicemap) checkGrid(grid); // a slicemap keeps only the columns
    const CurrentContext current(gl); // the caller's context is current again on return
    const std::uint64_t start = detail::nowNanoseconds();
    switch (representation) {
    case Representation::Slicemap:
    case Representation::SlicemapLocal: {
        SlicemapOptions o;
        o.slicing = representation == Representation::Slicemap ? Slicing::Uniform : Slicing::Local;
        o.slices = options.slices;
        Slicemap map = detail::sliceClosed(gl, mesh, box, grid, o);
        return Model(representation, std::move(map), detail::secondsSince(start));
    }
    case Representation::Solid:
    case Representation::SolidCompute: {
        BitGrid bits = detail::voxelizeClosed(
            gl, mesh, grid, representation == Representation::Solid ? SolidMethod::Raster : SolidMethod::Compute);
        return Model(representation, std::move(bits), detail::secondsSince(start));
    }
    }
    throw InvalidArgument("unknown voxel representation");
}

// The model's GL objects and the lookup program, made once per classifier.
struct GpuModelClassifier::Resources {
    GLuint program = 0; // from the context's cache
    GpuBitGrid bits;       // Solid methods
    GpuSlicemap slicemap;  // Slicemap methods
};

GpuModelClassifier::GpuModelClassifier(const GlContext& gl, Model model)
    : gl_(gl), model_(std::move(model)), gpu_(std::make_unique<Resources>()) {
    const CurrentContext current(gl_);
    const Slicemap* map = model_.slicemap();
    const char* define = !map                               ? "VDS_CLASSIFY_SOLID"
                         : map->slicing == Slicing::Uniform ? "VDS_CLASSIFY_SLICEMAP"
                                                            : "VDS_CLASSIFY_SLICEMAP_LOCAL";
    gpu_->program = gl.program(std::string("voxel.classify.") + define, [&] {
        return buildProgram({{GL_COMPUTE_SHADER, "voxel/classify.comp", ""}}, std::string("#define ") + define + "\n");
    }).id();
    if (map) gpu_->slicemap = GpuSlicemap(*map);
    else gpu_->bits = GpuBitGrid(*model_.solid());
    checkGl("uploading a voxel representation");
}

GpuModelClassifier::~GpuModelClassifier() {
    const CurrentContext current(gl_);
    gpu_.reset();
}

Method GpuModelClassifier::method() const { return gpuForm(model_.method()); }

std::string GpuModelClassifier::summary() const { return model_.summary() + ", looked up on " + gl_.info().renderer; }

void GpuModelClassifier::classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes,
                                        std::uint8_t* labels, const ClassifyOptions&) const {
    const CurrentContext current(gl_);
    const Slicemap* map = model_.slicemap();
    const GLuint id = gpu_->program;
    if (map) gpu_->slicemap.setUniforms(id, "u_slicemap", "u_ranges", "u_map", 0);
    else gpu_->bits.setUniforms(id, "u_voxels", "u_voxelGrid", 0);
    checkGl("binding a voxel representation");
    const std::size_t batch = std::size_t(1) << 22;
    Buffer pointBuffer = Buffer::create(), labelBuffer = Buffer::create();
    const std::size_t capacity = std::max<std::size_t>(1, std::min(count, batch));
    glNamedBufferStorage(pointBuffer.id(), GLsizeiptr(capacity * sizeof(glm::vec3)), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(labelBuffer.id(), GLsizeiptr(capacity * sizeof(GLuint)), nullptr, 0);
    std::vector<GLuint> out(capacity);
    std::vector<glm::vec3> packed(strideBytes == sizeof(glm::vec3) ? 0 : capacity);
    const char* base = reinterpret_cast<const char*>(xyz);
    glUseProgram(id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, pointBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, labelBuffer.id());
    for (std::size_t begin = 0; begin < count; begin += batch) {
        const std::size_t n = std::min(batch, count - begin);
        const void* points = base + begin * strideBytes;
        if (!packed.empty()) {
            for (std::size_t k = 0; k < n; ++k) std::memcpy(&packed[k], base + (begin + k) * strideBytes, sizeof(glm::vec3));
            points = packed.data();
        }
        glNamedBufferSubData(pointBuffer.id(), 0, GLsizeiptr(n * sizeof(glm::vec3)), points);
        glProgramUniform1ui(id, glGetUniformLocation(id, "u_count"), GLuint(n));
        vds::detail::dispatchItems(n, 256);
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
