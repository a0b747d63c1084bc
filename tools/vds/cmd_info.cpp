#include <cstdio>
#include <filesystem>

#include <glm/matrix.hpp>

#include <vds/vds_file.h>

#include "cli.h"

namespace cli {

namespace {

struct InfoArgs {
    std::string path;
    bool quiet = false; // accepted like every command's; info prints no progress
};

void info(InfoArgs& a) {
    const std::string& path = a.path;
    const vds::Sprite s = vds::readSprite(path);
    const auto& g = s.grid;
    std::printf("file:              %s (%ju bytes)\n", path.c_str(), std::uintmax_t(std::filesystem::file_size(path)));
    std::printf("format version:    %d (as this library writes it: 3 with a distance grid)\n",
                s.distance.empty() ? 2 : vds::Sprite::kFormatVersion);
    std::printf("source mesh:       %s, %ju triangles\n", s.sourceName.empty() ? "(unnamed)" : s.sourceName.c_str(),
                std::uintmax_t(s.sourceTriangles));
    std::printf("validation:        %s%s\n", s.validation.c_str(),
                s.status == vds::SolidStatus::Open ? "  [NOT A SOLID: answers are a surface's]" : "");
    std::printf("view axis:         %s\n", vds::toString(g.axis));
    std::printf("resolution:        %u x %u texels, texel size %g\n", g.width, g.height, double(g.texelSize));
    std::printf("depth complexity:  %u\n", s.depthComplexity);
    std::printf("crossings:         %zu\n", s.crossings.size());
    std::printf("mesh box:          (%g, %g, %g) - (%g, %g, %g)\n", double(g.box.lo.x), double(g.box.lo.y),
                double(g.box.lo.z), double(g.box.hi.x), double(g.box.hi.y), double(g.box.hi.z));
    std::printf("P_S:               (%g, %g, %g)\n", double(g.position.x), double(g.position.y), double(g.position.z));
    const glm::mat3& m = g.matrix;
    std::printf("M_S:               [%g %g %g; %g %g %g; %g %g %g]\n", double(m[0][0]), double(m[1][0]),
                double(m[2][0]), double(m[0][1]), double(m[1][1]), double(m[2][1]), double(m[0][2]), double(m[1][2]),
                double(m[2][2]));
    if (!s.distance.empty()) {
        const vds::Grid& d = s.distance.grid;
        std::printf("distance grid:     %u x %u x %u cells over (%g, %g, %g) - (%g, %g, %g)\n", d.dims.x, d.dims.y,
                    d.dims.z, double(d.box.lo.x), double(d.box.lo.y), double(d.box.lo.z), double(d.box.hi.x),
                    double(d.box.hi.y), double(d.box.hi.z));
    }
    std::printf("memory:            %zu bytes in memory, %zu bytes as the paper's dense texture\n", s.memoryBytes(),
                s.denseBytes());
}

} // namespace

void addInfo(CLI::App& app) {
    const auto [c, a] = addCommand<InfoArgs>(app, "info", "describe a sprite file",
                                             "Prints what a sprite file holds: size, depth complexity, placement\n"
                                             "(P_S, M_S), source mesh, validation, and memory figures.",
                                             info);
    c->add_option("SPRITE", a->path, "sprite file (.vds)")->required()->type_name("");
}

} // namespace cli
