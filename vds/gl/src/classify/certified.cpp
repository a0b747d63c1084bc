// vds: Method::CertifiedGpu (<vds/gl/certified.h>): the certified bands in
// a compute shader (vds/certified.comp), the unsure points compacted there
// and answered by the exact classifier on the host.
#include <vds/gl/certified.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/shader.h>
#include <vds/detail/parallel.h>
#include <vds/gl/detail/buffers.h>
#include <vds/gl/detail/dispatch.h>

namespace vds {

namespace {

// certified.comp's bindings: 0, 1 points, 2 labels, 3 offsets, 4 bands, 5 unsure list.
constexpr GLuint kLabelsBinding = 2, kOffsetsBinding = 3, kBandsBinding = 4, kUnsureBinding = 5;
constexpr std::size_t kPointBytes = 12;
// The unsure list: a 16-byte header (the count), then 16 bytes a point (x, y, z bits, index).
constexpr std::size_t kUnsureHeaderBytes = 16, kUnsureRecordBytes = 16;
constexpr std::uint32_t kLocalSize = 256;
// Unsure points answered per task of the library's threads (each an exact query).
constexpr std::size_t kExactChunk = 256;

std::size_t labelBytes(std::size_t points) { return (points + 3) / 4 * 4; }

// One program per rule: winding and the generalized winding number share
// one (where the bands certify them, the mesh is closed and oriented).
const Program& certifiedProgram(const GlContext& gl, Rule rule) {
    const bool parity = rule == Rule::Parity;
    return gl.program(std::string("vds.certified.") + (parity ? "parity" : "winding"), [parity] {
        return buildProgram({{GL_COMPUTE_SHADER, "vds/certified.comp", ""}},
                            std::string("#define VDS_RULE_ID ") + (parity ? "0" : "1") + "\n");
    });
}

const Program& scatterProgram(const GlContext& gl) {
    return gl.program("vds.certified.scatter",
                      [] { return buildProgram({{GL_COMPUTE_SHADER, "vds/certified_scatter.comp", ""}}); });
}

bool certifies(std::uint8_t rules, Rule rule) { return (rules >> unsigned(rule)) & 1u; }

struct UnsureRecord {
    std::uint32_t bits[3]; // x, y, z as read by the GPU
    std::uint32_t index;   // in the batch
    glm::vec3 point() const {
        glm::vec3 p;
        std::memcpy(&p, bits, sizeof p);
        return p;
    }
};

} // namespace

GpuCertifiedBands::GpuCertifiedBands(const CertifiedClassifier& certified)
    : context_(ContextStamp::current("GpuCertifiedBands")), grid_(certified.grid()) {
    const CertifiedBands b = certified.bands();
    box_ = b.box;
    depthAxis_ = b.depthAxis;
    rules_ = b.certifiedRules;
    const std::uint64_t limit = GlLimits::query().maxStorageBlockBytes;
    const std::size_t offsetBytes = (b.columnCount + 1) * sizeof(std::uint32_t);
    const std::size_t bandBytes = std::max<std::size_t>(b.bandCount, 1) * sizeof(CertifiedBand);
    detail::requireStorageSize(offsetBytes, limit, "the certified bands' offsets");
    detail::requireStorageSize(bandBytes, limit, "the certified bands");
    const std::uint32_t none[2] = {0, 0}; // a mesh the bands do not certify: no column is read
    offsets_ = detail::uploadBuffer(b.offsets ? static_cast<const void*>(b.offsets) : none,
                                    b.offsets ? offsetBytes : sizeof none, "uploading the certified bands");
    bands_ = detail::uploadBuffer(b.bands, b.bandCount * sizeof(CertifiedBand), "uploading the certified bands");
    bytes_ = offsetBytes + bandBytes;
}

void GpuCertifiedBands::setUniforms(GLuint program, const std::string& name, GLuint offsetsBinding,
                                    GLuint bandsBinding) const {
    context_.check("GpuCertifiedBands::setUniforms");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, offsetsBinding, offsets_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, bandsBinding, bands_.id());
    const auto at = [&](const char* field) { return glGetUniformLocation(program, (name + "." + field).c_str()); };
    glProgramUniformMatrix3fv(program, at("placement.matrix"), 1, GL_FALSE, &grid_.matrix[0][0]);
    glProgramUniform3fv(program, at("placement.position"), 1, &grid_.position[0]);
    glProgramUniform2i(program, at("size"), GLint(grid_.width), GLint(grid_.height));
    glProgramUniform3fv(program, at("lo"), 1, &box_.lo[0]);
    glProgramUniform3fv(program, at("hi"), 1, &box_.hi[0]);
    glProgramUniform1i(program, at("depthAxis"), depthAxis_);
    glProgramUniform1i(program, at("rules"), GLint(rules_));
    checkGl("GpuCertifiedBands::setUniforms");
}

