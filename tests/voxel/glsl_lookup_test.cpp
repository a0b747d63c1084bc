// The GLSL lookups (shaders/voxel/solid.glsl, slicemap.glsl) answer exactly
// as the C++ lookups on the same points, including points on cell and slice
// boundaries where rounding decides.
#include <vector>

#include <gtest/gtest.h>

#include "solids.h"
#include <vds/voxel/representation.h>

#include "../support/gl_fixture.h"
#include "points.h"

namespace vds::voxel {
namespace {

class GlslLookupTest : public vds::test::GlTest {};

// Random points, every cell centre of a coarse lattice, and points on the
// grid's cell planes and slice planes (where floor() decides).
std::vector<glm::vec3> probePoints(const Model& model) {
    const VoxelGrid& g = model.slicemap() ? model.slicemap()->grid : model.solid()->grid;
    const Box box = g.box;
    std::vector<glm::vec3> points = vds::test::randomPoints(box, 60000, 0.05f, 11);
    const glm::vec3 size = box.hi - box.lo;
    const float cell = g.cellSize();
    for (std::uint32_t i = 0; i <= g.dims.x; i += 3)
        for (std::uint32_t j = 0; j <= g.dims.y; j += 3)
            for (std::uint32_t k = 0; k <= 64; ++k) {
                const float x = box.lo.x + float(i) * cell, y = box.lo.y + float(j) * cell;
                points.emplace_back(x, y, box.lo.z + size.z * float(k) / 64.0f);
                points.emplace_back(x + 0.5f * cell, y + 0.5f * cell, box.lo.z + size.z * float(k) / 64.0f);
            }
    return points;
}

TEST_F(GlslLookupTest, EveryRepresentationAnswersOnTheGpuAsOnTheCpu) {
    const auto torus = solids::torus({0.1f, 0.2f, 0.3f}, 1.0f, 0.4f, 40);
    const auto shell = solids::shell({0, 0, 0}, 1.0f, 0.8f, 32);
    for (const auto* solid : {&torus, &shell})
        for (Representation r : {Representation::Slicemap, Representation::SlicemapLocal, Representation::Solid,
                                 Representation::SolidCompute}) {
            const Model model = buildModel(gl(), solid->mesh, r, {48});
            const std::vector<glm::vec3> points = probePoints(model);
            std::vector<std::uint8_t> cpu(points.size()), gpu(points.size(), 7);
            model.classify({points.data(), points.size()}, cpu.data());
            GpuModelClassifier(gl(), model).classify(points, gpu.data());
            std::size_t differing = 0, inside = 0;
            for (std::size_t k = 0; k < points.size(); ++k) {
                differing += cpu[k] != gpu[k];
                inside += cpu[k];
            }
            EXPECT_EQ(differing, 0u) << toString(r);
            EXPECT_GT(inside, points.size() / 20) << toString(r);
        }
}

TEST_F(GlslLookupTest, ManySlicesUseEveryTargetLayer) {
    const auto torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 32);
    ModelOptions options;
    options.resolution = 32;
    options.slices = 1024;
    for (Representation r : {Representation::Slicemap, Representation::SlicemapLocal}) {
        const Model model = buildModel(gl(), torus.mesh, r, options);
        ASSERT_EQ(model.slicemap()->renderTargets, 8u);
        const std::vector<glm::vec3> points = probePoints(model);
        std::vector<std::uint8_t> cpu(points.size()), gpu(points.size(), 7);
        model.classify(points, cpu.data(), {Rule::Parity, 1});
        GpuModelClassifier(gl(), model).classify(points, gpu.data());
        EXPECT_EQ(cpu, gpu) << toString(r);
    }
}

} // namespace
} // namespace vds::voxel
