// vds: the names of the library's option enums, in one place.
//
// Each enum that users pick by name (an axis, a rule, a bake method, a voxel
// representation, ...) has one table, a specialization of `EnumNames`; every
// parser, printer and command-line choice list reads that table.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace vds {

template <class E> struct EnumName {
    const char* name;
    E value;
};

/// Specialized for each named enum with `static constexpr EnumName<E> table[]`
/// and `static constexpr const char* kind` (e.g. "axis", for messages).
template <class E> struct EnumNames;

/// Throws `InvalidArgument`: "unknown <kind> '<text>' (expected a, b or c)";
/// `parseEnum`'s refusal, for callers that parse names of their own.
[[noreturn]] void throwUnknownName(const char* kind, std::string_view text, const std::vector<std::string>& names);

/// Every name of `E`, in table order.
template <class E> std::vector<std::string> enumNames() {
    std::vector<std::string> names;
    for (const auto& entry : EnumNames<E>::table) names.emplace_back(entry.name);
    return names;
}

/// The value named `text`; throws `InvalidArgument` naming the choices.
template <class E> E parseEnum(std::string_view text) {
    for (const auto& entry : EnumNames<E>::table)
        if (text == entry.name) return entry.value;
    throwUnknownName(EnumNames<E>::kind, text, enumNames<E>());
}

/// The name of `value` ("?" for a value outside the table).
template <class E> const char* enumName(E value) {
    for (const auto& entry : EnumNames<E>::table)
        if (entry.value == value) return entry.name;
    return "?";
}

} // namespace vds