// Where the host reads a batch's unsure list: the GPU appends to the list
// in its own memory (its atomics and writes stay local), then copies the
// count and the first records, as many as a batch is expected to hold, into
// this buffer in host memory, mapped for good (persistent, coherent), so
// that the host reads them with a memcpy once the batch's fence has passed.
// On an H200 a glGetNamedBufferSubData of the list itself cost about 4 ms
// a batch (20 of the 23 ms of 20M points in 5 batches). A batch with more
// unsure points than that reads the rest with glGetNamedBufferSubData.
Buffer readbackBuffer(std::size_t bytes, std::uint64_t limit, const unsigned char*& mapped) {
    const char* what = "the certified classifier's unsure points (read back)";
    detail::requireStorageSize(bytes, limit, what);
    Buffer b = Buffer::create();
    const GLbitfield access = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    glNamedBufferStorage(b.id(), GLsizeiptr(bytes), nullptr, access | GL_CLIENT_STORAGE_BIT);
    if (glGetError() == GL_OUT_OF_MEMORY) throw OutOfMemory(std::string("GL cannot allocate ") + what);
    mapped = static_cast<const unsigned char*>(glMapNamedBufferRange(b.id(), 0, GLsizeiptr(bytes), access));
    if (!mapped) throw GlError(std::string("GL cannot map ") + what);
    checkGl(what);
    return b;
}

/// Unsure records a batch's read-back buffer holds: 1/64 of the batch (the
/// certified bands leave 0.2-0.3% of uniform points unsure on closed meshes).
std::size_t readbackRecords(std::size_t batch) { return std::max<std::size_t>(1024, batch / 64); }

// Two batches' GL memory, kept between calls, so that the host answers one
// batch's unsure points while the GPU classifies the next.
struct GpuCertifiedClassifier::Batches {
    struct Slot {
        Buffer points, labels;   // staging in GPU memory, for host arrays
        Buffer unsure, answers;  // the unsure list; the exact answers for the scatter pass
        Buffer readback;                         // the list's count and first records (readbackBuffer)
        const unsigned char* readbackMapped = nullptr;
        Fence done;              // after the batch's dispatch
        std::vector<UnsureRecord> records;
        std::vector<std::uint32_t> answered; // (index << 1) | label
        std::size_t first = 0, count = 0;    // the batch's points
    };
    std::size_t batch = 1024;  // points a batch (a power of two)
    std::size_t capacity = 0;  // points each slot's buffers hold
    std::array<Slot, 2> slots;

    void reserve(std::size_t n, std::uint64_t limit) {
        if (n <= capacity) return;
        for (Slot& slot : slots) {
            slot.points = detail::zeroedBuffer(n * kPointBytes, limit, "the certified classifier's points");
            slot.labels = detail::zeroedBuffer(labelBytes(n), limit, "the certified classifier's labels");
            slot.unsure = detail::zeroedBuffer(kUnsureHeaderBytes + n * kUnsureRecordBytes, limit,
                                               "the certified classifier's unsure points");
            slot.readback = readbackBuffer(kUnsureHeaderBytes + readbackRecords(n) * kUnsureRecordBytes, limit,
                                           slot.readbackMapped);
            slot.answers = detail::zeroedBuffer(n * sizeof(std::uint32_t), limit, "the certified classifier's answers");
        }
        capacity = n;
    }

