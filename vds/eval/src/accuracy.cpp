// Accuracy of a sprite against the exact classifier. Trapp & Doellner 2008,
// section 5.2 names the errors (resolution, surfaces nearly parallel to the
// view); this measures them: how many points are wrong, and how far from the
// surface, in texels.
#include <vds/all.h>
#include <vds/eval/accuracy.h>

#include <algorithm>
#include <optional>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <memory>
#include <sstream>


#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <vds/eval/distance.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/gl/context.h>
#include <vds/eval/image.h>
#include <vds/mesh_check.h>
#include <vds/vds_file.h>

namespace vds::eval {

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

std::vector<glm::vec3> uniformPoints(const Box& box, std::size_t n, std::mt19937& rng) {
    const glm::vec3 size = box.hi - box.lo;
    std::uniform_real_distribution<float> u(-0.1f, 1.1f);
    std::vector<glm::vec3> p(n);
    for (auto& q : p) q = box.lo + glm::vec3(u(rng), u(rng), u(rng)) * size;
    return p;
}

// Area-weighted points on the surface, moved along the normal by up to
// `spread` either way.
std::vector<glm::vec3> surfacePoints(MeshView mesh, std::size_t n, float spread, std::mt19937& rng) {
    std::vector<double> area(mesh.triangleCount + 1, 0.0);
    for (std::size_t t = 0; t < mesh.triangleCount; ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        const glm::vec3 a = mesh.positions[tri.x], b = mesh.positions[tri.y], c = mesh.positions[tri.z];
        area[t + 1] = area[t] + 0.5 * double(glm::length(glm::cross(b - a, c - a)));
    }
    std::vector<glm::vec3> p;
    if (!(area.back() > 0.0)) return p;
    p.reserve(n);
    std::uniform_real_distribution<double> pick(0.0, area.back());
    std::uniform_real_distribution<float> u(0.0f, 1.0f), offset(-spread, spread);
    while (p.size() < n) {
        const std::size_t t = std::size_t(std::upper_bound(area.begin(), area.end(), pick(rng)) - area.begin()) - 1;
        const glm::uvec3 tri = mesh.triangles[std::min(t, mesh.triangleCount - 1)];
        const glm::vec3 a = mesh.positions[tri.x], b = mesh.positions[tri.y], c = mesh.positions[tri.z];
        const glm::vec3 normal = glm::cross(b - a, c - a);
        const float len = glm::length(normal);
        if (!(len > 0.0f)) continue;
        const float r1 = std::sqrt(u(rng)), r2 = u(rng);
        p.push_back(a * (1 - r1) + b * (r1 * (1 - r2)) + c * (r1 * r2) + normal * (offset(rng) / len));
    }
    return p;
}

// Slice through the box centre across `axis`: grey inside, white outside,
// red where the sprite says inside but the solid is not, blue the reverse.
Image sliceImage(const SpriteClassifier& sprite, const ExactClassifier& exact, const Box& box, int axis, Rule rule,
                 std::uint32_t size) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const glm::vec3 lo = box.lo - 0.05f * (box.hi - box.lo), hi = box.hi + 0.05f * (box.hi - box.lo);
    const float scale = std::max(hi[u] - lo[u], hi[v] - lo[v]) / float(size);
    const std::uint32_t w = std::max(1u, std::uint32_t((hi[u] - lo[u]) / scale)),
                        h = std::max(1u, std::uint32_t((hi[v] - lo[v]) / scale));
    std::vector<glm::vec3> points(std::size_t(w) * h);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) {
            glm::vec3 p;
            p[axis] = 0.5f * (box.lo[axis] + box.hi[axis]);
            p[u] = lo[u] + (float(x) + 0.5f) * scale;
            p[v] = hi[v] - (float(y) + 0.5f) * scale; // image rows run top to bottom
            points[std::size_t(y) * w + x] = p;
        }
    std::vector<std::uint8_t> a(points.size()), b(points.size());
    ClassifyOptions o;
    o.rule = rule;
    sprite.classify({points.data(), points.size()}, a.data(), o);
    exact.classify({points.data(), points.size()}, b.data(), o);
    Image image(w, h);
    for (std::size_t k = 0; k < points.size(); ++k) {
        const std::uint8_t g = b[k] ? 170 : 255;
        std::uint8_t* px = &image.rgba[4 * k];
        px[0] = px[1] = px[2] = g;
        px[3] = 255;
    }
    for (std::uint32_t y = 0; y < h; ++y) // wrong pixels as 3x3 dots, so single ones can be seen
        for (std::uint32_t x = 0; x < w; ++x) {
            const std::size_t k = std::size_t(y) * w + x;
            if (a[k] == b[k]) continue;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int xx = int(x) + dx, yy = int(y) + dy;
                    if (xx < 0 || yy < 0 || xx >= int(w) || yy >= int(h)) continue;
                    std::uint8_t* px = image.at(std::uint32_t(xx), std::uint32_t(yy));
                    px[0] = a[k] ? 220 : 20;
                    px[1] = 30;
                    px[2] = a[k] ? 30 : 220;
                }
        }
    return image;
}

