#include <vds/enum_names.h>

#include <algorithm>

#include <vds/axis.h>
#include <vds/error.h>
#include <vds/rule.h>

namespace vds {

namespace {

// Levenshtein distance, for "did you mean".
std::size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

} // namespace

std::string nearestName(std::string_view word, const std::vector<std::string>& names) {
    std::string best;
    std::size_t bestDistance = std::max<std::size_t>(1, word.size() / 3) + 1;
    for (const std::string& name : names) {
        const std::size_t d = editDistance(word, name);
        if (d < bestDistance) {
            bestDistance = d;
            best = name;
        }
    }
    return best;
}

void throwUnknownName(const char* kind, std::string_view text, const std::vector<std::string>& names) {
    std::string expected;
    for (std::size_t k = 0; k < names.size(); ++k)
        expected += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
    const std::string nearest = nearestName(text, names);
    throw InvalidArgument("unknown " + std::string(kind) + " '" + std::string(text) + "' (expected " + expected + ")" +
                          (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)"));
}

Axis parseAxis(const std::string& s) { return parseEnum<Axis>(s); }
Rule parseRule(const std::string& s) { return parseEnum<Rule>(s); }
const char* toString(Axis a) { return enumName(a); }
const char* toString(Rule r) { return enumName(r); }

} // namespace vds
