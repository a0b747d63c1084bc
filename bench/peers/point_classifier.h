// vds_peers_bench: the one interface the benchmark drives a peer through.
//
// A peer (Embree ray parity, CGAL Side_of_triangle_mesh) is built from a mesh
// by its own factory (embree_parity.h, cgal_side.h), which the benchmark
// times as the peer's build; `classify` is what it times as the query.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

namespace vds::peers {

class PointClassifier {
public:
    virtual ~PointClassifier() = default;
    PointClassifier() = default;
    PointClassifier(const PointClassifier&) = delete;
    PointClassifier& operator=(const PointClassifier&) = delete;

    /// `points` and `labels` hold `count` elements, owned by the caller, mesh
    /// coordinates; `labels[k]` becomes 1 inside, 0 outside.
    virtual void classify(const glm::vec3* points, std::size_t count, std::uint8_t* labels) const = 0;
    /// Threads `classify` runs on.
    virtual unsigned threads() const = 0;
};

} // namespace vds::peers
