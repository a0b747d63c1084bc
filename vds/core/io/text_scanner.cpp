#include <vds/detail/text_scanner.h>

#include <charconv>
#include <cmath>
#include <system_error>

#include <vds/error.h>

namespace vds::detail {
namespace {

/// Drops a '+' in front of a number, which from_chars does not take.
std::string_view withoutPlus(std::string_view token) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '+' && token[1] != '-') token.remove_prefix(1);
    return token;
}

/// Whether a number from_chars found out of range had a negative exponent
/// (so it is too small, not too large).
bool negativeExponent(std::string_view token) {
    const std::size_t e = token.find_first_of("eE");
    return e != std::string_view::npos && e + 1 < token.size() && token[e + 1] == '-';
}

template <class Float> NumberStatus parseFloating(std::string_view token, Float& value) {
    token = withoutPlus(token);
    const char* first = token.data();
    const char* last = first + token.size();
    Float v{};
    const auto [end, ec] = std::from_chars(first, last, v);
    if (ec == std::errc::invalid_argument || end != last) return NumberStatus::Malformed;
    if (ec == std::errc::result_out_of_range) {
        if (!negativeExponent(token)) return NumberStatus::OutOfRange;
        value = token[0] == '-' ? -Float(0) : Float(0); // the nearest float to a tiny number
        return NumberStatus::Ok;
    }
    if (!std::isfinite(v)) return NumberStatus::NotFinite;
    value = v;
    return NumberStatus::Ok;
}

} // namespace

void failAtLine(const std::string& name, std::size_t line, const std::string& what) {
    throw FormatError(name + ":" + std::to_string(line) + ": " + what);
}

void failAtByte(const std::string& name, std::uint64_t offset, const std::string& what) {
    throw FormatError(name + ": byte " + std::to_string(offset) + ": " + what);
}

std::string quoted(std::string_view token) {
    static const char hex[] = "0123456789abcdef";
    constexpr std::size_t kShown = 24;
    std::string out = "'";
    for (std::size_t i = 0; i < token.size() && i < kShown; ++i) {
        const auto c = static_cast<unsigned char>(token[i]);
        if (c >= 0x20 && c < 0x7f) {
            out += char(c);
        } else {
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
    if (token.size() > kShown) out += "...";
    return out + "'";
}

TextScanner::TextScanner(const char* data, std::size_t size) : text_(data, size) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") position_ = 3;
}

bool TextScanner::nextLine(std::string_view& line) {
    if (position_ >= text_.size()) return false;
    line_ = newlines_ + 1;
    const std::size_t end = text_.find('\n', position_);
    const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
    line = text_.substr(position_, stop - position_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    position_ = stop == text_.size() ? stop : stop + 1;
    if (stop != text_.size()) ++newlines_;
    return true;
}

bool TextScanner::nextToken(std::string_view& token) {
    while (position_ < text_.size() && (isBlank(text_[position_]) || text_[position_] == '\n')) {
        if (text_[position_] == '\n') ++newlines_;
        ++position_;
    }
    if (position_ >= text_.size()) return false;
    line_ = newlines_ + 1;
    const std::size_t start = position_;
    while (position_ < text_.size() && !isBlank(text_[position_]) && text_[position_] != '\n') ++position_;
    token = text_.substr(start, position_ - start);
    return true;
}

std::string_view TextScanner::restOfLine() {
    std::string_view rest;
    nextLine(rest);
    return rest;
}

bool Tokens::next(std::string_view& token) {
    std::size_t i = 0;
    while (i < rest_.size() && isBlank(rest_[i])) ++i;
    std::size_t j = i;
    while (j < rest_.size() && !isBlank(rest_[j])) ++j;
    token = rest_.substr(i, j - i);
    rest_.remove_prefix(j);
    return !token.empty();
}

std::size_t Tokens::count() const {
    Tokens copy = *this;
    std::size_t n = 0;
    std::string_view token;
    while (copy.next(token)) ++n;
    return n;
}

std::string_view beforeComment(std::string_view line) { return line.substr(0, line.find('#')); }

bool equalsKeyword(std::string_view token, std::string_view lowercase) {
    if (token.size() != lowercase.size()) return false;
    for (std::size_t i = 0; i < token.size(); ++i) {
        char c = token[i];
        if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
        if (c != lowercase[i]) return false;
    }
    return true;
}

NumberStatus parseNumber(std::string_view token, float& value) { return parseFloating(token, value); }
NumberStatus parseNumber(std::string_view token, double& value) { return parseFloating(token, value); }

NumberStatus parseNumber(std::string_view token, std::int64_t& value) {
    token = withoutPlus(token);
    const char* first = token.data();
    const char* last = first + token.size();
    std::int64_t v = 0;
    const auto [end, ec] = std::from_chars(first, last, v);
    if (ec == std::errc::invalid_argument || end != last) return NumberStatus::Malformed;
    if (ec == std::errc::result_out_of_range) return NumberStatus::OutOfRange;
    value = v;
    return NumberStatus::Ok;
}

std::string numberProblem(NumberStatus status, std::string_view token, const char* type) {
    switch (status) {
    case NumberStatus::Ok: break;
    case NumberStatus::Malformed: return quoted(token) + " is not " + type;
    case NumberStatus::OutOfRange: return quoted(token) + " is out of range for " + type;
    case NumberStatus::NotFinite: return quoted(token) + " is not finite";
    }
    return quoted(token) + " is fine";
}

float parseCoordinate(std::string_view token, const std::string& name, std::size_t line) {
    float v = 0.0f;
    const NumberStatus status = parseNumber(token, v);
    if (status != NumberStatus::Ok) failAtLine(name, line, "coordinate " + numberProblem(status, token, "a 32-bit float"));
    return v;
}

} // namespace vds::detail
