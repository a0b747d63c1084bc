// Links vds::core alone: bakes a unit cube on the CPU, classifies points
// against the sprite and the exact classifier, and checks both against the
// cube itself. Exit 0 when every answer is right.
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
    const vds::Sprite sprite = vds::bake(cube, options);
    const vds::ExactClassifier exact(cube);
    std::vector<glm::vec3> points;
    for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 20; ++j)
            for (int k = 0; k < 20; ++k) points.push_back(glm::vec3(i, j, k) * 0.1f - 0.45f);
    std::vector<std::uint8_t> labels(points.size()), exactLabels(points.size());
    vds::classify(sprite, {points.data(), points.size()}, labels.data());
    exact.classify({points.data(), points.size()}, exactLabels.data());
    std::size_t wrong = 0;
    for (std::size_t n = 0; n < points.size(); ++n) {
        const glm::vec3 p = points[n];
        const bool inside = p.x > 0 && p.x < 1 && p.y > 0 && p.y < 1 && p.z > 0 && p.z < 1;
        wrong += (labels[n] != 0) != inside;
        wrong += (exactLabels[n] != 0) != inside;
    }
    bool glRefused = false;
    try {
        options.method = vds::BakeMethod::Lists;
        vds::bake(cube, options);
    } catch (const vds::GlUnavailable&) {
        glRefused = true; // vds::gl is not linked
    }
    std::printf("%zu points, %zu wrong answers, GL method refused: %s\n", points.size(), wrong, glRefused ? "yes" : "no");
    return wrong == 0 && glRefused ? 0 : 1;
}
