// The GL rule (<vds/gl/context.h>) in vds::voxel: every entry point given a
// context leaves the caller's current context current, and a caster made
// in one context is refused by a render in another, in one line.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <vds/bake.h>
#include <vds/error.h>
#include <vds/voxel/refraction.h>
#include <vds/voxel/representation.h>
#include <vds/voxel/slicemap.h>
#include <vds/voxel/slicing.h>
#include <vds/voxel/solid.h>
#include <vds/voxel/surface.h>
#include <vds/voxel/transmittance.h>
#include "solids.h"

#include "../support/gl_fixture.h"

namespace vds::voxel {
namespace {

using VoxelContextTest = test::GlTest;

TEST_F(VoxelContextTest, EveryEntryPointLeavesTheCallersContextCurrent) {
    const TriangleMesh mesh = solids::sphere({0.0f, 0.0f, 0.0f}, 0.8f, 24).mesh;
    const Box box = meshBounds(mesh);
    const VoxelGrid grid = makeVoxelGrid(box, 24);
    BakeOptions bo;
    bo.resolution = 32;
    bo.method = BakeMethod::Cpu;
    const Sprite sprite = bakeCpu(mesh, bo);

    const GlContext callers; // current on creation: the caller's context
    auto stays = [&](const char* what) { EXPECT_TRUE(callers.isCurrent()) << what << " left another context current"; };
    const Slicemap map = buildSlicemap(gl(), mesh, box, 24);
    stays("buildSlicemap");
    SlicemapOptions local;
    local.slicing = Slicing::Local;
    const Slicemap localMap = buildSlicemap(gl(), mesh, box, 24, local);
    stays("buildSlicemap (local)");
    const SlicedVoxels slices = voxelizeSlices(gl(), mesh, grid);
    stays("voxelizeSlices");
    const BitGrid raster = voxelizeSolid(gl(), mesh, grid, SolidMethod::Raster);
    stays("voxelizeSolid (raster)");
    const BitGrid compute = voxelizeSolid(gl(), mesh, grid, SolidMethod::Compute);
    stays("voxelizeSolid (compute)");
    EXPECT_EQ(raster.words, compute.words);
    voxelizeSurface(gl(), mesh, grid);
    stays("voxelizeSurface");
    Model model = buildModel(gl(), mesh, Representation::Solid);
    stays("buildModel");
    {
        GpuModelClassifier classifier(gl(), std::move(model));
        stays("GpuModelClassifier");
        const std::vector<glm::vec3> points{{0.0f, 0.0f, 0.0f}, {2.0f, 0.0f, 0.0f}};
        std::uint8_t labels[2] = {7, 7};
        classifier.classify(points, labels);
        stays("GpuModelClassifier::classify");
        EXPECT_EQ(labels[0], 1);
        EXPECT_EQ(labels[1], 0);
    }
    stays("~GpuModelClassifier");

    ReceiverPlane plane;
    plane.origin = {-1.0f, -1.0f, -2.0f};
    plane.u = {2.0f, 0.0f, 0.0f};
    plane.v = {0.0f, 2.0f, 0.0f};
    plane.width = plane.height = 16;
    const LightFrame frame = makeLightFrame({0.0f, 0.0f, -1.0f});
    for (const GpuTransmittanceCaster& caster :
         {GpuTransmittanceCaster(gl(), map), GpuTransmittanceCaster(gl(), slices), GpuTransmittanceCaster(gl(), sprite)}) {
        stays("GpuTransmittanceCaster");
        renderTransmittance(gl(), caster, frame, plane, {});
        stays("renderTransmittance");
    }
    RefractionView view;
    view.lo = {-1.0f, -1.0f};
    view.hi = {1.0f, 1.0f};
    view.width = view.height = 16;
    view.startZ = -2.0f;
    view.backgroundZ = 2.0f;
    for (const GpuRefractionCaster& caster :
         {GpuRefractionCaster(gl(), localMap), GpuRefractionCaster(gl(), sprite), GpuRefractionCaster(gl(), slices)}) {
        stays("GpuRefractionCaster");
        renderRefraction(gl(), caster, view, {});
        stays("renderRefraction");
    }

    // A caster of the caller's context, rendered on another: refused.
    const GpuTransmittanceCaster foreign(slices);
    try {
        renderTransmittance(gl(), foreign, frame, plane, {});
        ADD_FAILURE() << "a caster of another context was used";
    } catch (const GlError& e) {
        EXPECT_NE(std::string(e.what()).find("the caster: made in another GL context"), std::string::npos) << e.what();
    }
    stays("the refused render");
}

} // namespace
} // namespace vds::voxel
