#include <vds/gl/sprite.h>
#include <vds/gl/distance.h>

#include <vds/gl/detail/sprite.h>

#include <algorithm>
#include <cassert>
#include <cstring>
#include <utility>
#include <vector>

#include <GL/glext.h>
#include <glm/vec4.hpp>

#include <vds/error.h>
#include <vds/gl/shader.h>

#include <vds/gl/detail/buffers.h>
#include <vds/gl/detail/context.h>
#include <vds/gl/detail/dispatch.h>
#include <vds/gl/detail/pack_boundary.h>

#include <vds/detail/parallel.h>

namespace vds {

namespace detail {

Texture makeSpriteTexture(glm::uvec3 size) {
    GLint max3d = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
    if (max3d <= 0) throw GlError("GpuSprite: no GL context current (GL reports no 3D texture size)");
    if (size.x > std::uint32_t(max3d) || size.y > std::uint32_t(max3d) || size.z > std::uint32_t(max3d))
        throw InvalidArgument("sprite " + std::to_string(size.x) + "x" + std::to_string(size.y) + "x" +
                              std::to_string(size.z) + " exceeds this GL's 3D texture limit " + std::to_string(max3d) +
                              "; bake at a lower resolution");
    Texture t = Texture::create(GL_TEXTURE_3D);
    glTextureStorage3D(t.id(), 1, GL_R32F, GLsizei(size.x), GLsizei(size.y), GLsizei(size.z));
    checkGl("allocating the sprite texture");
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(t.id(), wrap, GL_CLAMP_TO_BORDER);
    const float border[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    glTextureParameterfv(t.id(), GL_TEXTURE_BORDER_COLOR, border);
    checkGl("setting up the sprite texture");
    return t;
}

} // namespace detail

GpuSprite GpuSprite::adopt(Texture texture, Buffer offsets, Buffer crossings, std::uint64_t crossingCount,
                           glm::uvec3 size, const SpriteGrid& grid, SolidStatus status,
                           const std::vector<glm::vec3>& boundaryEdges) {
    GpuSprite s;
    s.context_ = ContextStamp::current("GpuSprite");
    s.boundary_ = GpuBoundary(grid, boundaryEdges, true);
    s.status_ = status;
    s.texture_ = std::move(texture);
    s.offsets_ = std::move(offsets);
    s.crossings_ = std::move(crossings);
    s.crossingCount_ = crossingCount;
    s.size_ = size;
    s.setPlacement(grid);
    return s;
}

GpuSprite::GpuSprite(const GlContext& gl, const Sprite& sprite, GpuSpriteParts parts) {
    const CurrentContext current(gl);
    upload(sprite, parts);
}

GpuSprite::GpuSprite(const Sprite& sprite, GpuSpriteParts parts) { upload(sprite, parts); }

GpuSprite::~GpuSprite() { releaseIfForeign(); }

GpuSprite& GpuSprite::operator=(GpuSprite&& o) noexcept {
    if (this != &o) {
        releaseIfForeign();
        context_ = o.context_;
        texture_ = std::move(o.texture_);
        offsets_ = std::move(o.offsets_);
        crossings_ = std::move(o.crossings_);
        crossingCount_ = o.crossingCount_;
        size_ = o.size_;
        matrix_ = o.matrix_;
        position_ = o.position_;
        status_ = o.status_;
        boundary_ = std::move(o.boundary_);
        distance_ = std::move(o.distance_);
    }
    return *this;
}

// Deleting the names under another context would delete that context's
// objects: leave them to the sprite's own context instead.
void GpuSprite::releaseIfForeign() noexcept {
    if (!context_ || !detail::glUsable() || context_.isCurrent()) return; // at exit the wrappers skip GL anyway
    texture_.release();
    offsets_.release();
    crossings_.release();
    boundary_.buffer_.release();
    distance_.texture_.release();
}

void GpuSprite::requireContext(const char* what) const { context_.check(what); }

void GpuSprite::upload(const Sprite& sprite, GpuSpriteParts parts) {
    context_ = ContextStamp::current("GpuSprite upload");
    const std::uint32_t w = sprite.width(), h = sprite.height(), d = std::max<std::uint32_t>(1, sprite.depthComplexity);
    size_ = {w, h, d};
    crossingCount_ = sprite.crossings.size();
    status_ = sprite.status;
    if (parts != GpuSpriteParts::ColumnsOnly) {
        texture_ = detail::makeSpriteTexture(size_);
        std::vector<float> dense;
        try {
            dense.assign(std::size_t(w) * h * d, 1.0f);
        } catch (const std::bad_alloc&) {
            throw OutOfMemory("not enough memory for a " + std::to_string(w) + "x" + std::to_string(h) + "x" +
                              std::to_string(d) + " texture");
        }
        const std::size_t layer = std::size_t(w) * h;
        for (std::size_t c = 0; c < layer; ++c)
            for (std::uint32_t k = sprite.offsets[c]; k < sprite.offsets[c + 1]; ++k)
                dense[(k - sprite.offsets[c]) * layer + c] = sprite.crossings[k];
        glTextureSubImage3D(texture_.id(), 0, 0, 0, 0, GLsizei(w), GLsizei(h), GLsizei(d), GL_RED, GL_FLOAT,
                            dense.data());
        checkGl("uploading the sprite texture");
    }
    if (!sprite.distance.empty()) distance_ = GpuDistanceGrid(sprite.distance);
    if (parts != GpuSpriteParts::TextureOnly) {
        offsets_ = detail::uploadBuffer(sprite.offsets.data(), sprite.offsets.size() * 4, "uploading the sprite's columns");
        crossings_ = detail::uploadBuffer(sprite.crossings.data(), sprite.crossings.size() * 4, "uploading the sprite's columns");
    }
    setPlacement(sprite.grid);
    boundary_ = GpuBoundary(sprite.grid, sprite.boundaryEdges, sprite.boundaryKnown || sprite.status != SolidStatus::Open);
}

// --- GpuBoundary, GpuDistanceGrid ----------------------------------------

GpuBoundary::GpuBoundary(const SpriteGrid& grid, const std::vector<glm::vec3>& edges, bool known)
    : context_(ContextStamp::current("GpuSprite upload")), known_(known) {
    const glm::ivec3 p = axisPermutation(grid.axis);
    // The edges loop by loop, and the chain tree's nodes after them, so
    // that the shader takes far chains by their chords and expansions.
    detail::PackedBoundary packed = detail::packBoundary(edges, grid.axis);
    if (packed.data.empty()) packed.data.emplace_back(0.0f);
    buffer_ = detail::uploadBuffer(packed.data.data(), packed.data.size() * sizeof(glm::vec4), "uploading the boundary edges");
    edgeCount_ = packed.edgeCount;
    nodeCount_ = packed.nodeCount;
    // As SpriteGrid::texelCentre computes a ray's point, in float.
    lo_ = {grid.box.lo[p.x], grid.box.lo[p.y], grid.box.lo[p.z]};
    step_ = {grid.texelSize, grid.texelSize, grid.box.hi[p.z] - grid.box.lo[p.z]};
}

void GpuBoundary::setUniforms(GLuint program, const std::string& name, GLuint binding) const {
    if (!known_)
        throw InvalidArgument("this sprite of an open mesh was written by .vds format version 1, which does not "
                              "store the boundary edges the generalized winding number needs: bake it again");
    context_.check("GpuBoundary::setUniforms");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer_.id());
    glProgramUniform3fv(program, glGetUniformLocation(program, (name + ".lo").c_str()), 1, &lo_[0]);
    glProgramUniform3fv(program, glGetUniformLocation(program, (name + ".step").c_str()), 1, &step_[0]);
    glProgramUniform1i(program, glGetUniformLocation(program, (name + ".edgeCount").c_str()), GLint(edgeCount_));
    glProgramUniform1i(program, glGetUniformLocation(program, (name + ".nodeCount").c_str()), GLint(nodeCount_));
    checkGl("GpuBoundary::setUniforms");
}

GpuDistanceGrid::GpuDistanceGrid(const SpriteDistance& distance)
    : context_(ContextStamp::current("GpuSprite upload")),
      texture_(uploadDistanceTexture(distance.grid, distance.cells.data())), box_(distance.grid.box) {}

void GpuDistanceGrid::setUniforms(GLuint program, const std::string& sampler, const std::string& lo,
                                  const std::string& hi, GLuint unit) const {
    if (!texture_) throw InvalidArgument("the sprite carries no distance grid (bake it with --distance)");
    context_.check("GpuDistanceGrid::setUniforms");
    glBindTextureUnit(unit, texture_.id());
    glProgramUniform1i(program, glGetUniformLocation(program, sampler.c_str()), GLint(unit));
    glProgramUniform3fv(program, glGetUniformLocation(program, lo.c_str()), 1, &box_.lo[0]);
    glProgramUniform3fv(program, glGetUniformLocation(program, hi.c_str()), 1, &box_.hi[0]);
    checkGl("GpuDistanceGrid::setUniforms");
}

// --- GpuSprite ---------------------------------------------------------------

void GpuSprite::setPlacement(const SpriteGrid& grid) {
    matrix_ = grid.matrix;
    position_ = grid.position;
}

void GpuSprite::bind(GLuint unit) const {
    requireContext("GpuSprite::bind");
    glBindTextureUnit(unit, texture_.id());
}

void GpuSprite::setUniforms(GLuint program, const std::string& sampler, const std::string& placement,
                            GLuint unit) const {
    bind(unit);
    glProgramUniform1i(program, glGetUniformLocation(program, sampler.c_str()), GLint(unit));
    glProgramUniformMatrix3fv(program, glGetUniformLocation(program, (placement + ".matrix").c_str()), 1, GL_FALSE,
                              &matrix_[0][0]);
    glProgramUniform3fv(program, glGetUniformLocation(program, (placement + ".position").c_str()), 1, &position_[0]);
    checkGl("GpuSprite::setUniforms");
}

// --- GpuClassifier ---------------------------------------------------------

namespace {

constexpr std::size_t kPointBytes = 12;
constexpr GLuint kBoundaryBinding = 5; // classify.comp's VDS_BOUNDARY_BINDING
// classify.comp's VDS_POINTS_PER_INVOCATION (the labels of one 32-bit word)
// and VDS_LOCAL_SIZE.
constexpr std::size_t kPointsPerInvocation = 4;
constexpr std::uint32_t kLocalSize = 256;

std::size_t labelBytes(std::size_t points) { return (points + 3) / 4 * 4; }

// Below this a block is copied on the calling thread: waking the pool's
// threads costs more than it saves.
constexpr std::size_t kThreadedCopyBytes = std::size_t(2) << 20;

// The program of one form and rule (classify.comp): the generalized winding
// number's boundary term is compiled into its own program only.
const Program& classifierProgram(const GlContext& gl, bool columns, Rule rule) {
    const int id = rule == Rule::Parity ? 0 : rule == Rule::Winding ? 1 : 2;
    const std::string key = std::string("vds.classify.") + (columns ? "columns." : "texture.") + toString(rule);
    return gl.program(key, [columns, id] {
        std::string defines = "#define VDS_RULE_ID " + std::to_string(id) + "\n";
        if (columns) defines += "#define VDS_COLUMNS\n";
        if (id == 2) defines += "#define VDS_BOUNDARY_TERM\n";
        return buildProgram({{GL_COMPUTE_SHADER, "vds/classify.comp", ""}}, defines);
    });
}

} // namespace

GpuClassifier::GpuClassifier(const GlContext& gl, std::size_t batchPoints, HostTransfer transfer)
    : gl_(&gl), batch_(batchPoints) {
    const CurrentContext current(gl);
    copied_ = transfer == HostTransfer::Copied || (transfer == HostTransfer::Auto && !gl.info().software);
    stamp_ = ContextStamp::current("GpuClassifier");
    classifierProgram(gl, true, Rule::Parity); // a shader error shows at construction, not at the first call
    maxBlock_ = gl.limits().maxStorageBlockBytes;
    // Dispatches of a power of two of points keep every range's offset aligned.
    maxDispatch_ = std::size_t(1) << 30;
    while (maxDispatch_ * kPointBytes > maxBlock_) maxDispatch_ >>= 1;
    checkGl("building the GPU classifier");
}

GpuClassifier::~GpuClassifier() {
    if (!gl_ || capacity_ == 0 || !detail::glUsable()) return;
    try {
        const CurrentContext current(*gl_); // the staging buffers are freed in their own context
        slots_ = {};
    } catch (const std::exception&) {
        for (Slot& slot : slots_) { // cannot reach the context (another thread): leave the names to it
            slot.points.release();
            slot.labels.release();
            slot.gpuPoints.release();
            slot.gpuLabels.release();
            slot.done = Fence();
        }
    }
}

GpuClassifier::GpuClassifier(GpuClassifier&& o) noexcept
    : gl_(std::exchange(o.gl_, nullptr)), stamp_(o.stamp_), batch_(o.batch_), maxBlock_(o.maxBlock_), maxDispatch_(o.maxDispatch_), slots_(std::move(o.slots_)),
      capacity_(std::exchange(o.capacity_, 0)), copied_(o.copied_) {}

GpuClassifier& GpuClassifier::operator=(GpuClassifier&& o) noexcept {
    if (this != &o) {
        gl_ = std::exchange(o.gl_, nullptr);
        stamp_ = o.stamp_;
        maxBlock_ = o.maxBlock_;
        maxDispatch_ = o.maxDispatch_;
        slots_ = std::move(o.slots_);
        capacity_ = std::exchange(o.capacity_, 0);
        batch_ = o.batch_;
        copied_ = o.copied_;
    }
    return *this;
}

void GpuClassifier::dispatch(const GpuSprite& sprite, GLuint points, GLintptr pointsOffset, GLuint labels,
                             GLintptr labelsOffset, std::size_t count, Rule rule) {
    const std::uint64_t offsetBytes = (std::uint64_t(sprite.size().x) * sprite.size().y + 1) * 4;
    const std::uint64_t crossingBytes = std::max<std::uint64_t>(sprite.crossingCount(), 1) * 4;
    const bool columns = bool(sprite.offsets()) && offsetBytes <= maxBlock_ && crossingBytes <= maxBlock_;
    if (!columns && !bool(sprite.texture())) throw InvalidArgument("GpuClassifier: the sprite holds nothing to classify with");
    if (rule == Rule::GeneralizedWinding && !sprite.boundary().known())
        throw InvalidArgument("this sprite of an open mesh was written by .vds format version 1, which does not "
                              "store the boundary edges the generalized winding number needs: bake it again");
    // With no boundary edges (a mesh that bounds a solid) the generalized
    // winding number is the winding number: the plain program.
    const bool boundaryTerm = rule == Rule::GeneralizedWinding && sprite.boundary().edgeCount() > 0;
    const Program& program = classifierProgram(*gl_, columns, boundaryTerm || rule == Rule::Parity ? rule : Rule::Winding);
    glUseProgram(program.id());
    if (columns) {
        // The ranges the shader reads: a baked sprite's buffers may be padded.
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 3, sprite.offsets().id(), 0, GLsizeiptr(offsetBytes));
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 4, sprite.crossings().id(), 0, GLsizeiptr(crossingBytes));
        glUniform2i(glGetUniformLocation(program.id(), "u_size"), GLint(sprite.size().x), GLint(sprite.size().y));
        glUniformMatrix3fv(glGetUniformLocation(program.id(), "u_placement.matrix"), 1, GL_FALSE, &sprite.matrix()[0][0]);
        glUniform3fv(glGetUniformLocation(program.id(), "u_placement.position"), 1, &sprite.position()[0]);
    } else {
        sprite.setUniforms(program.id(), "u_ldi", "u_placement", 0);
    }
    if (boundaryTerm) sprite.boundary().setUniforms(program.id(), "u_boundary", kBoundaryBinding);
    const GLint countLoc = glGetUniformLocation(program.id(), "u_count");
    for (std::size_t first = 0; first < count; first += maxDispatch_) {
        const std::size_t n = std::min(maxDispatch_, count - first);
        const GLintptr p = pointsOffset + GLintptr(first * kPointBytes), l = labelsOffset + GLintptr(first);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, points, p, GLsizeiptr(n * kPointBytes));
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, points, p, GLsizeiptr(n * kPointBytes));
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 2, labels, l, GLsizeiptr(labelBytes(n)));
        glUniform1ui(countLoc, GLuint(n));
        glDispatchCompute(detail::strideGroups((n + kPointsPerInvocation - 1) / kPointsPerInvocation, kLocalSize), 1, 1);
    }
    for (GLuint binding = 0; binding <= kBoundaryBinding; ++binding) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
    if (!columns) glBindTextureUnit(0, 0);
    glUseProgram(0);
}

