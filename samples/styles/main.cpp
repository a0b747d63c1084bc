// Sample: one model in three styles at once, each bound to a region of space
// by a solid (Trapp & Doellner 2008, Figure 3): the back of Spot in
// blueprint (silhouettes and grid lines), a sphere over the body in X-ray,
// the rest Gouraud-shaded.
//
//   vds_styles -o out.png [--with vds|slicemap|slicemap-local|solid|exact] [--size N] [--resolution N] [--data DIR]
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

#include <vds/eval/image.h>
#include <vds/gl/context.h>

#include "scene.h"

namespace {

struct Options {
    std::string output, with = "vds", data = VDS_SAMPLES_DATA;
    std::uint32_t size = 384, resolution = 256;
};

int run(const Options& o) {
    const vds::samples::Scene scene = vds::samples::stylesScene(o.data);
    vds::GlContext gl;
    vds::samples::SceneRenderer renderer(gl, scene, vds::samples::parseLookup(o.with), {o.resolution, false});
    vds::eval::writePng(renderer.render(o.size), o.output);
    std::printf("wrote %s: %ux%u, three styles with %s\n", o.output.c_str(), o.size, o.size, o.with.c_str());
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app("Renders Spot in three styles bound to solids: blueprint, X-ray and Gouraud.", "vds_styles");
    app.get_formatter()->label("Usage", "usage");
    app.option_defaults()->always_capture_default();
    app.add_option("-o,--output", o.output, "the picture")->required()->type_name("OUT.png");
    app.add_option("--with", o.with, "inside test in the shader")
        ->check(CLI::IsMember({"vds", "slicemap", "slicemap-local", "solid", "exact"}));
    app.add_option("--size", o.size, "image width and height in pixels")->check(CLI::Range(16u, 8192u));
    app.add_option("--resolution", o.resolution, "texels or cells along a solid's longest side")
        ->check(CLI::Range(8u, 2048u));
    app.add_option("--data", o.data, "folder with spot.obj and lens.obj")->type_name("DIR");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e); // --help
        std::fprintf(stderr, "vds_styles: %s (try 'vds_styles --help')\n", e.what());
        return 2;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_styles: error: %s\n", e.what());
        return 1;
    }
}
