// Sample: a pixel-exact cross-section from coarse bands. A slice through a
// mesh, one point a pixel, labelled twice at the same coarse resolution:
// left by the sprite on the GPU (sprite-gpu: wrong within a texel of the
// surface, drawn red where it is), right by certified-gpu (the bands in a
// compute shader, the few unsure pixels answered by the exact classifier:
// every pixel exact). Writes a PNG and says how many pixels each got wrong.
//
//   vds_exact_slice MESH -o out.png [--resolution 32] [--size 400] [--axis x|y|z] [--at 0.5]
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <vds/all.h>
#include <vds/error.h>
#include <vds/eval/image.h>
#include <vds/gl/certified.h>

namespace {

struct Options {
    std::string mesh, output;
    std::uint32_t resolution = 32, size = 400;
    vds::Axis axis = vds::Axis::Z;
    float at = 0.5f; ///< where the slice cuts the box along `axis`, 0..1
};

// The slice's pixel centres, row by row from the top: the two other axes
// across the box, `axis` at `at` of the box's extent.
std::vector<glm::vec3> slicePoints(const vds::Box& box, const Options& o) {
    const glm::ivec3 p = vds::axisPermutation(o.axis);
    std::vector<glm::vec3> points;
    for (std::uint32_t y = 0; y < o.size; ++y)
        for (std::uint32_t x = 0; x < o.size; ++x) {
            glm::vec3 q;
            q[p.x] = box.lo[p.x] + (float(x) + 0.5f) / float(o.size) * (box.hi[p.x] - box.lo[p.x]);
            q[p.y] = box.hi[p.y] - (float(y) + 0.5f) / float(o.size) * (box.hi[p.y] - box.lo[p.y]);
            q[p.z] = box.lo[p.z] + o.at * (box.hi[p.z] - box.lo[p.z]);
            points.push_back(q);
        }
    return points;
}

void paint(vds::eval::Image& image, std::uint32_t x, std::uint32_t y, bool inside, bool wrong) {
    std::uint8_t* px = image.at(x, y);
    const std::uint8_t colour[4] = {std::uint8_t(wrong ? 220 : inside ? 40 : 245),
                                    std::uint8_t(wrong ? 30 : inside ? 70 : 245),
                                    std::uint8_t(wrong ? 30 : inside ? 140 : 245), 255};
    std::copy(colour, colour + 4, px);
}

int run(const Options& o) {
    const vds::TriangleMesh mesh = vds::loadMesh(o.mesh);
    const vds::GlContext gl;
    vds::MethodOptions mo;
    mo.resolution = o.resolution;
    mo.axis = o.axis;
    const auto sprite = vds::makeClassifier(gl, mesh, vds::Method::SpriteGpu, mo);
    const auto certified = vds::makeClassifier(gl, mesh, vds::Method::CertifiedGpu, mo);
    const auto exact = vds::makeClassifier(mesh, vds::Method::Exact, mo);
    const std::vector<glm::vec3> points = slicePoints(vds::meshBounds(mesh), o);
    std::vector<std::uint8_t> bySprite(points.size()), byCertified(points.size()), truth(points.size());
    vds::ClassifyStats stats;
    vds::ClassifyOptions withStats;
    withStats.stats = &stats;
    sprite->classify(points, bySprite.data());
    certified->classify(points, byCertified.data(), withStats);
    exact->classify(points, truth.data());
    vds::eval::Image image(2 * o.size, o.size);
    std::size_t spriteWrong = 0, certifiedWrong = 0;
    for (std::uint32_t y = 0; y < o.size; ++y)
        for (std::uint32_t x = 0; x < o.size; ++x) {
            const std::size_t k = std::size_t(y) * o.size + x;
            spriteWrong += bySprite[k] != truth[k];
            certifiedWrong += byCertified[k] != truth[k];
            paint(image, x, y, bySprite[k], bySprite[k] != truth[k]);
            paint(image, o.size + x, y, byCertified[k], byCertified[k] != truth[k]);
        }
    vds::eval::writePng(image, o.output);
    std::printf("wrote %s: %zu pixels at %u texels; sprite-gpu wrong on %zu, certified-gpu on %zu "
                "(%zu answered from the bands on the GPU, %zu by the exact classifier)\n",
                o.output.c_str(), points.size(), o.resolution, spriteWrong, certifiedWrong, stats.certain, stats.exact);
    return certifiedWrong == 0 ? 0 : 1;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app("a pixel-exact cross-section from coarse bands, beside the sprite's");
    Options o;
    app.add_option("MESH", o.mesh, "a closed mesh")->required();
    app.add_option("-o,--output", o.output, "the PNG written")->required();
    app.add_option("--resolution", o.resolution, "texels on the box's longest side, both methods")
        ->check(CLI::Range(1u, vds::kMaxResolution))
        ->capture_default_str();
    app.add_option("--size", o.size, "pixels a side of each panel")->check(CLI::Range(1u, 4096u))->capture_default_str();
    std::string axis = "z";
    app.add_option("--axis", axis, "the slice's normal, also the bands' and the sprite's axis")
        ->check(CLI::IsMember({"x", "y", "z"}))
        ->capture_default_str();
    app.add_option("--at", o.at, "where along the axis, 0..1 of the box")
        ->check(CLI::Range(0.0f, 1.0f))
        ->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    try {
        o.axis = vds::parseEnum<vds::Axis>(axis);
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_exact_slice: %s\n", e.what());
        return 1;
    }
}