void GpuClassifier::enter(const char* what) const {
    if (!gl_) throw GlError(std::string(what) + ": the classifier is moved from");
    stamp_.checkThread(what);
}

void GpuClassifier::classify(const GpuSprite& sprite, GLuint points, std::size_t count, GLuint labels,
                             const ClassifyOptions& options) {
    enter("GpuClassifier::classify");
    const CurrentContext current(*gl_);
    sprite.requireContext("GpuClassifier::classify: the sprite");
    const Rule rule = options.rule;
    if (count == 0) return;
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    dispatch(sprite, points, 0, labels, 0, count, rule);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    checkGl("classifying points on the GPU");
}

// Staging buffers in host memory, mapped for good: the shader reads the points
// and writes the labels there, so the bus transfer is the dispatch itself.
void GpuClassifier::reserve(std::size_t points) {
    if (points <= capacity_) return;
    for (Slot& slot : slots_) {
        slot = Slot();
        slot.points = Buffer::create();
        slot.labels = Buffer::create();
        const GLbitfield write = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        const GLbitfield read = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        glNamedBufferStorage(slot.points.id(), GLsizeiptr(points * kPointBytes), nullptr, write | GL_CLIENT_STORAGE_BIT);
        glNamedBufferStorage(slot.labels.id(), GLsizeiptr(labelBytes(points)), nullptr, read | GL_CLIENT_STORAGE_BIT);
        checkGl("allocating the classifier's staging buffers");
        slot.pointsMap = glMapNamedBufferRange(slot.points.id(), 0, GLsizeiptr(points * kPointBytes), write);
        slot.labelsMap = glMapNamedBufferRange(slot.labels.id(), 0, GLsizeiptr(labelBytes(points)), read);
        if (!slot.pointsMap || !slot.labelsMap) throw GlError("cannot map the classifier's staging buffers");
        if (copied_) {
            slot.gpuPoints = Buffer::create();
            slot.gpuLabels = Buffer::create();
            glNamedBufferStorage(slot.gpuPoints.id(), GLsizeiptr(points * kPointBytes), nullptr, 0);
            glNamedBufferStorage(slot.gpuLabels.id(), GLsizeiptr(labelBytes(points)), nullptr, 0);
            checkGl("allocating the classifier's GPU buffers");
        }
    }
    capacity_ = points;
}