    // Queues the classification of `slot.count` points of `pointsBuffer`
    // from byte `pointsOffset` into `labelsBuffer` from byte `labelsOffset`
    // (2 where unsure), the unsure ones listed in `slot.unsure`; `slot.done`
    // signals when it is over.
    void dispatch(const GlContext& gl, const GpuCertifiedBands& bands, Slot& slot, GLuint pointsBuffer,
                  GLintptr pointsOffset, GLuint labelsBuffer, GLintptr labelsOffset, Rule rule) {
        const GLuint zero = 0;
        glNamedBufferSubData(slot.unsure.id(), 0, sizeof zero, &zero);
        const Program& program = certifiedProgram(gl, rule);
        glUseProgram(program.id());
        bands.setUniforms(program.id(), "u_certified", kOffsetsBinding, kBandsBinding);
        const auto bytes = GLsizeiptr(slot.count * kPointBytes);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, pointsBuffer, pointsOffset, bytes);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, pointsBuffer, pointsOffset, bytes);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kLabelsBinding, labelsBuffer, labelsOffset,
                          GLsizeiptr(labelBytes(slot.count)));
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kUnsureBinding, slot.unsure.id(), 0,
                          GLsizeiptr(kUnsureHeaderBytes + slot.count * kUnsureRecordBytes));
        glUniform1ui(glGetUniformLocation(program.id(), "u_count"), GLuint(slot.count));
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        glDispatchCompute(detail::strideGroups((slot.count + 3) / 4, kLocalSize), 1, 1);
        for (GLuint binding = 0; binding <= kUnsureBinding; ++binding)
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
        glUseProgram(0);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        const std::size_t held = std::min(slot.count, readbackRecords(capacity));
        glCopyNamedBufferSubData(slot.unsure.id(), slot.readback.id(), 0, 0,
                                 GLsizeiptr(kUnsureHeaderBytes + held * kUnsureRecordBytes));
        glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
        slot.done = Fence::insert();
        checkGl("classifying points on the GPU (certified)");
    }

    // Waits for the slot's dispatch and reads its unsure list into `records`
    // from the read-back buffer's mapping (the rest, if any, from the list).
    void collect(Slot& slot) {
        slot.done.wait();
        GLuint unsureCount = 0;
        std::memcpy(&unsureCount, slot.readbackMapped, sizeof unsureCount);
        slot.records.resize(unsureCount);
        const std::size_t held = std::min<std::size_t>(unsureCount, readbackRecords(capacity));
        if (held > 0) std::memcpy(slot.records.data(), slot.readbackMapped + kUnsureHeaderBytes, held * kUnsureRecordBytes);
        if (unsureCount > held)
            glGetNamedBufferSubData(slot.unsure.id(), GLintptr(kUnsureHeaderBytes + held * kUnsureRecordBytes),
                                    GLsizeiptr((unsureCount - held) * kUnsureRecordBytes), slot.records.data() + held);
    }

    // The slot's `answered` written into the labels from byte `labelsOffset`
    // (their unsure bytes, 2, become the answers).
    void scatter(const GlContext& gl, Slot& slot, GLuint labelsBuffer, GLintptr labelsOffset) {
        if (slot.answered.empty()) return;
        const auto bytes = GLsizeiptr(slot.answered.size() * sizeof(std::uint32_t));
        glNamedBufferSubData(slot.answers.id(), 0, bytes, slot.answered.data());
        const Program& program = scatterProgram(gl);
        glUseProgram(program.id());
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, labelsBuffer, labelsOffset, GLsizeiptr(labelBytes(slot.count)));
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, slot.answers.id(), 0, bytes);
        glUniform1ui(glGetUniformLocation(program.id(), "u_count"), GLuint(slot.answered.size()));
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        glDispatchCompute(detail::strideGroups(slot.answered.size(), kLocalSize), 1, 1);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
        glUseProgram(0);
        checkGl("writing the exact answers on the GPU (certified)");
    }
};

