// The VDS (Trapp & Döllner 2008) against slicemaps (Eisemann & Décoret 2006)
// and solid voxelizations (Schwarz 2012) as point-in-solid tests: see
// <vds/eval/compare.h>.
#include <vds/all.h>
#include <vds/eval/compare.h>

#include <algorithm>
#include <optional>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <sstream>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <vds/bake.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/mesh_check.h>
#include <vds/sprite.h>
#include <vds/voxel/representation.h>

#include <vds/eval/distance.h>

namespace vds::eval {

using namespace vds::voxel;
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The rows' methods, from the method table: the VDS on the CPU, then every
// voxel representation's CPU lookup (their GPU forms give the same labels).
std::vector<Method> comparedMethods(bool voxels) {
    std::vector<Method> methods = {Method::Sprite};
    for (const MethodInfo* m = methodTable(); voxels && m != methodTable() + kMethodCount; ++m)
        if (m->layer == Layer::Voxel && !m->gpu) methods.push_back(m->method);
    return methods;
}

struct Samples {
    std::vector<glm::vec3> points; // uniform first, then near the surface
    std::size_t uniform = 0;
    std::vector<std::uint8_t> parity, winding, gwn; // exact answers (gwn: Rule::GeneralizedWinding only)
};

Samples samplePoints(MeshView mesh, const Box& box, const CompareOptions& o) {
    Samples s;
    std::mt19937 rng(o.seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const glm::vec3 size = box.hi - box.lo;
    s.uniform = o.uniformPoints;
    s.points.reserve(o.uniformPoints + o.surfacePoints);
    for (std::size_t k = 0; k < o.uniformPoints; ++k) {
        const glm::vec3 u(unit(rng), unit(rng), unit(rng));
        s.points.push_back(box.lo + (u * (1.0f + 2.0f * o.padding) - o.padding) * size);
    }
    // Surface points: triangles by area, uniform within, then along the normal.
    std::vector<double> area(mesh.triangleCount);
    double total = 0.0;
    for (std::size_t t = 0; t < mesh.triangleCount; ++t) {
        const glm::dvec3 a(mesh.positions[mesh.triangles[t].x]), b(mesh.positions[mesh.triangles[t].y]),
            c(mesh.positions[mesh.triangles[t].z]);
        total += 0.5 * glm::length(glm::cross(b - a, c - a));
        area[t] = total;
    }
    const float band = o.surfaceBand * std::max({size.x, size.y, size.z});
    std::uniform_real_distribution<double> pick(0.0, total);
    std::uniform_real_distribution<float> offset(-band, band);
    for (std::size_t k = 0; k < o.surfacePoints && total > 0.0; ++k) {
        const std::size_t t = std::min<std::size_t>(
            std::size_t(std::lower_bound(area.begin(), area.end(), pick(rng)) - area.begin()), mesh.triangleCount - 1);
        const glm::vec3 a = mesh.positions[mesh.triangles[t].x], b = mesh.positions[mesh.triangles[t].y],
                        c = mesh.positions[mesh.triangles[t].z];
        float u = unit(rng), v = unit(rng);
        if (u + v > 1.0f) {
            u = 1.0f - u;
            v = 1.0f - v;
        }
        const glm::vec3 n = glm::cross(b - a, c - a);
        const float len = glm::length(n);
        const glm::vec3 normal = len > 0.0f ? n / len : glm::vec3(0.0f);
        s.points.push_back(a + u * (b - a) + v * (c - a) + offset(rng) * normal);
    }
    return s;
}

/// Distances of points to the surface, computed on first use.
class DistanceCache {
public:
    DistanceCache(MeshView mesh, std::size_t count) : surface_(mesh), distance_(count, -1.0) {}
    double operator()(const std::vector<glm::vec3>& points, std::size_t k) {
        if (distance_[k] < 0.0) distance_[k] = surface_.distance(points[k]);
        return distance_[k];
    }

private:
    SurfaceDistance surface_;
    std::vector<double> distance_;
};

struct Built {
    std::unique_ptr<Classifier> classifier; // by makeClassifier
    double seconds = 0.0;
    const Sprite* sprite() const {
        const auto* c = dynamic_cast<const SpriteClassifier*>(classifier.get());
        return c ? &c->sprite() : nullptr;
    }
    const Model* model() const { return dynamic_cast<const Model*>(classifier.get()); }
    std::size_t memoryBytes() const { return sprite() ? sprite()->memoryBytes() : model()->memoryBytes(); }
};

// The VDS bake resolution giving texels of the voxel grid's cell size.
std::uint32_t vdsResolution(const Box& box, std::uint32_t resolution) {
    const glm::vec3 e = box.hi - box.lo;
    const double ratio = double(std::max(e.x, e.y)) / double(std::max({e.x, e.y, e.z}));
    return std::max<std::uint32_t>(1, std::uint32_t(std::lround(ratio * resolution)));
}

// Sprites are baked by fragment lists along z; a voxel model's time is its
// own build (`Model::buildSeconds`), a sprite's the whole bake.
Built buildOnce(MeshView mesh, Method method, std::uint32_t resolution, GlContext& gl, const std::string& name) {
    MethodOptions o;
    o.resolution = resolution;
    o.axis = Axis::Z;
    o.bakeMethod = BakeMethod::Lists;
    o.sourceName = name;
    Built b;
    const auto start = std::chrono::steady_clock::now();
    b.classifier = makeClassifier(gl, mesh, method, o);
    b.seconds = b.model() ? b.model()->buildSeconds() : secondsSince(start);
    return b;
}

// Builds up to three times while the builds are quick (under 0.3 s in all),
// keeping the fastest time: single builds of a few milliseconds are noise.
Built build(MeshView mesh, Method method, std::uint32_t resolution, GlContext& gl, const std::string& name) {
    Built best = buildOnce(mesh, method, resolution, gl, name);
    double total = best.seconds;
    for (int k = 1; k < 3 && total < 0.3; ++k) {
        Built again = buildOnce(mesh, method, resolution, gl, name);
        total += again.seconds;
        if (again.seconds < best.seconds) best = std::move(again);
    }
    return best;
}

// Memory of a voxel representation at a resolution, without building it.
std::size_t voxelMemory(const Box& box, Method method, std::uint32_t resolution) {
    ModelOptions o;
    o.resolution = resolution;
    return modelMemoryBytes(box, representationOf(method), o);
}

// Largest resolution in [1, kMaxCompareResolution] whose estimate fits `budget`; 0 if none.
template <class Estimate> std::uint32_t largestWithin(std::size_t budget, const Estimate& estimate) {
    std::uint32_t lo = 0, hi = kMaxCompareResolution;
    while (lo < hi) {
        const std::uint32_t mid = lo + (hi - lo + 1) / 2;
        if (estimate(mid) <= budget)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

void report(const CompareOptions& o, const std::string& what) {
    if (o.progress) o.progress(what);
}

std::string formatBytes(std::size_t b) {
    char buf[32];
    if (b >= (std::size_t(1) << 20))
        std::snprintf(buf, sizeof buf, "%.2f MiB", double(b) / double(1 << 20));
    else if (b >= 1024)
        std::snprintf(buf, sizeof buf, "%.1f KiB", double(b) / 1024.0);
    else
        std::snprintf(buf, sizeof buf, "%zu B", b);
    return buf;
}


} // namespace

namespace {

// One comparison: the sample points with their exact labels, and the rows
// measured so far.
class Comparison {
public:
    Comparison(MeshView mesh, const CompareOptions& options, GlContext& gl, bool gwn, CompareResult& result)
        : mesh_(mesh), options_(options), gl_(gl), gwn_(gwn), result_(result) {}

    void sampleAndClassify();
    /// Builds `method` at `resolution` (a VDS: at its bake resolution) and
    /// scores it by `rule` (a sprite answers every rule; the others parity).
    Built measure(Method method, Rule rule, const std::string& series, std::uint64_t target, std::uint32_t resolution,
                  Built* prebuilt);
    /// The sprite by each rule the comparison scores it by, one build.
    Built measureSprite(const std::string& series, std::uint64_t target, std::uint32_t resolution, Built* prebuilt) {
        Built sprite = measure(Method::Sprite, Rule::Parity, series, target, resolution, prebuilt);
        sprite = measure(Method::Sprite, Rule::Winding, series, target, resolution, &sprite);
        if (gwn_) sprite = measure(Method::Sprite, Rule::GeneralizedWinding, series, target, resolution, &sprite);
        return sprite;
    }
    /// Every method within `budget` bytes; the VDS's bake resolution from
    /// `perColumn` bytes a column (then shrunk until the bake fits).
    void measureWithin(std::size_t budget, double perColumn, const std::vector<Method>& methods);

private:
    /// Throughput: whole passes over the points for at least 0.1 s.
    double pointsPerSecond(const Classifier& classifier, Rule rule);
    void score(CompareRow& row);

    MeshView mesh_;
    const CompareOptions& options_;
    GlContext& gl_;
    bool gwn_;
    CompareResult& result_;
    Samples samples_;
    std::unique_ptr<DistanceCache> distances_;
    std::vector<std::uint8_t> labels_;
};

void Comparison::sampleAndClassify() {
    samples_ = samplePoints(mesh_, result_.bounds, options_);
    const std::size_t count = samples_.points.size();
    result_.uniformPoints = samples_.uniform;
    result_.surfacePoints = count - samples_.uniform;
    auto start = std::chrono::steady_clock::now();
    const ExactClassifier exact(mesh_, Axis::Z);
    result_.exactBuildSeconds = secondsSince(start);
    samples_.parity.resize(count);
    samples_.winding.resize(count);
    ClassifyOptions parity;
    parity.threads = options_.threads;
    start = std::chrono::steady_clock::now();
    exact.classify(PointsView(samples_.points.data(), count), samples_.parity.data(), parity);
    result_.exactPointsPerSecond = double(count) / std::max(secondsSince(start), 1e-9);
    ClassifyOptions winding = parity;
    winding.rule = Rule::Winding;
    exact.classify(PointsView(samples_.points.data(), count), samples_.winding.data(), winding);
    if (gwn_) {
        samples_.gwn.resize(count);
        ClassifyOptions generalized = parity;
        generalized.rule = Rule::GeneralizedWinding;
        exact.classify(PointsView(samples_.points.data(), count), samples_.gwn.data(), generalized);
    }
    const std::vector<std::uint8_t>& inside = gwn_ ? samples_.gwn : samples_.parity;
    for (std::size_t k = 0; k < samples_.uniform; ++k) result_.uniformInside += inside[k];
    distances_ = std::make_unique<DistanceCache>(mesh_, count);
    labels_.resize(count);
}

double Comparison::pointsPerSecond(const Classifier& classifier, Rule rule) {
    ClassifyOptions o;
    o.threads = options_.threads;
    o.rule = rule;
    const std::size_t count = samples_.points.size();
    const auto queryStart = std::chrono::steady_clock::now();
    std::size_t passes = 0;
    do {
        classifier.classify(PointsView(samples_.points.data(), count), labels_.data(), o);
        ++passes;
    } while (secondsSince(queryStart) < 0.1);
    return double(passes * count) / std::max(secondsSince(queryStart), 1e-9);
}

// The row's errors: the last labels against the truth by its rule.
void Comparison::score(CompareRow& row) {
    const std::size_t count = samples_.points.size();
    const std::vector<std::uint8_t>& truth = gwn_                      ? samples_.gwn
                                             : row.rule == Rule::Winding ? samples_.winding
                                                                         : samples_.parity;
    for (std::size_t k = 0; k < count; ++k) {
        if (labels_[k] == truth[k]) continue;
        (k < samples_.uniform ? row.uniformWrong : row.surfaceWrong) += 1;
        row.worstErrorDistance = std::max(row.worstErrorDistance, (*distances_)(samples_.points, k));
    }
    row.uniformErrorRate = samples_.uniform ? double(row.uniformWrong) / double(samples_.uniform) : 0.0;
    row.surfaceErrorRate = count > samples_.uniform ? double(row.surfaceWrong) / double(count - samples_.uniform) : 0.0;
    row.errorRate = count ? double(row.uniformWrong + row.surfaceWrong) / double(count) : 0.0;
    row.worstErrorCells = row.cellSize > 0.0 ? row.worstErrorDistance / row.cellSize : 0.0;
}

Built Comparison::measure(Method method, Rule rule, const std::string& series, std::uint64_t target,
                          std::uint32_t resolution, Built* prebuilt) {
    Built built = prebuilt ? std::move(*prebuilt) : build(mesh_, method, resolution, gl_, options_.meshName);
    CompareRow row;
    row.method = method;
    row.rule = rule;
    row.series = series;
    row.target = target;
    row.resolution = resolution;
    row.buildSeconds = built.seconds;
    row.pointsPerSecond = pointsPerSecond(*built.classifier, rule);
    if (const Sprite* sprite = built.sprite()) {
        row.cells = glm::uvec3(sprite->width(), sprite->height(), sprite->depthComplexity);
        row.cellSize = sprite->grid.texelSize;
        row.memoryBytes = sprite->memoryBytes();
        if (rule == Rule::GeneralizedWinding) row.memoryBytes += sprite->boundaryEdges.size() * sizeof(glm::vec3);
        row.gpuBytes = sprite->denseBytes();
    } else {
        const Model& model = *built.model();
        row.cells = model.cells();
        row.cellSize = model.cellSize();
        row.memoryBytes = model.memoryBytes();
        row.gpuBytes = model.gpuBytes();
    }
    score(row);
    result_.rows.push_back(row);
    return built;
}

void Comparison::measureWithin(std::size_t budget, double perColumn, const std::vector<Method>& methods) {
    const Box& box = result_.bounds;
    std::uint32_t vds = largestWithin(budget, [&](std::uint32_t n) {
        const SpriteGrid g = makeGrid(box, Axis::Z, n);
        return std::size_t(double(g.width) * g.height * perColumn + 4.0);
    });
    for (int attempt = 0; vds > 0 && attempt < 4; ++attempt) {
        Built sprite = buildOnce(mesh_, Method::Sprite, vds, gl_, options_.meshName);
        if (sprite.memoryBytes() > budget) {
            vds = std::uint32_t(double(vds) * std::sqrt(double(budget) / double(sprite.memoryBytes())) * 0.98);
            continue;
        }
        sprite = build(mesh_, Method::Sprite, vds, gl_, options_.meshName); // timed
        measureSprite("memory", budget, vds, &sprite);
        break;
    }
    for (Method method : methods) {
        if (method == Method::Sprite) continue;
        const std::uint32_t r = largestWithin(budget, [&](std::uint32_t n) { return voxelMemory(box, method, n); });
        if (r > 0) measure(method, Rule::Parity, "memory", budget, r, nullptr);
    }
}

// Throws unless the mesh and the options can be compared.
void requireComparable(const MeshReport& validation, const CompareOptions& options, bool gwn) {
    // The rows hold the sprite to both rules, so both must define inside;
    // the generalized winding number is defined for every usable mesh.
    requireUsable(validation, options.meshName);
    requireVolume(validation, options.meshName);
    // An open mesh is told by the parity rule (the weaker), a closed one by the winding rule.
    requireInsideDefined(validation, options.meshName,
                         gwn ? Rule::GeneralizedWinding : validation.closed() ? Rule::Winding : Rule::Parity,
                         options.meshFlags);
    if (options.resolutions.empty()) throw InvalidArgument("compare needs at least one resolution");
    for (std::uint32_t r : options.resolutions)
        if (r == 0 || r > kMaxCompareResolution)
            throw InvalidArgument("compare resolution " + std::to_string(r) + " is out of range (1 to " +
                                  std::to_string(kMaxCompareResolution) + ")");
}

} // namespace

CompareResult compare(MeshView mesh, const CompareOptions& options, GlContext* gl) {
    const bool gwn = options.rule == Rule::GeneralizedWinding;
    const MeshReport validation = validateMesh(mesh);
    requireComparable(validation, options, gwn);
    const bool voxels = !gwn || validation.closed(); // the voxel builders need a closed mesh
    const CurrentContext restore; // the caller's context is current again on return
    std::optional<GlContext> own;
    if (!gl) gl = &own.emplace();
    CompareResult result;
    if (gwn) {
        result.truth = "generalized-winding";
        result.note = voxels ? "truth: the exact generalized winding number for every row; slicemaps and solid voxels "
                               "answer parity"
                             : "truth: the exact generalized winding number; the mesh is open, so slicemaps and solid "
                               "voxels (parity of a closed mesh) are left out: the VDS only";
    }
    result.meshName = options.meshName;
    result.triangles = mesh.triangleCount;
    result.validation = validation.summary();
    result.bounds = meshBounds(mesh);
    const Box& box = result.bounds;
    Comparison comparison(mesh, options, *gl, gwn, result);
    report(options, "sampling points and classifying them exactly");
    comparison.sampleAndClassify();

    report(options, "warming up (shader compilation)");
    const std::vector<Method> methods = comparedMethods(voxels);
    for (Method method : methods) buildOnce(mesh, method, 8, *gl, options.meshName);

    std::vector<std::size_t> budgets = options.memoryBudgets;
    for (std::uint32_t r : options.resolutions) {
        report(options, "resolution " + std::to_string(r));
        if (options.memoryBudgets.empty()) budgets.push_back(voxelMemory(box, Method::Solid, r));
        comparison.measureSprite("resolution", r, vdsResolution(box, r), nullptr);
        for (Method method : methods)
            if (method != Method::Sprite) comparison.measure(method, Rule::Parity, "resolution", r, r, nullptr);
    }

    // A VDS probe bake gives the crossings per column, to pick bake resolutions
    // for the budgets.
    const std::uint32_t probeResolution = vdsResolution(box, options.resolutions.front());
    const Built probe = buildOnce(mesh, Method::Sprite, probeResolution, *gl, options.meshName);
    const double columns0 = double(probe.sprite()->width()) * probe.sprite()->height();
    const double perColumn = 4.0 + 4.0 * double(probe.sprite()->crossings.size()) / columns0;
    for (std::size_t budget : budgets) {
        report(options, "memory budget " + formatBytes(budget));
        comparison.measureWithin(budget, perColumn, methods);
    }
    report(options, "done");
    return result;
}

std::string CompareRow::name() const {
    return std::string(methodInfo(method).name) + (rule == Rule::Parity ? "" : std::string("/") + enumName(rule));
}

std::string CompareResult::table() const {
    std::ostringstream out;
    char line[512];
    std::snprintf(line, sizeof line, "%-26s %-10s %9s %5s %-16s %10s %10s %9s %10s %8s %8s %8s %9s\n", "method",
                  "series", "target", "res", "cells", "memory", "gpu", "build ms", "Mpts/s", "err %", "unif %",
                  "surf %", "worst cl");
    out << line;
    for (const CompareRow& r : rows) {
        const std::string target = r.series == "memory" ? formatBytes(std::size_t(r.target)) : std::to_string(r.target);
        const std::string cells =
            std::to_string(r.cells.x) + "x" + std::to_string(r.cells.y) + "x" + std::to_string(r.cells.z);
        std::snprintf(line, sizeof line, "%-26s %-10s %9s %5u %-16s %10s %10s %9.1f %10.2f %8.3f %8.3f %8.3f %9.2f\n",
                      r.name().c_str(), r.series.c_str(), target.c_str(), r.resolution, cells.c_str(),
                      formatBytes(r.memoryBytes).c_str(), formatBytes(r.gpuBytes).c_str(), r.buildSeconds * 1e3,
                      r.pointsPerSecond * 1e-6, 100.0 * r.errorRate, 100.0 * r.uniformErrorRate,
                      100.0 * r.surfaceErrorRate, r.worstErrorCells);
        out << line;
    }
    if (!note.empty()) out << note << "\n";
    return out.str();
}

std::string CompareResult::json() const {
    nlohmann::json rowList = nlohmann::json::array();
    for (const CompareRow& r : rows)
        rowList.push_back({{"method", r.name()},
                           {"rule", enumName(r.rule)},
                           {"series", r.series},
                           {"target", r.target},
                           {"resolution", r.resolution},
                           {"cells", {r.cells.x, r.cells.y, r.cells.z}},
                           {"cell_size", r.cellSize},
                           {"memory_bytes", r.memoryBytes},
                           {"gpu_bytes", r.gpuBytes},
                           {"build_seconds", r.buildSeconds},
                           {"points_per_second", r.pointsPerSecond},
                           {"uniform_wrong", r.uniformWrong},
                           {"surface_wrong", r.surfaceWrong},
                           {"uniform_error_rate", r.uniformErrorRate},
                           {"surface_error_rate", r.surfaceErrorRate},
                           {"error_rate", r.errorRate},
                           {"worst_error_distance", r.worstErrorDistance},
                           {"worst_error_cells", r.worstErrorCells}});
    const nlohmann::json result = {
        {"mesh", meshName},
        {"triangles", triangles},
        {"validation", validation},
        {"bounds", {{"lo", {bounds.lo.x, bounds.lo.y, bounds.lo.z}}, {"hi", {bounds.hi.x, bounds.hi.y, bounds.hi.z}}}},
        {"uniform_points", uniformPoints},
        {"surface_points", surfacePoints},
        {"uniform_inside", uniformInside},
        {"truth", truth},
        {"note", note},
        {"exact_build_seconds", exactBuildSeconds},
        {"exact_points_per_second", exactPointsPerSecond},
        {"rows", rowList}};
    // Non-finite numbers are written as null (nlohmann's rule): the output is always valid JSON.
    return result.dump(2) + "\n";
}

} // namespace vds::eval
