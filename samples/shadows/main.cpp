// Sample: shadows of semi-transparent casters on a ground plane, from a
// voxel grid or a volumetric depth sprite built along the light, offscreen
// to a PNG (see docs/voxel-applications.md).
//
//   vds_shadows -o out.png [--method slicemap|slicemap-local|absorption|sprite|exact-surfaces|exact-thickness]
//               [--mesh FILE] [--size N] [--resolution R] [--sigma S] [--extinction K] [--absorption A]
//               [--light X Y Z]
//   (vds_shadows --help lists the defaults)
//
// The ground y = 0 is seen from straight above; the casters (a built-in
// scene, or MESH fitted into it) float above it, drawn as a light blue tint
// where they cover the ground. The methods:
//  - slicemap, slicemap-local: transmittance shadow map (Eisemann & Décoret
//    2006, section 3.1), (1 - sigma)^n for n occupied slices in front;
//  - absorption: per-voxel absorption of the geometry-shader voxelization
//    (Chang et al. 2014, section 4), exp(-sum of fragment counts * A);
//  - sprite: a VDS baked along the light, exp(-K * path length inside);
//  - exact-surfaces, exact-thickness: the CPU references by ray-mesh
//    intersection, for (1 - sigma)^n and exp(-K * length).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/error.h>
#include <vds/eval/image.h>
#include <vds/gl/context.h>
#include <vds/mesh_io.h>
#include <vds/voxel/transmittance.h>

#include "shapes.h"

