// The style binding (shaders/vds/styles.glsl) and the samples' scenes, on a
// real GL context: roles and combine modes against analytic expectations on
// a plate, and each sample scene through each representation's lookup
// against the exact reference within stated limits (Magnum's image
// comparison: a share of differing pixels and a mean channel delta).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <vds/distance.h>
#include <vds/gl/shader.h>
#include <vds/sprite.h>

#include "gl_fixture.h"
#include "image_compare.h"
#include "scene.h"

namespace {

namespace vs = vds::samples;

constexpr std::uint32_t kSize = 128;

// A thin plate facing +z, seen along -z: pixel (x, y) shows plate point
// (wx, wy) (the camera fits the plate's bounding sphere, as the samples do).
vs::Scene plateScene() {
    vs::Scene s;
    s.name = "plate";
    s.model = vs::box({-1.0f, -1.0f, -0.02f}, {1.0f, 1.0f, 0.02f});
    s.viewDirection = {0.0f, 0.0f, 1.0f};
    return s;
}

glm::vec2 platePoint(std::uint32_t x, std::uint32_t y) {
    const float radius = 0.5f * std::sqrt(2.0f * 2.0f * 2.0f + 0.04f * 0.04f);
    return {-radius + 2.0f * radius * (float(x) + 0.5f) / float(kSize),
            radius - 2.0f * radius * (float(y) + 0.5f) / float(kSize)};
}

struct Rect {
    glm::vec2 lo, hi;
    bool contains(glm::vec2 p) const { return p.x > lo.x && p.x < hi.x && p.y > lo.y && p.y < hi.y; }
    // Within `margin` of an edge: a pixel there may go either way.
    bool nearEdge(glm::vec2 p, float margin) const {
        const bool inX = p.x > lo.x - margin && p.x < hi.x + margin, inY = p.y > lo.y - margin && p.y < hi.y + margin;
        return (inX && inY) && (std::fabs(p.x - lo.x) < margin || std::fabs(p.x - hi.x) < margin ||
                                std::fabs(p.y - lo.y) < margin || std::fabs(p.y - hi.y) < margin);
    }
    vds::TriangleMesh mesh() const { return vs::box({lo, -0.5f}, {hi, 0.5f}); }
};

const Rect kA{{-0.6f, -0.5f}, {0.2f, 0.5f}};
const Rect kB{{-0.2f, -0.3f}, {0.6f, 0.7f}};

bool white(const vds::eval::Image& image, std::uint32_t x, std::uint32_t y) {
    const std::uint8_t* p = image.at(x, y);
    return p[0] == 255 && p[1] == 255 && p[2] == 255;
}

// Counts pixels (away from the rectangles' edges and the plate's rim) where
// `actual(x, y)` differs from `expected(inA, inB)`; also how many were checked.
std::pair<std::size_t, std::size_t> mismatches(const std::function<bool(std::uint32_t, std::uint32_t)>& actual,
                                               const std::function<bool(bool, bool)>& expected) {
    const float margin = 0.03f; // two pixels of 0.011 and a texel of 0.008 at resolution 128
    std::size_t wrong = 0, checked = 0;
    for (std::uint32_t y = 0; y < kSize; ++y)
        for (std::uint32_t x = 0; x < kSize; ++x) {
            const glm::vec2 p = platePoint(x, y);
            if (std::fabs(p.x) > 0.97f || std::fabs(p.y) > 0.97f) continue;
            if (kA.nearEdge(p, margin) || kB.nearEdge(p, margin)) continue;
            ++checked;
            wrong += actual(x, y) != expected(kA.contains(p), kB.contains(p));
        }
    return {wrong, checked};
}

class Styles : public vds::test::GlTest {};

// The include is part of vds::gl (embedded and installed beside vpt.glsl) and
// compiles on its own in every stage, with the VDS lookup or a caller's hook.
TEST_F(Styles, IncludeStandsAloneInEveryStageWithEitherLookup) {
    const auto paths = vds::embeddedShaderPaths();
    EXPECT_NE(std::find(paths.begin(), paths.end(), "vds/styles.glsl"), paths.end());
    const std::string body = "VdsStyle s = vdsStyleAt(vec3(0.5)); float v = s.discarded ? 0.0 : float(s.style);";
    for (const std::string& head :
         {std::string("#include \"vds/styles.glsl\"\n"),
          std::string("#define VDS_STYLE_SPRITES 12\nuniform float u_r[12];\n"
                      "#define VDS_STYLE_INSIDE(i, p) (length(p) < u_r[i])\n#include \"vds/styles.glsl\"\n")}) {
        EXPECT_NO_THROW(vds::buildProgram(
            {{GL_VERTEX_SHADER, "v", head + "void main() { " + body + " gl_Position = vec4(v); }\n"},
             {GL_FRAGMENT_SHADER, "f", head + "out vec4 c; void main() { " + body + " c = vec4(v); }\n"}}));
        EXPECT_NO_THROW(vds::buildProgram(
            {{GL_COMPUTE_SHADER, "c", head + "layout(local_size_x = 1) in; layout(std430, binding = 0) buffer B { float b[]; };\n"
                                             "void main() { " + body + " b[0] = v; }\n"}}));
    }
}

// Clip away / clip to, union / intersection: a pixel shows the background
// exactly where the roles and the combine mode say the plate is cut.
TEST_F(Styles, ClipRolesAndCombineModesCutWhereTheyShould) {
    struct Case {
        vs::Role role;
        vs::Combine combine;
        std::function<bool(bool, bool)> cut;
    };
    const Case cases[] = {
        {vs::Role::ClipAway, vs::Combine::Union, [](bool a, bool b) { return a || b; }},
        {vs::Role::ClipAway, vs::Combine::Intersection, [](bool a, bool b) { return a && b; }},
        {vs::Role::ClipTo, vs::Combine::Union, [](bool a, bool b) { return !(a || b); }},
        {vs::Role::ClipTo, vs::Combine::Intersection, [](bool a, bool b) { return !(a && b); }},
    };
    for (const vs::Lookup lookup : {vs::Lookup::Exact, vs::Lookup::Vds, vs::Lookup::Solid})
        for (const Case& c : cases) {
            vs::Scene scene = plateScene();
            scene.combineAway = scene.combineTo = c.combine;
            scene.solids.push_back({"a", kA.mesh(), {}, glm::mat4(1.0f), c.role, vs::Style::Shaded});
            scene.solids.push_back({"b", kB.mesh(), {}, glm::mat4(1.0f), c.role, vs::Style::Shaded});
            vs::SceneRenderer renderer(gl(), scene, lookup, {128, false});
            const vds::eval::Image image = renderer.render(kSize);
            const auto [wrong, checked] =
                mismatches([&](std::uint32_t x, std::uint32_t y) { return white(image, x, y); }, c.cut);
            EXPECT_GT(checked, 5000u);
            EXPECT_EQ(wrong, 0u) << vs::toString(lookup) << " role " << int(c.role) << " combine " << int(c.combine);
        }
}

// The clip sample's band (Scene::distanceWidth, shaders/samples/scene.frag)
// on the plate cut by a sphere, drawn through the scene's shader and
// vdsDistance from the sphere's distance grid, against the band of the exact
// distance (SignedDistance) of each pixel's plate point: orange exactly
// where 0 < d <= width, except where the exact distance lies within the
// lookup's bound (half a cell's diagonal, under one cell) of the band's outer
// edge (grown beyond the grid's cell centres as vpt.glsl states) or within a
// texel of the cut itself (the sprite's clip decides there).
TEST_F(Styles, ClipBandMatchesTheExactDistanceOfEachPixel) {
    const vds::TriangleMesh sphere = vs::uvSphere({0.1f, -0.1f, 0.0f}, 0.5f, 32);
    vs::Scene scene = plateScene();
    scene.solids.push_back({"sphere", sphere, {}, glm::mat4(1.0f), vs::Role::ClipAway, vs::Style::Shaded});
    scene.distanceWidth = 0.12f;
    scene.distanceResolution = 32;
    vs::SceneRenderer renderer(gl(), scene, vs::Lookup::Vds, {128, false});
    const vds::eval::Image image = renderer.render(kSize);
    const vds::SignedDistance exact(sphere, scene.rule);
    const vds::SpriteDistance field = vds::bakeDistance(sphere, vds::meshBounds(sphere), 32, scene.rule, 0);
    const glm::vec3 cell = (field.grid.box.hi - field.grid.box.lo) / glm::vec3(field.grid.dims);
    const double bound = 0.5 * glm::length(glm::dvec3(cell)) * (1.0 + 2.0 * std::sqrt(3.0) / 256.0);
    const double texel = 1.0 / 128.0 * 1.5; // the sprite's texel, and a half
    std::size_t band = 0, wrong = 0, checked = 0;
    for (std::uint32_t y = 0; y < kSize; ++y)
        for (std::uint32_t x = 0; x < kSize; ++x) {
            const glm::vec2 p = platePoint(x, y);
            if (std::fabs(p.x) > 0.97f || std::fabs(p.y) > 0.97f) continue;
            const glm::vec3 point(p, 0.02f);
            const double d = exact.distance(point);
            // Beyond the grid's cell centres the lookup is an upper bound, grown by at
            // most twice the way there (vpt.glsl): it can only miss band pixels there.
            const glm::vec3 centres = glm::clamp(point, field.grid.box.lo + 0.5f * cell, field.grid.box.hi - 0.5f * cell);
            const double beyond = 2.0 * glm::length(glm::dvec3(point - centres));
            const double edge = d - double(scene.distanceWidth);
            if (std::abs(d) <= texel || (edge >= -(bound + beyond) && edge <= bound)) continue;
            const std::uint8_t* rgba = image.at(x, y);
            const bool orange = rgba[0] > 30 && rgba[2] * 10 < rgba[0] * 3 && rgba[1] * 20 > rgba[0] * 9;
            const bool expected = d > 0.0 && d <= double(scene.distanceWidth);
            ++checked;
            band += expected;
            wrong += orange != expected;
        }
    EXPECT_GT(checked, 5000u);
    EXPECT_GT(band, 300u);
    EXPECT_EQ(wrong, 0u);
    std::printf("clip band on the plate: %zu pixels checked, %zu in the exact band, %zu differ\n", checked, band, wrong);
}

// Eight solids in one pass (the include's default), through every lookup:
// eight boxes in a 4 x 2 pattern cut eight holes in the plate.
TEST_F(Styles, EightSolidsCutInOnePassThroughEveryLookup) {
    std::vector<Rect> holes;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 2; ++j) {
            const glm::vec2 lo(-0.85f + 0.45f * float(i), -0.7f + 0.8f * float(j));
            holes.push_back({lo, lo + glm::vec2(0.3f, 0.5f)});
        }
    vs::Scene scene = plateScene();
    for (const Rect& r : holes) scene.solids.push_back({"hole", r.mesh(), {}, glm::mat4(1.0f), vs::Role::ClipAway, vs::Style::Shaded});
    for (const vs::Lookup lookup :
         {vs::Lookup::Exact, vs::Lookup::Vds, vs::Lookup::Slicemap, vs::Lookup::SlicemapLocal, vs::Lookup::Solid}) {
        vs::SceneRenderer renderer(gl(), scene, lookup, {128, false});
        const vds::eval::Image image = renderer.render(kSize);
        std::size_t wrong = 0, cut = 0, checked = 0;
        for (std::uint32_t y = 0; y < kSize; ++y)
            for (std::uint32_t x = 0; x < kSize; ++x) {
                const glm::vec2 p = platePoint(x, y);
                if (std::fabs(p.x) > 0.97f || std::fabs(p.y) > 0.97f) continue;
                if (std::any_of(holes.begin(), holes.end(), [&](const Rect& r) { return r.nearEdge(p, 0.03f); })) continue;
                const bool inside = std::any_of(holes.begin(), holes.end(), [&](const Rect& r) { return r.contains(p); });
                ++checked;
                cut += inside;
                wrong += white(image, x, y) != inside;
            }
        EXPECT_GT(cut, 1000u);
        EXPECT_EQ(wrong, 0u) << vs::toString(lookup) << ": " << wrong << " of " << checked;
    }
}

