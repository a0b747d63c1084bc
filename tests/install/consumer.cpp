// Links vds::core alone, built where no GL development files need to be:
// bakes a unit cube on the CPU, classifies points through the one contract
// (the sprite, the exact and the certified classifier, each a
// vds::Classifier), sweeps an occupancy grid, and checks every answer
// against the cube itself. It names glm's colour components (r, g, b): the
// library's own GLM settings do not reach its users. Exit 0 when every
// answer is right.
#include <cstdio>
#include <vector>

#include <vds/vds.h>

int main() {
    const std::vector<glm::vec3> corners = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                            {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const std::vector<glm::uvec3> faces = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                           {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    const vds::MeshView cube(corners.data(), corners.size(), faces.data(), faces.size());
    vds::BakeOptions options;
    options.resolution = 32;
    options.method = vds::BakeMethod::Cpu;
    const vds::SpriteClassifier sprite(vds::bakeCpu(cube, options));
    const vds::ExactClassifier exact(cube);
    const vds::CertifiedClassifier certified(cube, {32, vds::Axis::Z, 1});
    std::vector<glm::vec3> points;
    for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 20; ++j)
            for (int k = 0; k < 20; ++k) points.push_back(glm::vec3(i, j, k) * 0.1f - 0.45f);
    std::size_t wrong = 0;
    for (const vds::Classifier* classifier : {static_cast<const vds::Classifier*>(&sprite),
                                              static_cast<const vds::Classifier*>(&exact),
                                              static_cast<const vds::Classifier*>(&certified)}) {
        std::vector<std::uint8_t> labels(points.size());
        classifier->classify(points, labels.data());
        for (std::size_t n = 0; n < points.size(); ++n) {
            const glm::vec3 p = points[n];
            const bool inside = p.x > 0 && p.x < 1 && p.y > 0 && p.y < 1 && p.z > 0 && p.z < 1;
            wrong += (labels[n] != 0) != inside;
        }
    }
    // A 20^3 grid over [-0.5, 1.5]^3: cell centres at -0.45 + 0.1 i, as the points above.
    const vds::Grid grid{vds::Box{{-0.5f, -0.5f, -0.5f}, {1.5f, 1.5f, 1.5f}}, {20, 20, 20}};
    std::vector<std::uint8_t> cells(grid.cellCount());
    vds::occupancy(cube, grid, cells.data());
    std::size_t inside = 0;
    for (auto c : cells) inside += c;
    wrong += inside == 1000 ? 0 : 1; // x, y, z in 0.05 .. 0.95: 10 cells each way
    const glm::vec3 colour(1.0f, 0.5f, 0.25f);
    wrong += colour.r == 1.0f && colour.g == 0.5f && colour.b == 0.25f ? 0 : 1;
    std::printf("%zu points by 3 methods and a %zu-cell grid, %zu wrong answers\n", points.size(), cells.size(), wrong);
    return wrong == 0 ? 0 : 1;
}
