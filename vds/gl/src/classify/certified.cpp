// vds: Method::CertifiedGpu (<vds/gl/certified.h>): the certified bands in
// a compute shader (vds/certified.comp), the unsure points compacted there
// and answered by the exact classifier on the host.
#include <vds/gl/certified.h>

#include <algorithm>
#include <atomic>
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

GpuCertifiedBands::GpuCertifiedBands(const CertifiedClassifier& certified) : grid_(certified.grid()) {
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

// One batch's GL memory, kept between calls, and the host's copy of its
// unsure list.
struct GpuCertifiedClassifier::Batches {
    std::size_t batch = 1024;  // points a batch (a power of two)
    std::size_t capacity = 0; // points the buffers hold
    Buffer points, labels, unsure, answers;
    std::vector<UnsureRecord> records;
    std::vector<std::uint32_t> answered; // (index << 1) | label, for the scatter pass

    void reserve(std::size_t n, std::uint64_t limit) {
        if (n <= capacity) return;
        points = detail::zeroedBuffer(n * kPointBytes, limit, "the certified classifier's points");
        labels = detail::zeroedBuffer(labelBytes(n), limit, "the certified classifier's labels");
        unsure = detail::zeroedBuffer(kUnsureHeaderBytes + n * kUnsureRecordBytes, limit,
                                      "the certified classifier's unsure points");
        answers = detail::zeroedBuffer(n * sizeof(std::uint32_t), limit, "the certified classifier's answers");
        capacity = n;
    }

    // Classifies `count` points of `pointsBuffer` from byte `pointsOffset`
    // into `labelsBuffer` from byte `labelsOffset` (2 where unsure), and
    // reads the unsure list into `records`.
    void run(const GlContext& gl, const GpuCertifiedBands& bands, GLuint pointsBuffer, GLintptr pointsOffset,
             GLuint labelsBuffer, GLintptr labelsOffset, std::size_t count, Rule rule) {
        const GLuint zero = 0;
        glNamedBufferSubData(unsure.id(), 0, sizeof zero, &zero);
        const Program& program = certifiedProgram(gl, rule);
        glUseProgram(program.id());
        bands.setUniforms(program.id(), "u_certified", kOffsetsBinding, kBandsBinding);
        const auto bytes = GLsizeiptr(count * kPointBytes);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, pointsBuffer, pointsOffset, bytes);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, pointsBuffer, pointsOffset, bytes);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kLabelsBinding, labelsBuffer, labelsOffset,
                          GLsizeiptr(labelBytes(count)));
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kUnsureBinding, unsure.id(), 0,
                          GLsizeiptr(kUnsureHeaderBytes + count * kUnsureRecordBytes));
        glUniform1ui(glGetUniformLocation(program.id(), "u_count"), GLuint(count));
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        glDispatchCompute(detail::strideGroups((count + 3) / 4, kLocalSize), 1, 1);
        for (GLuint binding = 0; binding <= kUnsureBinding; ++binding)
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
        glUseProgram(0);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        GLuint unsureCount = 0;
        glGetNamedBufferSubData(unsure.id(), 0, sizeof unsureCount, &unsureCount);
        records.resize(unsureCount);
        if (unsureCount > 0)
            glGetNamedBufferSubData(unsure.id(), kUnsureHeaderBytes, GLsizeiptr(unsureCount * kUnsureRecordBytes),
                                    records.data());
        checkGl("classifying points on the GPU (certified)");
    }

    // `answered` written into the labels from byte `labelsOffset` (their
    // unsure bytes, 2, become the answers).
    void scatter(const GlContext& gl, GLuint labelsBuffer, GLintptr labelsOffset, std::size_t count) {
        if (answered.empty()) return;
        glNamedBufferSubData(answers.id(), 0, GLsizeiptr(answered.size() * sizeof(std::uint32_t)), answered.data());
        const Program& program = scatterProgram(gl);
        glUseProgram(program.id());
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, labelsBuffer, labelsOffset, GLsizeiptr(labelBytes(count)));
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, answers.id(), 0,
                          GLsizeiptr(answered.size() * sizeof(std::uint32_t)));
        glUniform1ui(glGetUniformLocation(program.id(), "u_count"), GLuint(answered.size()));
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        glDispatchCompute(detail::strideGroups(answered.size(), kLocalSize), 1, 1);
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
    while (batch * 2 <= batchPoints && (kUnsureHeaderBytes + batch * 2 * kUnsureRecordBytes) <= gl_.limits().maxStorageBlockBytes)
        batch *= 2;
    batches_->batch = batch;
}

