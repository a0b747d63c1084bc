// Sample: an animated solid clipping a mesh. A blob whose vertices move every
// frame (a sphere breathing and twisting) is re-baked every frame with its
// topology validated once (vds::Baker: updateVertices, rebake), and cuts
// Spot pixel-precisely through shaders/vds/styles.glsl; each frame is
// written as a PNG, with the re-bake's time.
//
//   vds_animate -o PREFIX [--frames N] [--resolution N] [--size N] [--method auto|cpu|lists|peel]
//               [--with vds|exact]
//   writes PREFIX000.png, PREFIX001.png, ...; --with exact renders each
//   frame with the exact classifier of the moved mesh instead (the reference).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <vds/error.h>
#include <vds/eval/image.h>
#include <vds/gl/baker.h>
#include <vds/gl/context.h>

#include "scene.h"

namespace {

struct Options {
    std::string prefix, method = "auto", with = "vds";
    std::uint32_t frames = 8, resolution = 256, size = 400;
};

// The blob at time t in [0, 1): the sphere's vertices moved along their
// radius by a travelling wave and twisted about y.
std::vector<glm::vec3> blob(const std::vector<glm::vec3>& rest, const glm::vec3& centre, float t) {
    std::vector<glm::vec3> out(rest.size());
    const float phase = 6.2831853f * t;
    for (std::size_t v = 0; v < rest.size(); ++v) {
        const glm::vec3 d = rest[v] - centre;
        const float wave = 1.0f + 0.25f * std::sin(3.0f * std::atan2(d.z, d.x) + phase) * std::cos(4.0f * d.y + phase);
        const float twist = 0.8f * std::sin(phase) * d.y;
        const glm::vec3 r = wave * d;
        out[v] = centre + glm::vec3(std::cos(twist) * r.x - std::sin(twist) * r.z, r.y,
                                    std::sin(twist) * r.x + std::cos(twist) * r.z);
    }
    return out;
}

int run(const Options& o) {
    const glm::vec3 centre(0.0f, 0.3f, 0.1f);
    vds::samples::Scene scene = vds::samples::clipScene(VDS_SAMPLES_DATA, vds::samples::Combine::Union);
    scene.name = "animate";
    const vds::TriangleMesh rest = vds::samples::uvSphere(centre, 0.42f, 32);
    scene.solids.resize(1);
    scene.solids[0] = {"blob", rest, {}, glm::mat4(1.0f), vds::samples::Role::ClipAway, vds::samples::Style::Shaded};

    vds::GlContext gl;
    vds::BakeOptions options;
    options.resolution = o.resolution;
    options.method = vds::parseBakeMethod(o.method);
    vds::BakeTimings timings;
    options.timings = &timings;
    vds::Baker baker(gl, rest, options); // validated, its axis chosen: once
    vds::samples::SceneRenderer renderer(gl, scene, vds::samples::Lookup::Vds, {o.resolution, false});
    for (std::uint32_t frame = 0; frame < o.frames; ++frame) {
        const std::vector<glm::vec3> moved = blob(rest.positions, centre, float(frame) / float(o.frames));
        char name[32];
        std::snprintf(name, sizeof name, "%03u.png", frame);
        if (o.with == "exact") {
            scene.solids[0].mesh.positions = moved;
            vds::samples::SceneRenderer exact(gl, scene, vds::samples::Lookup::Exact);
            vds::eval::writePng(exact.render(o.size), o.prefix + name);
            std::printf("frame %u: exact, wrote %s%s\n", frame, o.prefix.c_str(), name);
            continue;
        }
        baker.updateVertices(moved);
        const vds::Sprite sprite = baker.rebake();
        renderer.replaceSprite(0, sprite);
        vds::eval::writePng(renderer.render(o.size), o.prefix + name);
        std::printf("frame %u: re-baked %ux%ux%u in %.2f ms (GPU %.2f ms), wrote %s%s\n", frame, sprite.width(),
                    sprite.height(), sprite.depthComplexity, 1e3 * timings.wallSeconds, 1e3 * timings.gpuSeconds(),
                    o.prefix.c_str(), name);
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app("Renders Spot clipped by a deforming blob, re-baked every frame (vds::Baker).", "vds_animate");
    app.get_formatter()->label("Usage", "usage");
    app.option_defaults()->always_capture_default();
    app.add_option("-o,--output", o.prefix, "prefix of the pictures (PREFIX000.png, ...)")->required()->type_name("PREFIX");
    app.add_option("--frames", o.frames, "frames")->check(CLI::Range(1u, 1000u));
    app.add_option("--resolution", o.resolution, "texels along the blob's longest side")->check(CLI::Range(8u, 2048u));
    app.add_option("--size", o.size, "image width and height in pixels")->check(CLI::Range(16u, 8192u));
    app.add_option("--method", o.method, "bake method")->check(CLI::IsMember({"auto", "cpu", "lists", "peel"}));
    app.add_option("--with", o.with, "inside test: the re-baked VDS, or the exact classifier of the moved mesh")
        ->check(CLI::IsMember({"vds", "exact"}));
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e); // --help
        std::fprintf(stderr, "vds_animate: %s (try 'vds_animate --help')\n", e.what());
        return 2;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_animate: error: %s\n", e.what());
        return 1;
    }
}
