// Embree 3's point query (rtcPointQuery): the scene's BVH calls back for
// each triangle whose box the query sphere reaches; the callback computes
// the closest point and shrinks the sphere. The closest point is computed in
// float by Ericson's regions, as Embree's closest_point tutorial and
// Open3D's RaycastingScene::ComputeClosestPoints do.
#include "distance_peer.h"

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include <embree3/rtcore.h>

#include <glm/geometric.hpp>

namespace vds::peers {

namespace {

glm::vec3 closestOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return a;
    const glm::vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return b;
    const glm::vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return c;
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return a + ab * (d1 / (d1 - d3));
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return a + ac * (d2 / (d2 - d6));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const float denom = 1.0f / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

struct Scene {
    const glm::vec3* positions;
    const glm::uvec3* triangles;
};

struct Nearest {
    const Scene* scene;
    float distance;
};

bool visit(RTCPointQueryFunctionArguments* args) {
    Nearest& best = *static_cast<Nearest*>(args->userPtr);
    const glm::uvec3 t = best.scene->triangles[args->primID];
    const glm::vec3 p(args->query->x, args->query->y, args->query->z);
    const glm::vec3* v = best.scene->positions;
    const float d = glm::length(p - closestOnTriangle(p, v[t.x], v[t.y], v[t.z]));
    if (d >= args->query->radius) return false;
    args->query->radius = d;
    best.distance = d;
    return true; // the sphere shrank: Embree culls with the new radius
}

class EmbreeDistance final : public DistancePeer {
public:
    explicit EmbreeDistance(MeshView mesh) : scene_{mesh.positions, mesh.triangles} {
        device_ = rtcNewDevice("threads=1");
        if (!device_) throw std::runtime_error("Embree: rtcNewDevice failed");
        handle_ = rtcNewScene(device_);
        RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                     RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positionCount));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                                       RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangleCount));
        for (std::size_t v = 0; v < mesh.positionCount; ++v)
            for (int a = 0; a < 3; ++a) vertices[3 * v + a] = mesh.positions[v][a];
        for (std::size_t f = 0; f < mesh.triangleCount; ++f)
            for (int a = 0; a < 3; ++a) indices[3 * f + a] = mesh.triangles[f][a];
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(handle_, geometry);
        rtcReleaseGeometry(geometry);
        rtcCommitScene(handle_);
        if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw std::runtime_error("Embree: building the scene failed");
    }
    ~EmbreeDistance() override {
        rtcReleaseScene(handle_);
        rtcReleaseDevice(device_);
    }
    EmbreeDistance(const EmbreeDistance&) = delete;
    EmbreeDistance& operator=(const EmbreeDistance&) = delete;

    std::string name() const override {
        return "Embree " + std::to_string(RTC_VERSION_MAJOR) + "." + std::to_string(RTC_VERSION_MINOR) + "." +
               std::to_string(RTC_VERSION_PATCH) + " rtcPointQuery";
    }
    void distances(const std::vector<glm::vec3>& points, double* out) const override {
        for (std::size_t k = 0; k < points.size(); ++k) {
            RTCPointQuery query;
            query.x = points[k].x;
            query.y = points[k].y;
            query.z = points[k].z;
            query.time = 0.0f;
            query.radius = std::numeric_limits<float>::infinity();
            RTCPointQueryContext context;
            rtcInitPointQueryContext(&context);
            Nearest best{&scene_, std::numeric_limits<float>::infinity()};
            rtcPointQuery(handle_, &query, &context, visit, &best);
            out[k] = best.distance;
        }
    }

private:
    Scene scene_;
    RTCDevice device_ = nullptr;
    RTCScene handle_ = nullptr;
};

} // namespace

std::unique_ptr<DistancePeer> makeEmbreeDistance(MeshView mesh) { return std::make_unique<EmbreeDistance>(mesh); }

} // namespace vds::peers
