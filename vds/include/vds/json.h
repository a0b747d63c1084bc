// vds: the one JSON helper the reports need (eval, compare): a quoted string.
#pragma once

#include <cstdio>
#include <string>

namespace vds {

/// `s` as a JSON string literal: quotes and backslashes escaped, control
/// characters as \u00XX. Bytes >= 0x80 pass through (UTF-8 stays UTF-8).
inline std::string jsonString(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (static_cast<unsigned char>(c) < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
            continue;
        }
        out += c;
    }
    return out + "\"";
}

} // namespace vds