// What the evaluation holds across resolutions: the exact classifier, the
// distance field and the uniform points with their exact labels.
struct Yardstick {
    const ExactClassifier& exact;
    const SurfaceDistance& field;
    const std::vector<glm::vec3>& uniform;
    const std::vector<std::uint8_t>& uniformExact;
    double uniformExactSeconds;
};

// The sprite's size in texels, bytes and file bytes.
void describe(EvalRow& row, const Sprite& sprite) {
    row.width = sprite.width();
    row.height = sprite.height();
    row.depthComplexity = sprite.depthComplexity;
    row.texelSize = sprite.grid.texelSize;
    row.memoryBytes = sprite.memoryBytes();
    row.denseBytes = sprite.denseBytes();
    row.fileBytes = encodeSprite(sprite).size();
}

// The distances of (a sample of) the wrong points to the surface, in texels.
void measureDistances(EvalRow& row, std::vector<glm::vec3>& wrong, const SurfaceDistance& field, float texel,
                      std::size_t sample, std::mt19937& rng) {
    std::shuffle(wrong.begin(), wrong.end(), rng);
    wrong.resize(std::min(wrong.size(), sample));
    double sum = 0.0;
    for (const auto& p : wrong) {
        const double d = double(field.distance(p)) / double(texel);
        row.maxWrongDistanceTexels = std::max(row.maxWrongDistanceTexels, d);
        sum += d;
        row.wrongBeyondTexelDiagonal += d > std::sqrt(2.0);
    }
    row.distancesMeasured = wrong.size();
    row.meanWrongDistanceTexels = wrong.empty() ? 0.0 : sum / double(wrong.size());
}

// The sprite's labels of the uniform points and of points near the surface
// against the exact ones: rates, wrong counts, distances, slice images.
void score(EvalRow& row, const SpriteClassifier& vds, const Yardstick& y, const TriangleMesh& mesh, const Box& box,
           const EvalOptions& options, std::mt19937& rng) {
    ClassifyOptions classifyOptions;
    classifyOptions.rule = options.rule;
    classifyOptions.threads = options.threads;
    const std::vector<glm::vec3>& uniform = y.uniform;
    const float texel = vds.sprite().grid.texelSize;
    const std::vector<glm::vec3> near = surfacePoints(mesh, options.surfacePoints, 4.0f * texel, rng);
    std::vector<std::uint8_t> uniformVds(uniform.size()), nearVds(near.size()), nearExact(near.size());
    double t0 = now();
    vds.classify({uniform.data(), uniform.size()}, uniformVds.data(), classifyOptions);
    const double vdsSeconds = now() - t0;
    t0 = now();
    y.exact.classify({near.data(), near.size()}, nearExact.data(), classifyOptions);
    const double nearExactSeconds = now() - t0;
    vds.classify({near.data(), near.size()}, nearVds.data(), classifyOptions);
    row.vdsPointsPerSecond = vdsSeconds > 0 ? double(uniform.size()) / vdsSeconds : 0.0;
    const double exactSeconds = y.uniformExactSeconds + nearExactSeconds;
    row.exactPointsPerSecond = exactSeconds > 0 ? double(uniform.size() + near.size()) / exactSeconds : 0.0;

    std::vector<glm::vec3> wrong;
    row.uniformPoints = uniform.size();
    row.surfacePoints = near.size();
    for (std::size_t k = 0; k < uniform.size(); ++k)
        if (uniformVds[k] != y.uniformExact[k]) wrong.push_back(uniform[k]);
    row.uniformWrong = wrong.size();
    for (std::size_t k = 0; k < near.size(); ++k)
        if (nearVds[k] != nearExact[k]) wrong.push_back(near[k]);
    row.surfaceWrong = wrong.size() - row.uniformWrong;
    measureDistances(row, wrong, y.field, texel, options.distanceSample, rng);

    if (!options.imagePrefix.empty()) {
        for (int axis = 0; axis < 3; ++axis) {
            const std::string path =
                options.imagePrefix + "-" + std::to_string(row.resolution) + "-" + "xyz"[axis] + ".png";
            writePng(sliceImage(vds, y.exact, box, axis, options.rule, options.imageSize), path);
            row.images.push_back(path);
        }
    }
}

} // namespace

