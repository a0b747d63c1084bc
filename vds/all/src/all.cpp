// vds: the umbrella's entry points over every layer (<vds/all.h>): one
// switch over `Method`, no registry.
#include <vds/all.h>

#include <utility>

#include <vds/error.h>
#include <vds/mesh_check.h>

namespace vds {

namespace {

std::uint32_t resolutionFor(Method method, const MethodOptions& options) {
    return options.resolution ? options.resolution : methodInfo(method).defaultResolution;
}

Sprite bakeFor(const GlContext* gl, MeshView mesh, Method method, const MethodOptions& options) {
    BakeOptions bakeOptions;
    bakeOptions.resolution = resolutionFor(method, options);
    bakeOptions.axis = options.axis;
    bakeOptions.method = options.bakeMethod;
    bakeOptions.sourceName = options.sourceName;
    return gl ? bakeOnGl(*gl, mesh, bakeOptions) : bake(mesh, bakeOptions);
}

CertifiedOptions certifiedOptions(Method method, const MethodOptions& options) {
    CertifiedOptions o;
    o.resolution = resolutionFor(method, options);
    o.axis = options.axis.value_or(Axis::Z);
    o.threads = options.threads;
    return o;
}

// A GL classifier with the private context it was made on: the classifier
// goes first, then the context.
class OwnContext final : public Classifier {
public:
    template <class Make>
    explicit OwnContext(Make&& make) {
        const CurrentContext restore; // saved before GlContext() makes its own context current
        gl_ = std::make_unique<GlContext>();
        inner_ = make(*gl_);
    }
    ~OwnContext() override { inner_.reset(); }
    Method method() const override { return inner_->method(); }
    std::size_t memoryBytes() const override { return inner_->memoryBytes(); }
    std::string summary() const override { return inner_->summary(); }

protected:
    void classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                        const ClassifyOptions& options) const override {
        inner_->classify(PointsView::floats(xyz, count, strideBytes), labels, options);
    }
    void sweep(const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options) const override {
        inner_->occupancy(grid, cells, options);
    }

private:
    std::unique_ptr<GlContext> gl_;
    std::unique_ptr<Classifier> inner_;
};

// The methods of vds_core; a sprite baked on `gl` where given, else on the CPU.
std::unique_ptr<Classifier> makeCore(const GlContext* gl, MeshView mesh, Method method, const MethodOptions& options) {
    switch (method) {
    case Method::Sprite: return std::make_unique<SpriteClassifier>(bakeFor(gl, mesh, method, options));
    case Method::Exact: return std::make_unique<ExactClassifier>(mesh, options.axis.value_or(Axis::Z));
    case Method::Certified: return std::make_unique<CertifiedClassifier>(mesh, certifiedOptions(method, options));
    default: return nullptr;
    }
}

// A flat mesh bounds no volume: the one message, before any method is built.
void requireVolumeOf(MeshView mesh, const MethodOptions& options) {
    MeshReport bounds;
    bounds.bounds = meshBounds(mesh);
    requireVolume(bounds, options.sourceName);
}

void refuseCustom(Method method) {
    if (!methodInfo(method).builtIn())
        throw InvalidArgument("method 'custom' is a classifier defined outside the library; makeClassifier builds "
                              "the library's own methods only");
}

} // namespace

std::unique_ptr<Classifier> makeClassifier(const GlContext& gl, MeshView mesh, Method method,
                                           const MethodOptions& options) {
    refuseCustom(method);
    requireVolumeOf(mesh, options);
    if (auto core = makeCore(&gl, mesh, method, options)) return core;
    if (method == Method::SpriteGpu)
        return std::make_unique<GpuSpriteClassifier>(gl, bakeFor(&gl, mesh, method, options));
    if (method == Method::CertifiedGpu) return std::make_unique<GpuCertifiedClassifier>(gl, mesh, certifiedOptions(method, options));
    voxel::ModelOptions o;
    o.resolution = resolutionFor(method, options);
    o.slices = options.slices;
    voxel::Model model = voxel::buildModel(gl, mesh, voxel::representationOf(method), o);
    if (!methodInfo(method).gpu) return std::make_unique<voxel::Model>(std::move(model));
    return std::make_unique<voxel::GpuModelClassifier>(gl, std::move(model));
}

std::unique_ptr<Classifier> makeClassifier(MeshView mesh, Method method, const MethodOptions& options) {
    refuseCustom(method);
    requireVolumeOf(mesh, options);
    const bool needsGl = methodInfo(method).layer != Layer::Core ||
                         (method == Method::Sprite && options.bakeMethod != BakeMethod::Cpu);
    if (!needsGl) return makeCore(nullptr, mesh, method, options);
    // Build on a private context; CPU lookups (the voxel models) keep no GL.
    if (!methodInfo(method).gpu) {
        const CurrentContext restore;
        const GlContext gl;
        return makeClassifier(gl, mesh, method, options);
    }
    return std::make_unique<OwnContext>([&](const GlContext& gl) { return makeClassifier(gl, mesh, method, options); });
}

std::unique_ptr<Classifier> makeClassifier(const GlContext& gl, Sprite sprite, Method method) {
    if (method == Method::SpriteGpu) return std::make_unique<GpuSpriteClassifier>(gl, sprite);
    return makeClassifier(std::move(sprite), method);
}

std::unique_ptr<Classifier> makeClassifier(Sprite sprite, Method method) {
    if (method == Method::Sprite) return std::make_unique<SpriteClassifier>(std::move(sprite));
    if (method == Method::SpriteGpu)
        return std::make_unique<OwnContext>([&](const GlContext& gl) { return makeClassifier(gl, std::move(sprite), method); });
    throw InvalidArgument(std::string("method '") + enumName(method) +
                          "' is built from the mesh, not from a sprite (sprite methods: sprite, sprite-gpu)");
}

BakeMethod chooseBakeMethod(std::string* why) {
    std::string reason;
    if (!glAvailable(&reason)) {
        if (why) *why = "bake method auto: cpu, because no GL is available (" + reason + ")";
        return BakeMethod::Cpu;
    }
    const CurrentContext restore;
    const GlContext gl;
    return chooseBakeMethod(gl, why);
}

Sprite bake(MeshView mesh, const BakeOptions& options) {
    if (options.method == BakeMethod::Cpu) return bakeCpu(mesh, options);
    if (options.method == BakeMethod::Auto && !glAvailable()) return bakeCpu(mesh, options);
    const CurrentContext restore;
    const GlContext gl;
    return bakeOnGl(gl, mesh, options);
}

Sprite bake(const GlContext& gl, MeshView mesh, const BakeOptions& options) { return bakeOnGl(gl, mesh, options); }

} // namespace vds
