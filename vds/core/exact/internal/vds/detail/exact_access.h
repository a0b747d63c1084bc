// vds: test hooks into the exact classifier (not installed).
#pragma once

#include <glm/vec3.hpp>

#include <vds/exact.h>

namespace vds::detail {

struct ExactAccess {
    /// Same answer as `ExactClassifier::contains`, by a loop over every
    /// triangle (no acceleration): the reference the accelerated path is
    /// tested against.
    static bool containsBruteForce(const ExactClassifier& exact, const glm::vec3& p, Rule rule = Rule::Parity);
};

} // namespace vds::detail
