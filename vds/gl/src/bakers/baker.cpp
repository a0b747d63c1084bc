// vds: re-baking a deforming mesh (<vds/gl/baker.h>).
#include <vds/gl/baker.h>

#include <cmath>
#include <string>
#include <utility>

#include <vds/error.h>
#include <vds/gl/bake.h>
#include <vds/mesh_check.h>

#include <vds/gl/detail/bake_setup.h>
#include <vds/gl/detail/layer_count.h>

namespace vds {

namespace {

bool finite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

BakeOptions cpuOnly(BakeOptions options) {
    if (options.method != BakeMethod::Cpu && options.method != BakeMethod::Auto)
        throw InvalidArgument(std::string("Baker: the ") + toString(options.method) +
                              " method needs a GL context (Baker(gl, mesh, options))");
    options.method = BakeMethod::Cpu;
    return options;
}

BakeOptions chosen(const GlContext& gl, BakeOptions options) {
    if (options.method == BakeMethod::Auto) options.method = chooseBakeMethod(gl);
    return options;
}

} // namespace

Baker::Baker(const GlContext& gl, TriangleMesh mesh, BakeOptions options)
    : gl_(&gl), mesh_(std::move(mesh)), options_(chosen(gl, std::move(options))) {
    validate();
}

Baker::Baker(TriangleMesh mesh, BakeOptions options) : mesh_(std::move(mesh)), options_(cpuOnly(std::move(options))) {
    validate();
}

// The one validation: the report, the axis, and which vertices bound the box.
void Baker::validate() {
    BakeOptions first = options_;
    first.timings = nullptr;
    // The GL bakers count the layers in their own raster, on a GPU beside validation.
    detail::GlPhaseClock untimed(nullptr);
    const detail::BakeSetup setup = gl_ && options_.method != BakeMethod::Cpu
                                        ? detail::prepareGlBake(*gl_, mesh_, first, untimed).setup
                                        : detail::prepareBake(mesh_, first);
    report_ = setup.report;
    options_.axis = setup.grid.axis;
    std::vector<bool> named(mesh_.positions.size(), false);
    for (const glm::uvec3& t : mesh_.triangles)
        for (int c = 0; c < 3; ++c) named[t[c]] = true;
    for (std::size_t v = 0; v < named.size(); ++v)
        if (named[v]) used_.push_back(std::uint32_t(v));
}

void Baker::updateVertices(const glm::vec3* positions, std::size_t count) {
    if (count != mesh_.positions.size())
        throw InvalidArgument("Baker::updateVertices: " + std::to_string(count) + " positions for a mesh of " +
                              std::to_string(mesh_.positions.size()) + " vertices");
    for (std::uint32_t v : used_)
        if (!finite(positions[v]))
            throw InvalidMesh("Baker::updateVertices: vertex " + std::to_string(v) + " has a NaN or infinite coordinate");
    mesh_.positions.assign(positions, positions + count);
}

Sprite Baker::rebake() {
    const detail::BakeClock clock(options_.timings);
    detail::BakeSetup setup;
    {
        const detail::HostPhase phase(options_.timings, BakePhase::Validation);
        setup.report = report_;
        // The box of the vertices the triangles name, as validateMesh bounds them.
        Box& box = setup.report.bounds;
        box.lo = box.hi = mesh_.positions[used_.front()];
        for (std::uint32_t v : used_) {
            box.lo = glm::min(box.lo, mesh_.positions[v]);
            box.hi = glm::max(box.hi, mesh_.positions[v]);
        }
        requireVolume(setup.report, options_.sourceName);
        setup.grid = makeGrid(box, *options_.axis, options_.resolution);
    }
    if (!gl_) return detail::bakeCpu(setup, mesh_, options_);
    return detail::bakePrepared(*gl_, setup, mesh_, options_, {});
}

} // namespace vds
