// Sample: refraction through closed solids in front of a checkerboard, from
// a local slicemap pair or a VDS (two-surface, Eisemann & Décoret 2006 /
// Wyman 2005), by marching voxels with per-voxel normals (multiple-surface,
// Chang et al. 2014), or exactly by ray tracing the mesh; offscreen to PNG
// (see docs/voxel-applications.md).
//
//   vds_refraction -o out.png [--method slicemap|sprite|voxels|exact] [--mesh FILE] [--size N]
//                  [--resolution R] [--eta E] [--absorption A] [--frost F] [--view X Y Z]
//   (vds_refraction --help lists the defaults)
//
// The camera is orthographic, looking along --view; the checkerboard stands
// behind the solids, across the view. --frost > 0 blurs it more the longer
// a ray travelled inside (frosted glass).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/gtc/constants.hpp>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/error.h>
#include <vds/eval/image.h>
#include <vds/gl/context.h>
#include <vds/mesh_io.h>
#include <vds/voxel/refraction.h>
#include <vds/voxel/light_frame.h>

#include "shapes.h"

namespace {

struct Options {
    std::string output, mesh, method = "sprite";
    std::uint32_t size = 256, resolution = 128;
    float eta = 1.33f, absorption = 0.8f, frost = 0.0f;
    std::vector<float> view{0.25f, -0.35f, 1.0f};
};

// A closed torus around the y axis, outward facing.
void addTorus(vds::TriangleMesh& m, const glm::vec3& centre, float major, float minor, std::uint32_t segments) {
    const std::uint32_t base = std::uint32_t(m.positions.size()), around = segments, tube = segments / 2;
    const float pi = glm::pi<float>();
    for (std::uint32_t i = 0; i < around; ++i)
        for (std::uint32_t j = 0; j < tube; ++j) {
            const float u = 2 * pi * float(i) / float(around), v = 2 * pi * float(j) / float(tube);
            const float r = major + minor * std::cos(v);
            m.positions.push_back(centre + glm::vec3(r * std::cos(u), minor * std::sin(v), r * std::sin(u)));
        }
    const auto at = [&](std::uint32_t i, std::uint32_t j) { return base + (i % around) * tube + j % tube; };
    for (std::uint32_t i = 0; i < around; ++i)
        for (std::uint32_t j = 0; j < tube; ++j) {
            m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j)});
            m.triangles.push_back({at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)});
        }
}

using vds::samples::addSphere;

// A sphere, and a torus tilted to the view (concave: rays cross it up to
// four times).
vds::TriangleMesh builtInScene() {
    vds::TriangleMesh m;
    addSphere(m, {-0.55f, 0.1f, 0.0f}, 0.45f, 64);
    addTorus(m, {0.55f, -0.1f, 0.0f}, 0.36f, 0.16f, 64);
    return m;
}

double millisecondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