GpuCertifiedClassifier::~GpuCertifiedClassifier() {
    const CurrentContext current(gl_);
    batches_.reset();
    bands_.reset();
}

std::size_t GpuCertifiedClassifier::memoryBytes() const {
    return bands_->bytes() + batches_->capacity * (kPointBytes + 1 + kUnsureRecordBytes + 4) +
           cpu_->exact().memoryBytes();
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
        for (std::size_t k = begin; k < end; ++k) write(k, records[k].index, exact.contains(records[k].point(), options.rule));
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
    const char* base = reinterpret_cast<const char*>(xyz);
    std::vector<glm::vec3> staged;
    std::size_t exactCount = 0;
    for (std::size_t first = 0; first < count; first += b.batch) {
        const std::size_t n = std::min(b.batch, count - first);
        const void* packed = base + first * strideBytes;
        if (strideBytes != kPointBytes) {
            staged.resize(n);
            for (std::size_t k = 0; k < n; ++k) std::memcpy(&staged[k], base + (first + k) * strideBytes, kPointBytes);
            packed = staged.data();
        }
        glNamedBufferSubData(b.points.id(), 0, GLsizeiptr(n * kPointBytes), packed);
        b.run(gl_, *bands_, b.points.id(), 0, b.labels.id(), 0, n, options.rule);
        glGetNamedBufferSubData(b.labels.id(), 0, GLsizeiptr(n), labels + first);
        answerExactly(exact, b.records, options, [&](std::size_t, std::uint32_t index, bool inside) {
            labels[first + index] = inside ? 1 : 0;
        });
        exactCount += b.records.size();
    }
    checkGl("classifying points on the GPU (certified)");
    if (options.stats) *options.stats = {count - exactCount, exactCount};
}

void GpuCertifiedClassifier::classify(GLuint points, std::size_t count, GLuint labels,
                                      const ClassifyOptions& options) const {
    const CurrentContext current(gl_);
    Batches& b = *batches_;
    b.reserve(std::min(b.batch, std::max<std::size_t>(count, 1)), gl_.limits().maxStorageBlockBytes);
    const bool whole = !certifies(bands_->certifiedRules(), options.rule);
    std::size_t exactCount = 0;
    std::vector<glm::vec3> host;
    std::vector<std::uint8_t> answers;
    for (std::size_t first = 0; first < count; first += b.batch) {
        const std::size_t n = std::min(b.batch, count - first);
        const auto pointsOffset = GLintptr(first * kPointBytes), labelsOffset = GLintptr(first);
        if (whole) { // every point exact: read back, classify on the host, copy the labels in
            host.resize(n);
            answers.assign(labelBytes(n), 0);
            glGetNamedBufferSubData(points, pointsOffset, GLsizeiptr(n * kPointBytes), host.data());
            ClassifyOptions o = options;
            o.stats = nullptr;
            cpu_->exact().classify(host, answers.data(), o);
            glNamedBufferSubData(b.labels.id(), 0, GLsizeiptr(answers.size()), answers.data());
            glCopyNamedBufferSubData(b.labels.id(), labels, 0, labelsOffset, GLsizeiptr(answers.size()));
            exactCount += n;
            continue;
        }
        b.run(gl_, *bands_, points, pointsOffset, labels, labelsOffset, n, options.rule);
        b.answered.resize(b.records.size());
        answerExactly(cpu_->exact(), b.records, options, [&](std::size_t k, std::uint32_t index, bool inside) {
            b.answered[k] = (index << 1) | (inside ? 1u : 0u);
        });
        b.scatter(gl_, labels, labelsOffset, n);
        exactCount += b.records.size();
    }
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    checkGl("classifying points on the GPU (certified)");
    if (options.stats) *options.stats = {count - exactCount, exactCount};
}

} // namespace vds