// Style solids: the one with the higher index wins; a lens wins over every
// style solid whatever its index. X-ray on the plate (over white) is bluish,
// flat shading warm.
TEST_F(Styles, LensWinsOverStylesAndLaterStylesWinOverEarlier) {
    for (const vs::Lookup lookup : {vs::Lookup::Exact, vs::Lookup::Vds}) {
        vs::Scene scene = plateScene();
        scene.baseStyle = vs::Style::Shaded;
        // Lens first (index 0, shaded), style second (index 1, X-ray): in A and B the lens wins.
        scene.solids.push_back({"lens-b", kB.mesh(), {}, glm::mat4(1.0f), vs::Role::Lens, vs::Style::Shaded});
        scene.solids.push_back({"style-a", kA.mesh(), {}, glm::mat4(1.0f), vs::Role::Style, vs::Style::XRay});
        vs::SceneRenderer renderer(gl(), scene, lookup, {128, false});
        const vds::eval::Image image = renderer.render(kSize);
        const auto bluish = [&](std::uint32_t x, std::uint32_t y) { return image.at(x, y)[2] > image.at(x, y)[0]; };
        auto [wrong, checked] = mismatches(bluish, [](bool a, bool b) { return a && !b; });
        EXPECT_GT(checked, 5000u);
        EXPECT_EQ(wrong, 0u) << vs::toString(lookup) << ": lens over style";

        // Two style solids: the later (B, shaded) wins over the earlier (A, X-ray).
        scene.solids[0] = {"style-a", kA.mesh(), {}, glm::mat4(1.0f), vs::Role::Style, vs::Style::XRay};
        scene.solids[1] = {"style-b", kB.mesh(), {}, glm::mat4(1.0f), vs::Role::Style, vs::Style::Shaded};
        scene.baseStyle = vs::Style::XRay;
        vs::SceneRenderer second(gl(), scene, lookup, {128, false});
        const vds::eval::Image image2 = second.render(kSize);
        std::tie(wrong, checked) = mismatches(
            [&](std::uint32_t x, std::uint32_t y) { return image2.at(x, y)[2] > image2.at(x, y)[0]; },
            [](bool, bool b) { return !b; });
        EXPECT_EQ(wrong, 0u) << vs::toString(lookup) << ": later style over earlier";
    }
}