int run(const Options& o) {
    using namespace vds::voxel;
    const vds::TriangleMesh world = o.mesh.empty() ? builtInScene() : vds::loadMesh(o.mesh);
    const LightFrame frame = makeLightFrame({o.view[0], o.view[1], o.view[2]});
    const vds::TriangleMesh mesh = toLightSpace(world, frame);
    const vds::Box box = vds::meshBounds(mesh);
    const glm::vec3 extent = box.hi - box.lo;
    const float side = 1.15f * std::max(extent.x, extent.y);
    const glm::vec2 centre = 0.5f * (glm::vec2(box.lo) + glm::vec2(box.hi));

    RefractionView view;
    view.lo = centre - 0.5f * side;
    view.hi = centre + 0.5f * side;
    view.width = view.height = o.size;
    view.startZ = box.lo.z - 0.1f * extent.z;
    view.backgroundZ = box.hi.z + 0.75f * side;
    RefractionParameters params;
    params.eta = o.eta;
    params.absorption = o.absorption / side; // per scene size, so --absorption reads the same for any mesh
    params.frost = o.frost;
    params.checker = side / 12.0f;

    vds::GlContext gl;
    RefractionImage image;
    std::string built;
    const auto start = std::chrono::steady_clock::now();
    if (o.method == "slicemap") {
        SlicemapOptions so;
        so.slicing = Slicing::Local;
        const Slicemap map = buildSlicemap(gl, mesh, box, o.resolution, so);
        built = "local slicemap pair " + std::to_string(map.grid.dims.x) + "x" + std::to_string(map.grid.dims.y) + "x" +
                std::to_string(map.slices()) + ", built in " + std::to_string(millisecondsSince(start)) + " ms";
        image = renderRefraction(gl, GpuRefractionCaster(map), view, params);
    } else if (o.method == "sprite") {
        vds::BakeOptions bo;
        bo.resolution = o.resolution;
        bo.axis = vds::Axis::Z;
        const vds::Sprite sprite = vds::bake(gl, mesh, bo);
        if (sprite.status != vds::SolidStatus::Closed)
            std::fprintf(stderr, "%s: warning: the mesh is not a closed solid; lengths inside it are not defined (%s)\n",
                         "vds_refraction", sprite.validation.c_str());
        built = "sprite " + std::to_string(sprite.width()) + "x" + std::to_string(sprite.height()) + "x" +
                std::to_string(sprite.depthComplexity) + ", built in " + std::to_string(millisecondsSince(start)) + " ms";
        image = renderRefraction(gl, GpuRefractionCaster(sprite), view, params);
    } else if (o.method == "voxels") {
        const SlicedVoxels voxels = voxelizeSlices(gl, mesh, makeVoxelGrid(box, o.resolution));
        built = "voxels " + std::to_string(voxels.grid.dims.x) + "x" + std::to_string(voxels.grid.dims.y) + "x" +
                std::to_string(voxels.grid.dims.z) + ", built in " + std::to_string(millisecondsSince(start)) + " ms";
        image = renderRefraction(gl, GpuRefractionCaster(voxels), view, params);
    } else {
        image = refractExactly(mesh, view, params);
        built = "exact ray tracing on the CPU, " + std::to_string(millisecondsSince(start)) + " ms";
    }

    vds::eval::Image png(o.size, o.size);
    const std::size_t row = std::size_t(o.size) * 4;
    for (std::uint32_t y = 0; y < o.size; ++y) // bottom-up rows to PNG's top-down
        std::copy_n(&image.rgba[(o.size - 1 - y) * row], row, png.at(0, y));
    vds::eval::writePng(png, o.output);
    std::printf("wrote %s: %ux%u, %s, %zu triangles; %s; shading %.3f ms (GL_TIME_ELAPSED), %.3f ms to glFinish, GL %s\n",
                o.output.c_str(), o.size, o.size, o.method.c_str(), world.triangles.size(), built.c_str(),
                image.gpuMilliseconds, image.wallMilliseconds, gl.info().renderer.c_str());
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app("Renders closed solids as refracting glass in front of a checkerboard, from a local slicemap\n"
                 "pair, a volumetric depth sprite, per-voxel normals, or exactly.",
                 "vds_refraction");
    app.get_formatter()->label("Usage", "usage");
    app.option_defaults()->always_capture_default();
    app.add_option("-o,--output", o.output, "the picture")->required()->type_name("OUT.png");
    app.add_option("--method", o.method, "representation the rays are traced through")
        ->check(CLI::IsMember({"slicemap", "sprite", "voxels", "exact"}));
    app.add_option("--mesh", o.mesh, "closed solids instead of the built-in scene (OBJ, PLY, STL, OFF)")
        ->type_name("MESH");
    app.add_option("--size", o.size, "image width and height in pixels")->check(CLI::Range(16u, 4096u));
    app.add_option("--resolution", o.resolution, "columns (texels, cells) along the longest side")
        ->check(CLI::Range(8u, 1024u));
    app.add_option("--eta", o.eta, "refractive index inside")->check(CLI::Range(1.0f, 4.0f));
    app.add_option("--absorption", o.absorption, "absorption per scene size of length inside")
        ->check(CLI::Range(0.0f, 100.0f));
    app.add_option("--frost", o.frost, "background blur per unit of length inside (frosted glass)")
        ->check(CLI::Range(0.0f, 100.0f));
    app.add_option("--view", o.view, "direction the camera looks")->expected(3)->type_name("X Y Z");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e); // --help
        std::fprintf(stderr, "vds_refraction: %s (try 'vds_refraction --help')\n", e.what());
        return 2;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_refraction: error: %s\n", e.what());
        return 1;
    }
}
