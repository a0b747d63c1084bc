// vds: how crossings in front of a point decide "inside".
#pragma once

#include <cstdint>
#include <string>

#include <vds/enum_names.h>

namespace vds {

/// How crossings in front of a point decide inside.
enum class Rule : std::uint8_t {
    Parity,  ///< the paper's rule: an odd number of crossings in front is inside
    Winding, ///< non-zero winding: entering crossings +1, leaving -1, inside if the sum != 0
    /// The generalized winding number (Jacobson et al. 2013) above 1/2: the
    /// solid angle the surface subtends, over 4 pi. On a mesh that bounds a
    /// solid it is the winding number; on open meshes, soups and meshes with
    /// holes it stays meaningful. The exact classifier, sprites (which store
    /// the mesh's boundary edges), the GPU classifier and the GPU sweep
    /// answer it for any mesh; see `Sprite::generalizedWinding` for a
    /// sprite's error bound. The voxel representations do not. Values
    /// within 1e-9 of 1/2 (rounding) are ties and outside: a flat sheet's
    /// own points, whose value is exactly 1/2, lie on the surface, not inside.
    GeneralizedWinding,
};
constexpr std::size_t kRuleCount = 3;

template <> struct EnumNames<Rule> {
    static constexpr const char* kind = "rule";
    static constexpr EnumName<Rule> table[] = {
        {"parity", Rule::Parity}, {"winding", Rule::Winding}, {"generalized-winding", Rule::GeneralizedWinding}};
};

/// Parses "parity"/"winding"/"generalized-winding" (`parseEnum`); throws `InvalidArgument`.
Rule parseRule(const std::string& s);
const char* toString(Rule r);

/// Inside or outside by `rule`, from the signed count of crossings in front
/// of a point (its parity is the count's): for a mesh that bounds a solid
/// the generalized winding number is this count, so it reads as Winding.
constexpr bool insideByRule(int winding, Rule rule) {
    return rule == Rule::Parity ? (winding & 1) != 0 : winding != 0;
}

} // namespace vds