GpuCertifiedClassifier::GpuCertifiedClassifier(const GlContext& gl, MeshView mesh, const CertifiedOptions& options,
                                               std::size_t batchPoints)
    : gl_(gl), cpu_(std::make_unique<CertifiedClassifier>(mesh, options)), batches_(std::make_unique<Batches>()) {
    const CurrentContext current(gl_);
    bands_ = std::make_unique<GpuCertifiedBands>(*cpu_);
    certifiedProgram(gl_, Rule::Parity); // a shader error shows at construction, not at the first call
    // A power of two of points keeps every batch's byte offsets aligned for
    // glBindBufferRange; the unsure list, 16 bytes a point, must fit one block.
    std::size_t batch = 1024;
    const std::uint64_t block = gl_.limits().maxStorageBlockBytes;
    while (batch * 2 <= batchPoints && kUnsureHeaderBytes + batch * 2 * kUnsureRecordBytes <= block) batch *= 2;
    batches_->batch = batch;
}

GpuCertifiedClassifier::~GpuCertifiedClassifier() {
    const CurrentContext current(gl_);
    batches_.reset();
    bands_.reset();
}

std::size_t GpuCertifiedClassifier::memoryBytes() const {
    const std::size_t perPoint = kPointBytes + 1 + kUnsureRecordBytes + sizeof(std::uint32_t);
    return bands_->bytes() + batches_->slots.size() * batches_->capacity * perPoint + cpu_->exact().memoryBytes();
}

std::string GpuCertifiedClassifier::summary() const {
    return "certified-gpu " + cpu_->summary().substr(std::string("certified ").size()) + " on " + gl_.info().renderer;
}

namespace {

// The unsure points of a batch answered by the exact classifier on the
// library's threads: `write(index, inside)` for each record.
template <class Write>
void answerExactly(const ExactClassifier& exact, const std::vector<UnsureRecord>& records,
                   const ClassifyOptions& options, const Write& write) {
    detail::parallelFor(options.threads, records.size(), kExactChunk, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k)
            write(k, records[k].index, exact.contains(records[k].point(), options.rule));
    });
}

} // namespace

void GpuCertifiedClassifier::classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes,
                                            std::uint8_t* labels, const ClassifyOptions& options) const {
    const ExactClassifier& exact = cpu_->exact();
    if (!certifies(bands_->certifiedRules(), options.rule)) { // the exact path whole, as the CPU form
        ClassifyOptions whole = options;
        whole.stats = nullptr;
        exact.classify(PointsView::floats(xyz, count, strideBytes), labels, whole);
        if (options.stats) *options.stats = {0, count};
        return;
    }
    const CurrentContext current(gl_);
    Batches& b = *batches_;
    b.reserve(std::min(b.batch, count), gl_.limits().maxStorageBlockBytes);
    std::size_t exactCount = 0;
    // A batch's labels read back and its unsure points answered, while the GPU runs the next batch.
    const auto finish = [&](Batches::Slot& slot) {
        b.collect(slot);
        glGetNamedBufferSubData(slot.labels.id(), 0, GLsizeiptr(slot.count), labels + slot.first);
        answerExactly(exact, slot.records, options, [&](std::size_t, std::uint32_t index, bool inside) {
            labels[slot.first + index] = inside ? 1 : 0;
        });
        exactCount += slot.records.size();
    };
    const char* base = reinterpret_cast<const char*>(xyz);
    std::vector<glm::vec3> staged;
    Batches::Slot* previous = nullptr;
    for (std::size_t first = 0, next = 0; first < count; first += b.batch, ++next) {
        Batches::Slot& slot = b.slots[next % b.slots.size()]; // free: its batch was finished last round
        slot.first = first;
        slot.count = std::min(b.batch, count - first);
        const void* packed = base + first * strideBytes;
        if (strideBytes != kPointBytes) {
            staged.resize(slot.count);
            for (std::size_t k = 0; k < slot.count; ++k)
                std::memcpy(&staged[k], base + (first + k) * strideBytes, kPointBytes);
            packed = staged.data();
        }
        glNamedBufferSubData(slot.points.id(), 0, GLsizeiptr(slot.count * kPointBytes), packed);
        b.dispatch(gl_, *bands_, slot, slot.points.id(), 0, slot.labels.id(), 0, options.rule);
        if (previous) finish(*previous);
        previous = &slot;
    }
    if (previous) finish(*previous);
    checkGl("classifying points on the GPU (certified)");
    if (options.stats) *options.stats = {count - exactCount, exactCount};
}

