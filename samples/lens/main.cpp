// Sample: a 3D magic lens (Trapp & Doellner 2008, section 4, Figure 2).
// Spot is drawn Gouraud-shaded; inside a spherical lens volume it turns to
// X-ray (or, --style blueprint, edges and grid lines), showing the inner surfaces. The lens moves along a path over the
// cow: each frame is a new placement of the same solid (Sprite::transform on
// the GPU sprite, no re-bake), written as DIR/lens-NN.png.
//
//   vds_lens -o DIR [--frames N] [--style xray|blueprint] [--with vds|slicemap|slicemap-local|solid|exact] [--size N] [--resolution N] [--data DIR]
//            [--soft-edge W]
//
// --soft-edge W (--with vds): the X-ray fades in over W (mesh units of the
// lens) inside the lens's border and a glow fades out over W outside it,
// from the lens's signed distance grid through vdsDistance.
#include <cstdio>
#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include <vds/eval/image.h>
#include <vds/gl/context.h>

#include "scene.h"

namespace {

struct Options {
    std::string output, with = "vds", style = "xray", data = VDS_SAMPLES_DATA;
    std::uint32_t frames = 4, size = 384, resolution = 256;
    float softEdge = 0.0f;
};

int run(const Options& o) {
    vds::samples::Scene scene = vds::samples::lensScene(o.data);
    if (o.style == "blueprint") scene.solids[0].style = vds::samples::Style::Blueprint;
    scene.distanceWidth = o.softEdge;
    std::filesystem::create_directories(o.output);
    vds::GlContext gl;
    vds::samples::SceneRenderer renderer(gl, scene, vds::samples::parseLookup(o.with), {o.resolution, false});
    for (std::uint32_t f = 0; f < o.frames; ++f) {
        const float t = o.frames > 1 ? float(f) / float(o.frames - 1) : 0.0f;
        renderer.place(0, vds::samples::lensPath(t));
        char name[32];
        std::snprintf(name, sizeof name, "lens-%02u.png", f);
        const std::string path = (std::filesystem::path(o.output) / name).string();
        vds::eval::writePng(renderer.render(o.size), path);
        std::printf("wrote %s: lens at t = %.2f, %s\n", path.c_str(), double(t), o.with.c_str());
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app("Renders Spot with a 3D magic lens (X-ray inside a sphere) moved along a path, one PNG a frame.",
                 "vds_lens");
    app.get_formatter()->label("Usage", "usage");
    app.option_defaults()->always_capture_default();
    app.add_option("-o,--output", o.output, "folder for lens-NN.png")->required()->type_name("DIR");
    app.add_option("--frames", o.frames, "frames along the path")->check(CLI::Range(1u, 100u));
    app.add_option("--with", o.with, "inside test in the shader")
        ->check(CLI::IsMember({"vds", "slicemap", "slicemap-local", "solid", "exact"}));
    app.add_option("--style", o.style, "style inside the lens: X-ray or blueprint edges")
        ->check(CLI::IsMember({"xray", "blueprint"}));
    app.add_option("--size", o.size, "image width and height in pixels")->check(CLI::Range(16u, 8192u));
    app.add_option("--resolution", o.resolution, "texels or cells along the lens's longest side")
        ->check(CLI::Range(8u, 2048u));
    app.add_option("--data", o.data, "folder with spot.obj")->type_name("DIR");
    app.add_option("--soft-edge", o.softEdge, "width of the lens's soft edge, from its distance grid (0: a hard edge)")
        ->check(CLI::Range(0.0f, 1e6f))
        ->type_name("W");
    try {
        app.parse(argc, argv);
        if (o.softEdge > 0.0f && o.with != "vds") throw CLI::ValidationError("--soft-edge", "needs --with vds");
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e); // --help
        std::fprintf(stderr, "vds_lens: %s (try 'vds_lens --help')\n", e.what());
        return 2;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_lens: error: %s\n", e.what());
        return 1;
    }
}
