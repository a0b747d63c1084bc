// vds internal: pi, once, for the solid angles of the winding number, the
// mesh check's inside-out parts, the occupancy sweep's boundary term and
// anything else in the library that measures angles (GLSL gets it as a
// define from here).
#pragma once

namespace vds::detail {

constexpr double kPi = 3.14159265358979323846;
/// The full solid angle: a winding number is a sum of solid angles over it.
constexpr double kFourPi = 4.0 * kPi;

} // namespace vds::detail
