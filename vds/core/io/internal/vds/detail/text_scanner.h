// Lines, tokens and numbers of text file formats (OBJ, OFF, ASCII PLY and STL,
// point lists), read from memory without a copy, independent of the locale.
//
// Every reader reports a problem as FormatError "<name>:<line>: <what>" for
// text and "<name>: byte <offset>: <what>" for binary data; the helpers here
// build those messages so that they read alike in every format.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace vds::detail {

[[noreturn]] void failAtLine(const std::string& name, std::size_t line, const std::string& what);
[[noreturn]] void failAtByte(const std::string& name, std::uint64_t offset, const std::string& what);

/// A token as it may be shown in a message: at most 24 characters, bytes
/// outside printable ASCII as \xNN, in quotes.
std::string quoted(std::string_view token);

/// A cursor over text held in memory, counting lines (LF or CRLF; a last
/// line without LF counts). Lines and tokens are views into the text. A
/// UTF-8 byte order mark in front, which some Windows programs write, is
/// skipped.
class TextScanner {
public:
    TextScanner(const char* data, std::size_t size);

    /// The text from the current position to the end of its line, without
    /// the line break (at a line start: the next line); false at the end.
    bool nextLine(std::string_view& line);
    /// The next whitespace-separated token, across lines; false at the end.
    bool nextToken(std::string_view& token);
    /// What is left of the current line, after the last token, without the
    /// line break; the scanner moves to the start of the next line.
    std::string_view restOfLine();

    /// Line of the last line or token returned (1-based).
    std::size_t line() const { return line_; }
    /// Bytes consumed so far: after `nextLine`, the start of the next line.
    std::size_t offset() const { return position_; }

private:
    std::string_view text_;
    std::size_t position_ = 0;
    std::size_t newlines_ = 0; ///< line breaks before position_
    std::size_t line_ = 0;
};

/// Whitespace-separated tokens of one line (space, tab, CR, VT, FF).
class Tokens {
public:
    explicit Tokens(std::string_view text) : rest_(text) {}
    bool next(std::string_view& token);
    /// The tokens left, without consuming them.
    std::size_t count() const;

private:
    std::string_view rest_;
};

/// `line` up to its first `#`.
std::string_view beforeComment(std::string_view line);

/// True for ' ', '\t', '\r', '\v', '\f' (not '\n').
inline bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// Case-insensitive comparison with a lowercase ASCII keyword.
bool equalsKeyword(std::string_view token, std::string_view lowercase);

enum class NumberStatus {
    Ok,
    Malformed,  ///< not a number, or characters after it
    OutOfRange, ///< a number too large for the type (floats: magnitude above the largest finite value)
    NotFinite,  ///< "nan", "inf", "infinity" (either sign)
};

/// The whole token as a number, as C's "%f" / "%lld" would write it ('+' also
/// allowed in front); floats are rounded to nearest, tiny ones to zero.
NumberStatus parseNumber(std::string_view token, float& value);
NumberStatus parseNumber(std::string_view token, double& value);
NumberStatus parseNumber(std::string_view token, std::int64_t& value);

/// A float coordinate for a mesh or a point set: finite, within float range.
/// Throws FormatError at `line` of `name` otherwise ("coordinate 'x' is ...").
float parseCoordinate(std::string_view token, const std::string& name, std::size_t line);

/// A message for a number that did not parse: "'1e39' is out of range for a
/// 32-bit float", "'abc' is not a number", "'nan' is not finite".
std::string numberProblem(NumberStatus status, std::string_view token, const char* type);

} // namespace vds::detail
