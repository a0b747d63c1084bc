// libFuzzer harness for one mesh format (VDS_FUZZ_FORMAT: Obj, Ply, Stl, Off):
// parseMesh on arbitrary bytes, then validateMesh on whatever it returns.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <vds/mesh.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>

#include "fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        const vds::TriangleMesh mesh = vds::parseMesh(reinterpret_cast<const char*>(data), size,
                                                      vds::MeshFormat::VDS_FUZZ_FORMAT, vds::fuzz::kName);
        // A mesh that was read has valid indices and finite coordinates.
        for (const glm::uvec3& t : mesh.triangles)
            if (t.x >= mesh.positions.size() || t.y >= mesh.positions.size() || t.z >= mesh.positions.size())
                vds::fuzz::broken("triangle index out of range");
        for (const glm::vec3& p : mesh.positions)
            if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
                vds::fuzz::broken("non-finite coordinate read");
        const vds::MeshReport report = vds::validateMesh(mesh);
        if (report.badIndices != 0 || report.nonFiniteVertices != 0) vds::fuzz::broken("validation disagrees");
        (void)report.summary();
    } catch (const vds::FormatError& e) {
        vds::fuzz::checkMessage(e);
    } catch (const vds::OutOfMemory& e) {
        vds::fuzz::checkMessage(e);
    }
    return 0;
}
