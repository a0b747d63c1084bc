#include <cstdio>
#include <filesystem>

#include <glm/matrix.hpp>

#include <vds/vds_file.h>

#include "cli.h"

namespace cli {

int info(int argc, char** argv) {
    const Args args(argc, argv, {}, {"--help", "--quiet"});
    if (args.has("--help")) {
        std::fputs("usage: vds info SPRITE.vds\n\nPrints what a sprite file holds: size, depth complexity,\n"
                   "placement (P_S, M_S), source mesh, validation, and memory figures.\n",
                   stdout);
        return 0;
    }
    args.expectPositional(1, "one sprite file");
    const std::string& path = args.positional()[0];
    const vds::Sprite s = vds::readSprite(path);
    const auto& g = s.grid;
    std::printf("file:              %s (%ju bytes)\n", path.c_str(), std::uintmax_t(std::filesystem::file_size(path)));
    std::printf("format version:    %d\n", vds::Sprite::kFormatVersion);
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
    std::printf("memory:            %zu bytes in memory, %zu bytes as the paper's dense texture\n", s.memoryBytes(),
                s.denseBytes());
    return 0;
}

} // namespace cli