void GpuClassifier::finish(Slot& slot, std::uint8_t* labels) {
    if (slot.count == 0) return;
    slot.done.wait();
    copy(labels + slot.first, slot.labelsMap, slot.count);
    slot.done.reset();
    slot.count = 0;
}

// A host block of a batch copied on the library's threads, up to 16, one
// equal slice each: a core's memcpy is slower than the bus the points then
// cross, a PCIe 5 x16 link's 50 GB/s.
void GpuClassifier::copy(void* dst, const void* src, std::size_t bytes) {
    if (bytes < kThreadedCopyBytes) {
        std::memcpy(dst, src, bytes);
        return;
    }
    const unsigned threads = std::min(16u, detail::ThreadPool::hardwareThreads());
    detail::parallelFor(threads, bytes, (bytes + threads - 1) / threads, [&](std::size_t begin, std::size_t end) {
        std::memcpy(static_cast<char*>(dst) + begin, static_cast<const char*>(src) + begin, end - begin);
    });
}

// The staged batch classified, its labels back in the slot's staging
// buffer when `slot.done` signals.
void GpuClassifier::send(Slot& slot, const GpuSprite& sprite, Rule rule) {
    if (copied_) {
        glCopyNamedBufferSubData(slot.points.id(), slot.gpuPoints.id(), 0, 0, GLsizeiptr(slot.count * kPointBytes));
        dispatch(sprite, slot.gpuPoints.id(), 0, slot.gpuLabels.id(), 0, slot.count, rule);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glCopyNamedBufferSubData(slot.gpuLabels.id(), slot.labels.id(), 0, 0, GLsizeiptr(labelBytes(slot.count)));
    } else {
        dispatch(sprite, slot.points.id(), 0, slot.labels.id(), 0, slot.count, rule);
    }
    glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
    slot.done = Fence::insert();
}

