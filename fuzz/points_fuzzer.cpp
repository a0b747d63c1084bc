// libFuzzer harness for the point readers: the same bytes as text lines and
// as a PLY file; points that read are finite.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <vds/mesh_io.h>

#include "fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    for (vds::PointFormat format : {vds::PointFormat::Text, vds::PointFormat::Ply}) {
        try {
            const auto points = vds::parsePoints(reinterpret_cast<const char*>(data), size, format, vds::fuzz::kName);
            for (const glm::vec3& p : points)
                if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
                    vds::fuzz::broken("non-finite point read");
        } catch (const vds::FormatError& e) {
            vds::fuzz::checkMessage(e);
        } catch (const vds::OutOfMemory& e) {
            vds::fuzz::checkMessage(e);
        }
    }
    return 0;
}