void GpuCertifiedClassifier::classifyAllExact(GLuint points, std::size_t count, GLuint labels,
                                              const ClassifyOptions& options) const {
    Batches& b = *batches_;
    std::vector<glm::vec3> host;
    std::vector<std::uint8_t> answers;
    ClassifyOptions o = options;
    o.stats = nullptr;
    for (std::size_t first = 0; first < count; first += b.batch) { // read back, classify, copy the labels in
        const std::size_t n = std::min(b.batch, count - first);
        host.resize(n);
        answers.assign(labelBytes(n), 0);
        glGetNamedBufferSubData(points, GLintptr(first * kPointBytes), GLsizeiptr(n * kPointBytes), host.data());
        cpu_->exact().classify(host, answers.data(), o);
        const Buffer& staging = b.slots[0].labels;
        glNamedBufferSubData(staging.id(), 0, GLsizeiptr(answers.size()), answers.data());
        glCopyNamedBufferSubData(staging.id(), labels, 0, GLintptr(first), GLsizeiptr(answers.size()));
    }
    if (options.stats) *options.stats = {0, count};
}

void GpuCertifiedClassifier::classify(GLuint points, std::size_t count, GLuint labels,
                                      const ClassifyOptions& options) const {
    const CurrentContext current(gl_);
    Batches& b = *batches_;
    b.reserve(std::min(b.batch, std::max<std::size_t>(count, 1)), gl_.limits().maxStorageBlockBytes);
    if (!certifies(bands_->certifiedRules(), options.rule)) {
        classifyAllExact(points, count, labels, options);
    } else {
        std::size_t exactCount = 0;
        // A batch's unsure points answered on the host and written in, while the GPU runs the next batch.
        const auto finish = [&](Batches::Slot& slot) {
            b.collect(slot);
            slot.answered.resize(slot.records.size());
            answerExactly(cpu_->exact(), slot.records, options, [&](std::size_t k, std::uint32_t index, bool inside) {
                slot.answered[k] = (index << 1) | (inside ? 1u : 0u);
            });
            b.scatter(gl_, slot, labels, GLintptr(slot.first));
            exactCount += slot.records.size();
        };
        Batches::Slot* previous = nullptr;
        for (std::size_t first = 0, next = 0; first < count; first += b.batch, ++next) {
            Batches::Slot& slot = b.slots[next % b.slots.size()];
            slot.first = first;
            slot.count = std::min(b.batch, count - first);
            b.dispatch(gl_, *bands_, slot, points, GLintptr(first * kPointBytes), labels, GLintptr(first),
                       options.rule);
            if (previous) finish(*previous);
            previous = &slot;
        }
        if (previous) finish(*previous);
        if (options.stats) *options.stats = {count - exactCount, exactCount};
    }
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    checkGl("classifying points on the GPU (certified)");
}

} // namespace vds