// Moving a solid (Sprite::transform on the GPU sprite, no re-bake) gives the
// picture of the solid baked where it was moved to: the lens sample's frames
// against the exact reference at the same placements.
TEST_F(Styles, MovedLensMatchesTheExactReferenceAlongThePath) {
    const vs::Scene scene = vs::lensScene(VDS_SAMPLES_DATA);
    vs::SceneRenderer vdsRenderer(gl(), scene, vs::Lookup::Vds, {256, false});
    vs::SceneRenderer exact(gl(), scene, vs::Lookup::Exact);
    for (const float t : {0.0f, 0.5f, 1.0f}) {
        vdsRenderer.place(0, vs::lensPath(t));
        exact.place(0, vs::lensPath(t));
        const vs::ImageDifference d = vs::compareImages(vdsRenderer.render(kSize), exact.render(kSize));
        EXPECT_GT(d.covered, 3000u);
        // Limit: 1 % of the covered pixels, the lens's silhouette at a texel of 1/256 of its size.
        std::printf("lens t = %.1f: %zu of %zu pixels differ\n", double(t), d.pixels, d.covered);
        EXPECT_LE(double(d.pixels), 0.01 * double(d.covered)) << "t = " << t << ": " << d.pixels << " of " << d.covered;
    }
}

// Every sample scene through every lookup against the exact reference, at
// 128 px and resolution 128. Limits: the share of covered pixels that differ
// (any channel by more than 8) and the mean channel delta over the picture.
// Measured on llvmpipe: at most 0.5 % of the covered pixels differ for any
// lookup, mean delta under 0.15; the limits (1 % for the VDS, 2 % for the
// voxel grids, mean 0.5) leave room for other rasterizers.
TEST_F(Styles, SampleScenesThroughEachLookupMatchTheExactReference) {
    struct Limit {
        vs::Lookup lookup;
        double share, mean;
    };
    const Limit limits[] = {{vs::Lookup::Vds, 0.01, 0.5},
                            {vs::Lookup::Slicemap, 0.02, 0.5},
                            {vs::Lookup::SlicemapLocal, 0.02, 0.5},
                            {vs::Lookup::Solid, 0.02, 0.5}};
    std::vector<vs::Scene> scenes = {vs::clipScene(VDS_SAMPLES_DATA, vs::Combine::Union),
                                     vs::clipScene(VDS_SAMPLES_DATA, vs::Combine::Intersection),
                                     vs::lensScene(VDS_SAMPLES_DATA), vs::stylesScene(VDS_SAMPLES_DATA)};
    scenes[2].solids[0].placement = vs::lensPath(0.5f);
    for (const vs::Scene& scene : scenes) {
        vs::SceneRenderer exact(gl(), scene, vs::Lookup::Exact);
        const vds::eval::Image reference = exact.render(kSize);
        for (const Limit& limit : limits) {
            vs::SceneRenderer renderer(gl(), scene, limit.lookup, {128, false});
            const vs::ImageDifference d = vs::compareImages(renderer.render(kSize), reference);
            EXPECT_GT(d.covered, 3000u) << scene.name;
            const double share = double(d.pixels) / double(d.covered);
            std::printf("%-18s %-15s %4zu of %5zu pixels differ (%.2f %%), mean delta %.2f\n", scene.name.c_str(),
                        vs::toString(limit.lookup), d.pixels, d.covered, 100.0 * share, d.mean);
            EXPECT_LE(share, limit.share) << scene.name << " with " << vs::toString(limit.lookup) << ": " << d.pixels
                                          << " of " << d.covered << " pixels differ";
            EXPECT_LE(d.mean, limit.mean) << scene.name << " with " << vs::toString(limit.lookup);
        }
    }
}

// The styles sample's picture against the stored one (made on llvmpipe):
// the shading itself, not only the inside answers, stays as it was.
// Rasterizers may differ along edges and style borders, a whole pixel there
// (max 255), but the mean stays small.
TEST_F(Styles, StylesSceneMatchesItsStoredPicture) {
    vs::SceneRenderer renderer(gl(), vs::stylesScene(VDS_SAMPLES_DATA), vs::Lookup::Vds, {128, false});
    EXPECT_TRUE(vds::test::imageMatchesReference(renderer.render(kSize), VDS_TEST_DATA "/styles-vds-128.png", 255, 1.0));
}

} // namespace
