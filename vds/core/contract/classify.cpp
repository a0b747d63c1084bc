// vds: the one classify contract (<vds/classify.h>): points views, the
// method table, and what every Classifier shares (rule checks, float64
// points, occupancy by cell centres).
#include <vds/classify.h>

#include <algorithm>
#include <cassert>
#include <cstring>
#include <vector>

#include <vds/error.h>

namespace vds {

namespace {

constexpr std::uint8_t bit(Rule r) { return std::uint8_t(1u << unsigned(r)); }
constexpr std::uint8_t kAllRules = bit(Rule::Parity) | bit(Rule::Winding) | bit(Rule::GeneralizedWinding);
constexpr std::uint8_t kParity = bit(Rule::Parity);

// One row a method, in `Method` order. The voxel representations answer
// parity only (their builders XOR or count occupancy, never orientation).
constexpr MethodInfo kMethods[kMethodCount] = {
    {Method::Sprite, "sprite", Layer::Core, false, false, false, true, kAllRules, 1024,
     "the volumetric parity test on a baked sprite, on the CPU"},
    {Method::Exact, "exact", Layer::Core, false, true, false, false, kAllRules, 0,
     "exact predicates on the triangles themselves (the yardstick)"},
    {Method::Certified, "certified", Layer::Core, false, true, false, false, kAllRules, 1024,
     "the exact answers, most from certified bands per texel"},
    {Method::SpriteGpu, "sprite-gpu", Layer::Gl, true, false, false, true, kAllRules, 1024,
     "the volumetric parity test in a GL compute shader"},
    {Method::Slicemap, "slicemap", Layer::Voxel, false, false, true, false, kParity, 256,
     "front/back slicemap pair, uniform slicing, looked up on the CPU"},
    {Method::SlicemapLocal, "slicemap-local", Layer::Voxel, false, false, true, false, kParity, 256,
     "front/back slicemap pair, local slicing, looked up on the CPU"},
    {Method::Solid, "solid", Layer::Voxel, false, false, true, false, kParity, 256,
     "solid voxels by rasterization, looked up on the CPU"},
    {Method::SolidCompute, "solid-compute", Layer::Voxel, false, false, true, false, kParity, 256,
     "solid voxels in compute, looked up on the CPU"},
    {Method::SlicemapGpu, "slicemap-gpu", Layer::Voxel, true, false, true, false, kParity, 256,
     "the slicemap pair, looked up in a GL compute shader"},
    {Method::SlicemapLocalGpu, "slicemap-local-gpu", Layer::Voxel, true, false, true, false, kParity, 256,
     "the locally sliced slicemap pair, looked up in a GL compute shader"},
    {Method::SolidGpu, "solid-gpu", Layer::Voxel, true, false, true, false, kParity, 256,
     "rasterized solid voxels, looked up in a GL compute shader"},
    {Method::SolidComputeGpu, "solid-compute-gpu", Layer::Voxel, true, false, true, false, kParity, 256,
     "compute-shader solid voxels, looked up in a GL compute shader"},
    {Method::CertifiedGpu, "certified-gpu", Layer::Gl, true, true, false, false, kAllRules, 1024,
     "the exact answers, the certified bands' in a GL compute shader, the rest on the CPU"},
    {Method::Custom, "custom", Layer::Core, false, false, false, false, kAllRules, 0,
     "a classifier defined outside the library (derive from vds::Classifier)"},
};

constexpr bool tableInOrder() {
    for (std::size_t k = 0; k < kMethodCount; ++k)
        if (std::size_t(kMethods[k].method) != k) return false;
    return true;
}
static_assert(tableInOrder(), "kMethods must list the methods in enum order");

constexpr std::pair<Method, Method> kGpuForms[] = {{Method::Sprite, Method::SpriteGpu},
                                                   {Method::Certified, Method::CertifiedGpu},
                                                   {Method::Slicemap, Method::SlicemapGpu},
                                                   {Method::SlicemapLocal, Method::SlicemapLocalGpu},
                                                   {Method::Solid, Method::SolidGpu},
                                                   {Method::SolidCompute, Method::SolidComputeGpu}};

// Float64 and float points are classified through float chunks of this many points.
constexpr std::size_t kChunk = std::size_t(1) << 16;

} // namespace

namespace {
PointsView viewOf(const void* xyz, std::size_t n, std::size_t strideBytes, Scalar scalar) {
    PointsView v;
    v.data = xyz;
    v.count = n;
    v.strideBytes = strideBytes;
    v.scalar = scalar;
    return v;
}
} // namespace

PointsView PointsView::floats(const float* xyz, std::size_t n, std::size_t strideBytes) {
    return viewOf(xyz, n, strideBytes, Scalar::Float32);
}

PointsView PointsView::doubles(const double* xyz, std::size_t n, std::size_t strideBytes) {
    return viewOf(xyz, n, strideBytes, Scalar::Float64);
}

glm::vec3 PointsView::operator[](std::size_t k) const {
    assert(k < count);
    const char* at = static_cast<const char*>(data) + k * strideBytes;
    if (scalar == Scalar::Float32) {
        glm::vec3 p;
        std::memcpy(&p, at, sizeof p);
        return p;
    }
    double d[3];
    std::memcpy(d, at, sizeof d);
    return {float(d[0]), float(d[1]), float(d[2])};
}

PointsView PointsView::slice(std::size_t first, std::size_t n) const {
    assert(first + n <= count);
    PointsView v = *this;
    v.data = static_cast<const char*>(data) + first * strideBytes;
    v.count = n;
    return v;
}

const MethodInfo& methodInfo(Method method) {
    assert(std::size_t(method) < kMethodCount);
    return kMethods[std::size_t(method)];
}

const MethodInfo* methodTable() { return kMethods; }

void requireRule(Method method, Rule rule) {
    if (answers(method, rule)) return;
    std::string rules;
    for (const auto& entry : EnumNames<Rule>::table)
        if (answers(method, entry.value)) rules += std::string(rules.empty() ? "" : ", ") + entry.name;
    throw InvalidArgument(std::string("method '") + enumName(method) + "' cannot answer the " + enumName(rule) +
                          " rule (it answers " + rules + ")");
}

Method cpuForm(Method method) {
    for (const auto& [cpu, gpu] : kGpuForms)
        if (gpu == method) return cpu;
    return method;
}

Method gpuForm(Method method) {
    for (const auto& [cpu, gpu] : kGpuForms)
        if (cpu == method) return gpu;
    return method;
}

Classifier::~Classifier() = default;

std::string Classifier::summary() const { return enumName(method()); }

std::uint8_t Classifier::rules() const { return methodInfo(method()).rules; }

namespace {

void requireRule(const Classifier& classifier, Rule rule) {
    if (classifier.answers(rule)) return;
    requireRule(classifier.method(), rule); // the table's wording where the table says no
    throw InvalidArgument(classifier.summary() + " cannot answer the " + enumName(rule) + " rule");
}

} // namespace

void Classifier::classify(const PointsView& points, std::uint8_t* labels, const ClassifyOptions& options) const {
    requireRule(*this, options.rule);
    assert((points.data && labels) || points.count == 0);
    assert(points.strideBytes >= 3 * points.scalarBytes());
    // Methods without an exact fallback leave the stats as preset: every
    // point answered by the method itself.
    if (options.stats) *options.stats = {points.count, 0};
    if (points.scalar == Scalar::Float32) {
        classifyFloats(static_cast<const float*>(points.data), points.count, points.strideBytes, labels, options);
        return;
    }
    // Doubles: rounded to float a chunk at a time, stats summed over chunks.
    ClassifyStats total;
    ClassifyStats chunkStats;
    ClassifyOptions chunkOptions = options;
    chunkOptions.stats = options.stats ? &chunkStats : nullptr;
    std::vector<glm::vec3> floats(std::min(points.count, kChunk));
    for (std::size_t first = 0; first < points.count; first += kChunk) {
        const std::size_t n = std::min(kChunk, points.count - first);
        for (std::size_t k = 0; k < n; ++k) floats[k] = points[first + k];
        chunkStats = {n, 0};
        classifyFloats(reinterpret_cast<const float*>(floats.data()), n, sizeof(glm::vec3), labels + first,
                       chunkOptions);
        total.certain += chunkStats.certain;
        total.exact += chunkStats.exact;
    }
    if (options.stats) *options.stats = total;
}

bool Classifier::contains(const glm::vec3& p, Rule rule) const {
    std::uint8_t label = 0;
    ClassifyOptions options;
    options.rule = rule;
    options.threads = 1;
    classify(PointsView(&p, 1), &label, options);
    return label != 0;
}

void Classifier::occupancy(const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options) const {
    checkGrid(grid);
    requireRule(*this, options.rule);
    assert(cells);
    if (options.stats) *options.stats = {grid.cellCount(), 0};
    sweep(grid, cells, options);
}

void Classifier::sweep(const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options) const {
    // Cell centres in order, a chunk at a time (k fastest, as `Grid::index`).
    std::vector<glm::vec3> centres;
    centres.reserve(std::min(grid.cellCount(), kChunk));
    ClassifyStats total;
    ClassifyStats chunkStats;
    ClassifyOptions chunkOptions = options;
    chunkOptions.stats = options.stats ? &chunkStats : nullptr;
    std::size_t done = 0;
    const auto flush = [&] {
        chunkStats = {centres.size(), 0};
        classifyFloats(reinterpret_cast<const float*>(centres.data()), centres.size(), sizeof(glm::vec3), cells + done,
                       chunkOptions);
        total.certain += chunkStats.certain;
        total.exact += chunkStats.exact;
        done += centres.size();
        centres.clear();
    };
    for (std::uint32_t i = 0; i < grid.dims.x; ++i)
        for (std::uint32_t j = 0; j < grid.dims.y; ++j)
            for (std::uint32_t k = 0; k < grid.dims.z; ++k) {
                centres.push_back(grid.cellCentre(i, j, k));
                if (centres.size() == kChunk) flush();
            }
    if (!centres.empty()) flush();
    if (options.stats) *options.stats = total;
}

void occupancy(const Classifier& classifier, const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options) {
    classifier.occupancy(grid, cells, options);
}

} // namespace vds
