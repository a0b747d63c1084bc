// libFuzzer harness for the .vds reader: decodeSprite on arbitrary bytes; a
// sprite that reads must be consistent and answer point queries.
#include <cstddef>
#include <cstdint>
#include <optional>

#include <glm/vec3.hpp>

#include <vds/sprite.h>
#include <vds/vds_file.h>

#include "fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::optional<vds::Sprite> sprite;
    try {
        sprite = vds::decodeSprite(reinterpret_cast<const char*>(data), size, vds::fuzz::kName);
    } catch (const vds::FormatError& e) {
        vds::fuzz::checkMessage(e);
        return 0;
    } catch (const vds::OutOfMemory& e) {
        vds::fuzz::checkMessage(e);
        return 0;
    }
    try {
        sprite->checkConsistent();
    } catch (const vds::Error&) {
        vds::fuzz::broken("an inconsistent sprite was read");
    }
    const vds::Box& box = sprite->grid.box;
    for (float t : {-0.5f, 0.0f, 0.25f, 0.5f, 1.0f, 1.5f}) {
        const glm::vec3 p = box.lo + t * (box.hi - box.lo);
        (void)sprite->contains(p, vds::Rule::Parity);
        (void)sprite->contains(p, vds::Rule::Winding);
    }
    return 0;
}
