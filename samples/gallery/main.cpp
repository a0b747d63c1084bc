// Sample: the renderer's comparison in pictures and numbers. For each scene
// (clip, lens, styles) it renders the exact reference (fragments classified
// by the exact classifier) and the same scene through each representation's
// GLSL lookup, at equal resolution and at equal memory (the voxel grid as
// large as fits in the VDS's bytes), and writes:
//   DIR/SCENE-exact.png, DIR/SCENE-REP-BUDGET.png, DIR/SCENE-REP-BUDGET-diff.png
//   DIR/gallery.json, DIR/gallery.md   differing pixels, GPU frame time, memory
// REP is vds, slicemap, slicemap-local or solid; BUDGET is "res" or "mem"
// (the VDS is the memory yardstick, so it has one row).
//
//   vds_gallery -o DIR [--size N] [--resolution N] [--scenes clip,lens,styles] [--data DIR]
#include <algorithm>
#include <cstdio>
#include <memory>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <vds/atomic_file.h>
#include <vds/error.h>
#include <vds/eval/image.h>
#include <vds/gl/context.h>

#include "scene.h"

namespace {

namespace fs = std::filesystem;
namespace vs = vds::samples;

struct Options {
    std::string output, data = VDS_SAMPLES_DATA;
    std::vector<std::string> scenes{"clip", "lens", "styles"};
    std::uint32_t size = 256, resolution = 128;
    int repeats = 15;
};

vs::Scene makeScene(const std::string& name, const std::string& data) {
    if (name == "clip") return vs::clipScene(data, vs::Combine::Union);
    if (name == "clip-intersection") return vs::clipScene(data, vs::Combine::Intersection);
    if (name == "lens") {
        vs::Scene s = vs::lensScene(data);
        s.solids[0].placement = vs::lensPath(0.5f);
        return s;
    }
    return vs::stylesScene(data);
}

// "lens: vds 64x64x2 texels, 0.03 MiB" -> "vds 64x64x2 texels";
// "lens: slicemap: 32x32x32 slices, ..." -> "32x32x32 slices".
std::string compact(const std::string& solid) {
    std::string s = solid.substr(solid.find(": ") + 2);
    if (s.find(": ") != std::string::npos) s = s.substr(s.find(": ") + 2);
    return s.substr(0, s.find(','));
}

void writeText(const std::string& path, const std::string& text) {
    vds::AtomicFile file(path);
    std::ofstream out(file.path(), std::ios::binary);
    out << text;
    out.close();
    if (!out) throw vds::IoError("cannot write " + path);
    file.commit();
}

struct Entry {
    vs::Lookup lookup;
    bool equalMemory;
    std::unique_ptr<vs::SceneRenderer> renderer;
    std::vector<double> ms;
};

// The fastest of the frames: on a shared machine, the one least disturbed by other work.
double fastest(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

int run(const Options& o) {
    fs::create_directories(o.output);
    vds::GlContext gl;
    nlohmann::json rows = nlohmann::json::array();
    std::string md = "| scene | lookup | budget | first solid | memory | differing pixels | share of covered | "
                     "frame ms (llvmpipe) | frame time / VDS's |\n|---|---|---|---|---|---|---|---|---|\n";
    char line[512];
    for (const std::string& name : o.scenes) {
        const vs::Scene scene = makeScene(name, o.data);
        // The reference first, then every lookup and budget; the VDS is the
        // memory yardstick, so it has one entry.
        std::vector<Entry> entries;
        entries.push_back({vs::Lookup::Exact, false, std::make_unique<vs::SceneRenderer>(gl, scene, vs::Lookup::Exact), {}});
        for (const vs::Lookup lookup : {vs::Lookup::Vds, vs::Lookup::Slicemap, vs::Lookup::SlicemapLocal, vs::Lookup::Solid})
            for (const bool equalMemory : {false, true})
                if (!(lookup == vs::Lookup::Vds && equalMemory))
                    entries.push_back({lookup, equalMemory,
                                       std::make_unique<vs::SceneRenderer>(gl, scene, lookup,
                                                                           vs::RepresentationSize{o.resolution, equalMemory}),
                                       {}});
        std::vector<vds::eval::Image> images;
        for (Entry& e : entries) images.push_back(e.renderer->render(o.size));
        // Frame times interleaved, one frame of each in turn, so a change in
        // the machine's load falls on all of them alike.
        for (int r = 0; r < o.repeats; ++r)
            for (Entry& e : entries) e.ms.push_back(e.renderer->frameMilliseconds(o.size, 1));
        const double vdsMs = fastest(entries[1].ms);

        vds::eval::writePng(images[0], (fs::path(o.output) / (name + "-exact.png")).string());
        const double exactMs = fastest(entries[0].ms);
        std::snprintf(line, sizeof line, "| %s | exact | - | - | - | 0 | 0 %% | %.1f | %.2f |\n", name.c_str(), exactMs,
                      exactMs / vdsMs);
        md += line;
        std::printf("%s", line);
        for (std::size_t k = 1; k < entries.size(); ++k) {
            const Entry& e = entries[k];
            const vds::eval::Image& image = images[k];
            const vs::ImageDifference diff = vs::compareImages(image, images[0]);
            const double ms = fastest(e.ms);
            const std::string budget = e.lookup == vs::Lookup::Vds ? "res+mem" : e.equalMemory ? "mem" : "res";
            const std::string stem = name + "-" + vs::toString(e.lookup) + "-" + (e.equalMemory ? "mem" : "res");
            vds::eval::writePng(image, (fs::path(o.output) / (stem + ".png")).string());
            vds::eval::writePng(diff.picture, (fs::path(o.output) / (stem + "-diff.png")).string());
            const double share = diff.covered ? double(diff.pixels) / double(diff.covered) : 0.0;
            const std::vector<std::string> solids = e.renderer->describe();
            rows.push_back({{"scene", name},
                            {"lookup", vs::toString(e.lookup)},
                            {"budget", budget},
                            {"size", o.size},
                            {"solids", solids},
                            {"memory_bytes", e.renderer->memoryBytes()},
                            {"differing_pixels", diff.pixels},
                            {"covered_pixels", diff.covered},
                            {"differing_share", share},
                            {"max_channel_delta", diff.max},
                            {"mean_channel_delta", diff.mean},
                            {"frame_ms", ms},
                            {"frame_ms_over_vds", ms / vdsMs},
                            {"image", stem + ".png"},
                            {"difference", stem + "-diff.png"}});
            std::snprintf(line, sizeof line, "| %s | %s | %s | %s | %.2f MiB | %zu | %.2f %% | %.1f | %.2f |\n",
                          name.c_str(), vs::toString(e.lookup), budget.c_str(), compact(solids.front()).c_str(),
                          double(e.renderer->memoryBytes()) / 1048576.0, diff.pixels, 100.0 * share, ms, ms / vdsMs);
            md += line;
            std::printf("%s", line);
            std::fflush(stdout);
        }
    }
    nlohmann::json doc = {{"size", o.size},
                          {"resolution", o.resolution},
                          {"renderer", gl.info().renderer},
                          {"difference_threshold", 8},
                          {"rows", rows}};
    writeText((fs::path(o.output) / "gallery.json").string(), doc.dump(2) + "\n");
    writeText((fs::path(o.output) / "gallery.md").string(), md);
    std::printf("wrote %s/gallery.json and gallery.md (GL %s)\n", o.output.c_str(), gl.info().renderer.c_str());
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app("Renders each scene exactly and through the VDS, slicemaps and solid voxels, at equal resolution\n"
                 "and equal memory, and writes the pictures, difference pictures and a table.",
                 "vds_gallery");
    app.get_formatter()->label("Usage", "usage");
    app.option_defaults()->always_capture_default();
    app.add_option("-o,--output", o.output, "folder for the pictures and tables")->required()->type_name("DIR");
    app.add_option("--size", o.size, "image width and height in pixels")->check(CLI::Range(16u, 4096u));
    app.add_option("--resolution", o.resolution, "texels or cells along a solid's longest side")
        ->check(CLI::Range(8u, 1024u));
    app.add_option("--scenes", o.scenes, "scenes to render")
        ->delimiter(',')
        ->check(CLI::IsMember({"clip", "clip-intersection", "lens", "styles"}));
    app.add_option("--repeats", o.repeats, "frames timed per picture, interleaved (the fastest is shown)")->check(CLI::Range(1, 100));
    app.add_option("--data", o.data, "folder with spot.obj and lens.obj")->type_name("DIR");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e); // --help
        std::fprintf(stderr, "vds_gallery: %s (try 'vds_gallery --help')\n", e.what());
        return 2;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_gallery: error: %s\n", e.what());
        return 1;
    }
}