EvalReport evaluate(const TriangleMesh& mesh, const EvalOptions& options, GlContext* gl,
                    const std::function<void(const std::string&)>& progress) {
    auto say = [&](const std::string& s) {
        if (progress) progress(s);
    };
    const MeshReport validation = validateMesh(mesh);
    requireUsable(validation, mesh.name);
    requireVolume(validation, mesh.name);
    requireInsideDefined(validation, mesh.name, options.rule);
    EvalReport report;
    report.mesh = mesh.name;
    report.triangles = mesh.triangles.size();
    report.validation = validation.summary();
    report.rule = options.rule;
    report.axis = options.axis;
    const Box box = validation.bounds;

    const CurrentContext restore; // the caller's context is current again on return
    std::optional<GlContext> own;
    if (!gl && options.method != BakeMethod::Cpu) gl = &own.emplace();
    ClassifyOptions classifyOptions;
    classifyOptions.rule = options.rule;
    classifyOptions.threads = options.threads;

    say("building the exact classifier");
    const ExactClassifier exact(mesh, options.axis);
    const SurfaceDistance field(mesh);
    std::mt19937 rng(options.seed);
    const std::vector<glm::vec3> uniform = uniformPoints(box, options.uniformPoints, rng);
    std::vector<std::uint8_t> uniformExact(uniform.size());
    const double t0 = now();
    exact.classify({uniform.data(), uniform.size()}, uniformExact.data(), classifyOptions);
    const Yardstick yardstick{exact, field, uniform, uniformExact, now() - t0};

    for (std::uint32_t resolution : options.resolutions) {
        EvalRow row;
        row.resolution = resolution;
        BakeOptions bakeOptions;
        bakeOptions.resolution = resolution;
        bakeOptions.axis = options.axis;
        bakeOptions.method = options.method;
        bakeOptions.sourceName = mesh.name;
        say("baking at " + std::to_string(resolution));
        const double bakeStart = now();
        const SpriteClassifier vds(gl ? bake(*gl, mesh, bakeOptions) : bake(mesh, bakeOptions));
        row.bakeSeconds = now() - bakeStart;
        describe(row, vds.sprite());
        say("classifying at " + std::to_string(resolution));
        score(row, vds, yardstick, mesh, box, options, rng);
        report.rows.push_back(row);
    }
    return report;
}

std::string toTable(const EvalReport& r) {
    std::string out = r.mesh + ": " + std::to_string(r.triangles) + " triangles, " + r.validation + ", rule " +
                      toString(r.rule) + ", axis " + toString(r.axis) + "\n\n";
    out += "| resolution | w x h x d | wrong (uniform) | wrong (near surface) | max / mean wrong distance [texels] | "
           "beyond sqrt(2) texels | bake [s] | .vds bytes | memory bytes | dense bytes | VDS pts/s | exact pts/s |\n"
           "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    const auto percent = [](std::size_t part, std::size_t whole) { return whole ? 100.0 * part / whole : 0.0; };
    for (const EvalRow& w : r.rows) {
        char row[512]; // numbers only
        std::snprintf(row, sizeof row,
                      "| %u | %ux%ux%u | %zu / %zu (%.4f%%) | %zu / %zu (%.3f%%) | %.2f / %.2f | %zu of %zu | %.2f | "
                      "%zu | %zu | %zu | %.3g | %.3g |\n",
                      w.resolution, w.width, w.height, w.depthComplexity, w.uniformWrong, w.uniformPoints,
                      percent(w.uniformWrong, w.uniformPoints), w.surfaceWrong, w.surfacePoints,
                      percent(w.surfaceWrong, w.surfacePoints), w.maxWrongDistanceTexels, w.meanWrongDistanceTexels,
                      w.wrongBeyondTexelDiagonal, w.distancesMeasured, w.bakeSeconds, w.fileBytes, w.memoryBytes,
                      w.denseBytes, w.vdsPointsPerSecond, w.exactPointsPerSecond);
        out += row;
    }
    return out;
}

std::string toJson(const EvalReport& r) {
    nlohmann::json rows = nlohmann::json::array();
    for (const EvalRow& w : r.rows)
        rows.push_back({{"resolution", w.resolution},
                        {"width", w.width},
                        {"height", w.height},
                        {"depth_complexity", w.depthComplexity},
                        {"texel_size", w.texelSize},
                        {"bake_seconds", w.bakeSeconds},
                        {"file_bytes", w.fileBytes},
                        {"memory_bytes", w.memoryBytes},
                        {"dense_bytes", w.denseBytes},
                        {"uniform_points", w.uniformPoints},
                        {"uniform_wrong", w.uniformWrong},
                        {"surface_points", w.surfacePoints},
                        {"surface_wrong", w.surfaceWrong},
                        {"distances_measured", w.distancesMeasured},
                        {"max_wrong_distance_texels", w.maxWrongDistanceTexels},
                        {"mean_wrong_distance_texels", w.meanWrongDistanceTexels},
                        {"wrong_beyond_texel_diagonal", w.wrongBeyondTexelDiagonal},
                        {"vds_points_per_second", w.vdsPointsPerSecond},
                        {"exact_points_per_second", w.exactPointsPerSecond},
                        {"images", w.images}});
    const nlohmann::json report = {{"mesh", r.mesh},           {"triangles", r.triangles},
                                   {"validation", r.validation}, {"rule", toString(r.rule)},
                                   {"axis", toString(r.axis)},   {"rows", rows}};
    // Non-finite numbers are written as null (nlohmann's rule): the output is always valid JSON.
    return report.dump(2) + "\n";
}

} // namespace vds::eval
