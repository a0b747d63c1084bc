// Sample: render a mesh offscreen, clipped pixel-precisely by up to eight
// solids in one pass (Trapp & Doellner 2008, Figure 1), through the GLSL
// include shaders/vds/styles.glsl, and write a PNG.
//
//   vds_clip MESH (--clip A.vds | --solid B.obj)... -o out.png [--with vds|slicemap|slicemap-local|solid|exact]
//            [--combine union|intersection] [--keep] [--resolution N] [--size N] [--view iso|x|y|z] [--rule parity|winding]
//            [--band W [--distance-resolution N]]
//   (vds_clip --help lists the defaults)
//
// Fragments of MESH inside the union (or intersection) of the solids are
// discarded (--keep: those outside); back faces seen through the cut, the
// cut surface, are drawn in red. Solids given as meshes are baked (or
// voxelized, --with) at --resolution; sprites (.vds) work with --with vds
// only. The camera is orthographic, fitted to MESH's bounding box. --band W
// draws a band of width W (mesh units) in orange where a solid cuts the
// surface, from the solids' signed distance grids through vdsDistance
// (sprites bring theirs: `vds bake --distance N`; meshes get one baked).
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <vds/error.h>
#include <vds/eval/image.h>
#include <vds/gl/context.h>
#include <vds/mesh_io.h>
#include <vds/vds_file.h>

#include "scene.h"

namespace {

struct Options {
    std::string mesh, output, view = "iso", with = "vds", combine = "union";
    std::vector<std::string> clips, solids;
    bool keep = false;
    std::uint32_t size = 800, resolution = 256, distanceResolution = 64;
    float band = 0.0f;
    std::string rule = vds::enumName(vds::Rule::Parity);
};

int run(const Options& o) {
    if (o.clips.size() + o.solids.size() > 8) throw vds::InvalidArgument("at most 8 solids (--clip and --solid together)");
    vds::samples::Scene scene;
    scene.name = o.mesh;
    scene.model = vds::loadMesh(o.mesh);
    scene.combineAway = scene.combineTo =
        o.combine == "union" ? vds::samples::Combine::Union : vds::samples::Combine::Intersection;
    scene.rule = vds::parseRule(o.rule);
    scene.distanceWidth = o.band;
    scene.distanceResolution = o.distanceResolution;
    const vds::samples::Role role = o.keep ? vds::samples::Role::ClipTo : vds::samples::Role::ClipAway;
    for (const auto& path : o.clips) {
        vds::samples::SceneSolid solid;
        solid.name = path;
        solid.sprite = vds::readSprite(path);
        solid.role = role;
        scene.solids.push_back(std::move(solid));
    }
    for (const auto& path : o.solids) {
        vds::samples::SceneSolid solid;
        solid.name = path;
        solid.mesh = vds::loadMesh(path);
        solid.role = role;
        scene.solids.push_back(std::move(solid));
    }
    if (o.view == "x") scene.viewDirection = {1, 0, 0};
    else if (o.view == "y") { scene.viewDirection = {0, 1, 0}; scene.up = {0, 0, -1}; }
    else if (o.view == "z") scene.viewDirection = {0, 0, 1};

    vds::GlContext gl;
    vds::samples::SceneRenderer renderer(gl, scene, vds::samples::parseLookup(o.with), {o.resolution, false});
    vds::eval::writePng(renderer.render(o.size), o.output);
    std::printf("wrote %s: %ux%u, %s clipped by %zu solid(s) with %s, GL %s\n", o.output.c_str(), o.size, o.size,
                o.mesh.c_str(), scene.solids.size(), o.with.c_str(), gl.info().renderer.c_str());
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app("Renders MESH with every fragment inside the solids discarded (--keep: outside), pixel-precisely,\n"
                 "in one pass; back faces seen through the cut are red.",
                 "vds_clip");
    app.get_formatter()->label("Usage", "usage");
    app.option_defaults()->always_capture_default();
    app.add_option("MESH", o.mesh, "mesh to render (OBJ, PLY, STL, OFF)")->required()->type_name("");
    auto* clip = app.add_option("--clip", o.clips, "a baked sprite that cuts the mesh (--with vds)")
                     ->expected(1, 8)
                     ->allow_extra_args(false)
                     ->type_name("SPRITE.vds");
    auto* solid = app.add_option("--solid", o.solids, "a closed mesh that cuts the mesh, baked or voxelized at --resolution")
                      ->expected(1, 8)
                      ->allow_extra_args(false)
                      ->type_name("SOLID.obj");
    app.add_option("-o,--output", o.output, "the picture")->required()->type_name("OUT.png");
    app.add_option("--with", o.with, "inside test in the shader")
        ->check(CLI::IsMember({"vds", "slicemap", "slicemap-local", "solid", "exact"}));
    app.add_option("--combine", o.combine, "the clip region: union or intersection of the solids")
        ->check(CLI::IsMember({"union", "intersection"}));
    app.add_flag("--keep", o.keep, "keep only what lies inside the clip region");
    app.add_option("--resolution", o.resolution, "texels or cells along a solid's longest side")
        ->check(CLI::Range(8u, 2048u));
    app.add_option("--size", o.size, "image width and height in pixels")->check(CLI::Range(16u, 8192u));
    app.add_option("--view", o.view, "look along -x, -y, -z or diagonally")->check(CLI::IsMember({"iso", "x", "y", "z"}));
    app.add_option("--band", o.band, "width of a band along the cut, from the solids' distance grids (0: none)")
        ->check(CLI::Range(0.0f, 1e6f))
        ->type_name("W");
    app.add_option("--distance-resolution", o.distanceResolution,
                   "cells along the longest side of a distance grid baked for --band")
        ->check(CLI::Range(4u, 1024u));
    app.add_option("--rule", o.rule, "inside rule for the sprites")->check(CLI::IsMember({"parity", "winding"}));
    try {
        app.parse(argc, argv);
        if (clip->count() + solid->count() == 0) throw CLI::RequiredError("--clip or --solid");
        if (clip->count() > 0 && o.with != "vds")
            throw CLI::ValidationError("--clip", "sprites work with --with vds only; give the solid's mesh with --solid");
        if (o.band > 0.0f && o.with != "vds") throw CLI::ValidationError("--band", "needs --with vds");
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e); // --help
        std::fprintf(stderr, "vds_clip: %s (try 'vds_clip --help')\n", e.what());
        return 2;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_clip: error: %s\n", e.what());
        return 1;
    }
}
