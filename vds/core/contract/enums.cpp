#include <vds/enum_names.h>

#include <vds/axis.h>
#include <vds/error.h>
#include <vds/rule.h>

namespace vds {

void throwUnknownName(const char* kind, std::string_view text, const std::vector<std::string>& names) {
    std::string expected;
    for (std::size_t k = 0; k < names.size(); ++k)
        expected += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
    throw InvalidArgument("unknown " + std::string(kind) + " '" + std::string(text) + "' (expected " + expected + ")");
}

Axis parseAxis(const std::string& s) { return parseEnum<Axis>(s); }
Rule parseRule(const std::string& s) { return parseEnum<Rule>(s); }
const char* toString(Axis a) { return enumName(a); }
const char* toString(Rule r) { return enumName(r); }

} // namespace vds
