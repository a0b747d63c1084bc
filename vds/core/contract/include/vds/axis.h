// vds: the view axis of a sprite, an exact classifier or a band grid.
#pragma once

#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include <vds/enum_names.h>

namespace vds {

/// The axis a sprite looks along. The viewer sits at the box's low side and
/// looks towards +axis. The texture's s and t follow the two other axes in
/// cyclic order: Z -> (x,y), X -> (y,z), Y -> (z,x), so no view mirrors.
enum class Axis : std::uint8_t { X = 0, Y = 1, Z = 2 };

template <> struct EnumNames<Axis> {
    static constexpr const char* kind = "axis";
    static constexpr EnumName<Axis> table[] = {{"x", Axis::X}, {"y", Axis::Y}, {"z", Axis::Z}};
};

/// Parses "x"/"y"/"z" (`parseEnum`); throws `InvalidArgument`.
Axis parseAxis(const std::string& s);
const char* toString(Axis a);

/// Index of the texture's s, t and r axes in mesh coordinates for a view axis.
inline glm::ivec3 axisPermutation(Axis axis) {
    switch (axis) {
    case Axis::X: return {1, 2, 0};
    case Axis::Y: return {2, 0, 1};
    case Axis::Z: break;
    }
    return {0, 1, 2};
}

} // namespace vds