namespace {

struct Options {
    std::string output, mesh, method = "slicemap";
    std::uint32_t size = 256, resolution = 128;
    float sigma = 0.3f, extinction = 1.5f, absorption = 0.15f;
    std::vector<float> light{0.35f, -1.0f, 0.25f};
};

using vds::samples::addSphere;

void addBox(vds::TriangleMesh& m, const glm::vec3& lo, const glm::vec3& hi) {
    const std::uint32_t b = std::uint32_t(m.positions.size());
    for (int k = 0; k < 8; ++k)
        m.positions.push_back({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
    const std::uint32_t faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    for (const auto& f : faces) m.triangles.push_back({b + f[0], b + f[1], b + f[2]});
}

// The built-in casters: a "tree crown" of 40 small overlapping spheres (many
// surfaces, dense in the middle), a hollow shell (4 surfaces), a solid
// sphere and a slab (2 each).
vds::TriangleMesh builtInScene() {
    vds::TriangleMesh m;
    std::uint32_t state = 12345u;
    const auto next = [&] { state = state * 1664525u + 1013904223u; return float(state >> 8) / float(1u << 24); };
    for (int k = 0; k < 40;) {
        const glm::vec3 p(2 * next() - 1, 2 * next() - 1, 2 * next() - 1);
        if (glm::length(p) > 1.0f) continue;
        addSphere(m, glm::vec3(-0.9f, 1.5f, -0.7f) + 0.55f * p, 0.16f, 12);
        ++k;
    }
    addSphere(m, {0.9f, 1.3f, -0.6f}, 0.5f, 32);
    addSphere(m, {0.9f, 1.3f, -0.6f}, 0.3f, 32, true);
    addSphere(m, {0.8f, 1.1f, 0.9f}, 0.4f, 32);
    addBox(m, {-1.1f, 0.9f, 0.5f}, {-0.2f, 1.0f, 1.3f});
    return m;
}

// MESH scaled uniformly into the box the built-in scene fills.
vds::TriangleMesh fitted(vds::TriangleMesh m) {
    const vds::Box b = vds::meshBounds(m);
    const glm::vec3 centre = 0.5f * (b.lo + b.hi), extent = b.hi - b.lo;
    const float scale = 2.4f / std::max({extent.x, extent.y, extent.z});
    for (auto& p : m.positions) p = (p - centre) * scale + glm::vec3(0.0f, 1.5f, 0.0f);
    return m;
}

double millisecondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

int run(const Options& o) {
    using namespace vds::voxel;
    const vds::TriangleMesh world = o.mesh.empty() ? builtInScene() : fitted(vds::loadMesh(o.mesh));
    const LightFrame frame = makeLightFrame({o.light[0], o.light[1], o.light[2]});
    const vds::TriangleMesh light = toLightSpace(world, frame);
    const vds::Box bounds = vds::meshBounds(light);

    ReceiverPlane plane;
    plane.origin = {-2.2f, 0.0f, -2.2f};
    plane.u = {4.4f, 0.0f, 0.0f};
    plane.v = {0.0f, 0.0f, 4.4f};
    plane.width = plane.height = o.size;
    TransmittanceParameters params;
    params.sigma = o.sigma;
    params.extinction = o.extinction;

    vds::GlContext gl;
    TransmittanceImage image;
    std::string built;
    const auto start = std::chrono::steady_clock::now();
    if (o.method == "slicemap" || o.method == "slicemap-local") {
        SlicemapOptions so;
        so.slicing = o.method == "slicemap" ? Slicing::Uniform : Slicing::Local;
        const Slicemap map = buildSlicemap(gl, light, bounds, o.resolution, so);
        const double buildMs = millisecondsSince(start);
        const GpuTransmittanceCaster caster(map);
        image = renderTransmittance(gl, caster, frame, plane, params);
        built = std::to_string(map.grid.dims.x) + "x" + std::to_string(map.grid.dims.y) + "x" +
                std::to_string(map.slices()) + " slicemap pair, " + std::to_string(caster.gpuBytes() / 1024) +
                " KiB, built in " + std::to_string(buildMs) + " ms";
    } else if (o.method == "absorption") {
        SlicingOptions so;
        so.absorptionPerFragment = o.absorption;
        const SlicedVoxels voxels = voxelizeSlices(gl, light, makeVoxelGrid(bounds, o.resolution), so);
        const double buildMs = millisecondsSince(start);
        const GpuTransmittanceCaster caster(voxels);
        image = renderTransmittance(gl, caster, frame, plane, params);
        built = std::to_string(voxels.grid.dims.x) + "x" + std::to_string(voxels.grid.dims.y) + "x" +
                std::to_string(voxels.grid.dims.z) + " voxels, " + std::to_string(caster.gpuBytes() / 1024) +
                " KiB, built in " + std::to_string(buildMs) + " ms";
    } else if (o.method == "sprite") {
        vds::BakeOptions bo;
        bo.resolution = o.resolution;
        bo.axis = vds::Axis::Z;
        const vds::Sprite sprite = vds::bake(gl, light, bo);
        if (sprite.status != vds::SolidStatus::Closed)
            std::fprintf(stderr, "%s: warning: the mesh is not a closed solid; lengths inside it are not defined (%s)\n",
                         "vds_shadows", sprite.validation.c_str());
        const double buildMs = millisecondsSince(start);
        const GpuTransmittanceCaster caster(sprite);
        image = renderTransmittance(gl, caster, frame, plane, params);
        built = std::to_string(sprite.width()) + "x" + std::to_string(sprite.height()) + "x" +
                std::to_string(sprite.depthComplexity) + " sprite, " + std::to_string(caster.gpuBytes() / 1024) +
                " KiB, built in " + std::to_string(buildMs) + " ms";
    } else {
        const bool surfaces = o.method == "exact-surfaces";
        image = transmittanceOnCpu(plane, frame,
                                   surfaces ? TransmittanceSource::SlicemapSurfaces : TransmittanceSource::SpriteThickness,
                                   params, [&](const glm::vec3& p) {
                                       const ExactCrossings c = exactCrossingsInFront(light, p);
                                       return surfaces ? double(c.surfaces) : c.thickness;
                                   });
        built = "exact ray-mesh crossings on the CPU, " + std::to_string(millisecondsSince(start)) + " ms";
    }

    // The casters seen from above, to tint the ground where they cover it.
    const LightFrame down = makeLightFrame({0.0f, -1.0f, 0.0f});
    const vds::TriangleMesh fromAbove = toLightSpace(world, down);

    vds::eval::Image png(o.size, o.size);
    for (std::uint32_t j = 0; j < o.size; ++j)
        for (std::uint32_t i = 0; i < o.size; ++i) {
            const float t = image.transmittance[std::size_t(j) * o.size + i];
            const glm::vec3 p = plane.point(i, j);
            const bool checker = (int(std::floor(p.x * 2.5f)) + int(std::floor(p.z * 2.5f))) & 1;
            glm::vec3 c = (checker ? glm::vec3(0.93f, 0.90f, 0.82f) : glm::vec3(0.84f, 0.80f, 0.72f)) *
                          (0.25f + 0.75f * t);
            if (exactCrossingsInFront(fromAbove, down.toLightSpace(p)).surfaces > 0)
                c = 0.75f * c + 0.25f * glm::vec3(0.35f, 0.55f, 0.95f);
            std::uint8_t* px = png.at(i, o.size - 1 - j); // PNG rows run top to bottom
            for (int k = 0; k < 3; ++k) px[k] = std::uint8_t(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
            px[3] = 255;
        }
    vds::eval::writePng(png, o.output);
    std::printf("wrote %s: %ux%u, %s, %zu triangles; %s; shading %.3f ms (GL_TIME_ELAPSED), %.3f ms to glFinish, GL %s\n",
                o.output.c_str(), o.size, o.size, o.method.c_str(), world.triangles.size(), built.c_str(),
                image.gpuMilliseconds, image.wallMilliseconds, gl.info().renderer.c_str());
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app("Renders the shadows of semi-transparent casters on a ground plane, seen from above, from a\n"
                 "slicemap, per-voxel absorption or a volumetric depth sprite built along the light.",
                 "vds_shadows");
    app.get_formatter()->label("Usage", "usage");
    app.option_defaults()->always_capture_default();
    app.add_option("-o,--output", o.output, "the picture")->required()->type_name("OUT.png");
    app.add_option("--method", o.method, "how the light left is computed")
        ->check(CLI::IsMember({"slicemap", "slicemap-local", "absorption", "sprite", "exact-surfaces", "exact-thickness"}));
    app.add_option("--mesh", o.mesh, "closed casters instead of the built-in scene (OBJ, PLY, STL, OFF)")
        ->type_name("MESH");
    app.add_option("--size", o.size, "image width and height in pixels")->check(CLI::Range(16u, 4096u));
    app.add_option("--resolution", o.resolution, "columns (texels) along the longer side across the light")
        ->check(CLI::Range(8u, 1024u));
    app.add_option("--sigma", o.sigma, "attenuation per surface (slicemap, exact-surfaces)")->check(CLI::Range(0.0f, 1.0f));
    app.add_option("--extinction", o.extinction, "per unit of length inside (sprite, exact-thickness)")
        ->check(CLI::Range(0.0f, 1000.0f));
    app.add_option("--absorption", o.absorption, "absorption per fragment (absorption)")->check(CLI::Range(0.0f, 1000.0f));
    app.add_option("--light", o.light, "direction the light travels")->expected(3)->type_name("X Y Z");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e); // --help
        std::fprintf(stderr, "vds_shadows: %s (try 'vds_shadows --help')\n", e.what());
        return 2;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_shadows: error: %s\n", e.what());
        return 1;
    }
}