void GpuClassifier::classify(const GpuSprite& sprite, const PointsView& points, std::uint8_t* labels,
                             const ClassifyOptions& options) {
    enter("GpuClassifier::classify");
    const CurrentContext current(*gl_);
    sprite.requireContext("GpuClassifier::classify: the sprite");
    const std::size_t count = points.count;
    const Rule rule = options.rule;
    if (options.stats) *options.stats = {count, 0};
    if (count == 0) return;
    const bool packed = points.scalar == Scalar::Float32 && points.strideBytes == kPointBytes;
    const std::size_t batch = std::clamp<std::size_t>(batch_, 1024, maxDispatch_) & ~std::size_t(3);
    reserve(std::min(batch, labelBytes(count)));
    const std::size_t step = std::min(batch, capacity_);
    std::size_t next = 0;
    try {
        for (std::size_t first = 0; first < count; first += step, ++next) {
            Slot& slot = slots_[next % slots_.size()];
            finish(slot, labels); // the batch three back: its buffers are free again
            slot.first = first;
            slot.count = std::min(step, count - first);
            if (packed) {
                copy(slot.pointsMap, static_cast<const char*>(points.data) + first * kPointBytes,
                     slot.count * kPointBytes);
            } else {
                auto* to = static_cast<glm::vec3*>(slot.pointsMap);
                for (std::size_t k = 0; k < slot.count; ++k) to[k] = points[first + k];
            }
            send(slot, sprite, rule);
        }
        for (std::size_t k = 0; k < slots_.size(); ++k) finish(slots_[(next + k) % slots_.size()], labels);
    } catch (...) {
        glFinish(); // no batch may still use the staging buffers when they are next written
        for (Slot& slot : slots_) {
            slot.done.reset();
            slot.count = 0;
        }
        throw;
    }
    checkGl("classifying points on the GPU");
}

} // namespace vds
