#include <vds/gl/shader.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <utility>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/detail/pi.h>

namespace vds {
namespace detail {
// Generated from shaders/vds by cmake/embed_shaders.cmake.
extern const ShaderFile kGlShaders[];
extern const std::size_t kGlShadersCount;
} // namespace detail

namespace {

// Every registered file by path; vds::gl's own files are there from the start.
// Entries are never removed, so references handed out stay valid.
struct Registry {
    std::mutex mutex;
    std::map<std::string, std::string> files;
    Registry() {
        for (std::size_t i = 0; i < detail::kGlShadersCount; ++i)
            files.emplace(detail::kGlShaders[i].path, std::string(detail::kGlShaders[i].text, detail::kGlShaders[i].size));
    }
};

Registry& registry() {
    static Registry r;
    return r;
}

std::size_t fileNumber(std::vector<std::string>& files, const std::string& name) {
    auto it = std::find(files.begin(), files.end(), name);
    if (it != files.end()) return std::size_t(it - files.begin());
    files.push_back(name);
    return files.size() - 1;
}

// Blanks out comments in `line` (a line of a file), carrying an open block
// comment over to the next line in `inBlock`.
std::string withoutComments(const std::string& line, bool& inBlock) {
    std::string code(line.size(), ' ');
    for (std::size_t i = 0; i < line.size(); ++i) {
        if (inBlock) {
            if (line.compare(i, 2, "*/") == 0) {
                inBlock = false;
                ++i;
            }
            continue;
        }
        if (line.compare(i, 2, "//") == 0) break;
        if (line.compare(i, 2, "/*") == 0) {
            inBlock = true;
            ++i;
            continue;
        }
        code[i] = line[i];
    }
    return code;
}

// The directive of a comment-free line: its name ("include", "if", ...) and
// the rest, or an empty name when the line is no directive.
std::pair<std::string, std::string> directiveOf(const std::string& code) {
    std::size_t p = code.find_first_not_of(" \t");
    if (p == std::string::npos || code[p] != '#') return {};
    p = code.find_first_not_of(" \t", p + 1);
    if (p == std::string::npos) return {};
    std::size_t e = p;
    while (e < code.size() && (std::isalnum(static_cast<unsigned char>(code[e])) || code[e] == '_')) ++e;
    std::string rest = code.substr(e);
    rest.erase(0, std::min(rest.size(), rest.find_first_not_of(" \t")));
    while (!rest.empty() && (rest.back() == ' ' || rest.back() == '\t' || rest.back() == '\r')) rest.pop_back();
    return {code.substr(p, e - p), rest};
}

std::string firstWord(const std::string& s) {
    std::size_t e = 0;
    while (e < s.size() && (std::isalnum(static_cast<unsigned char>(s[e])) || s[e] == '_')) ++e;
    return s.substr(0, e);
}

// What the resolver knows of a conditional group.
enum class Branch { Taken, Skipped, Unknown };

// The value of a simple `#if`/`#elif` condition: an integer literal, or
// `defined NAME` / `defined(NAME)`, optionally negated with `!`. Anything
// else is Unknown (the resolver then keeps the includes of both branches).
Branch evaluate(std::string expr, const std::set<std::string>& macros) {
    auto trim = [](std::string& s) {
        s.erase(0, std::min(s.size(), s.find_first_not_of(" \t")));
        while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.pop_back();
    };
    trim(expr);
    bool negate = false;
    while (!expr.empty() && expr[0] == '!') {
        negate = !negate;
        expr.erase(0, 1);
        trim(expr);
    }
    auto result = [&](bool value) { return value != negate ? Branch::Taken : Branch::Skipped; };
    if (!expr.empty() && std::all_of(expr.begin(), expr.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
        return result(std::stol(expr) != 0);
    if (expr.compare(0, 7, "defined") == 0) {
        std::string rest = expr.substr(7);
        trim(rest);
        bool paren = !rest.empty() && rest[0] == '(';
        if (paren) rest.erase(0, 1);
        trim(rest);
        const std::string name = firstWord(rest);
        rest.erase(0, name.size());
        trim(rest);
        if (paren) {
            if (rest.empty() || rest[0] != ')') return Branch::Unknown;
            rest.erase(0, 1);
            trim(rest);
        }
        if (!name.empty() && rest.empty()) return result(macros.count(name) > 0);
    }
    return Branch::Unknown;
}

struct Group {
    Branch branch;   // the branch being read
    bool anyTaken;   // a branch before this one was taken
    bool anyUnknown; // a branch before this one was unknown
};

bool skipping(const std::vector<Group>& groups) {
    return std::any_of(groups.begin(), groups.end(), [](const Group& g) { return g.branch == Branch::Skipped; });
}

// State of one assembly: file numbers, includes seen, macros defined so far.
struct Assembly {
    std::vector<std::string> files;
    std::set<std::string> included;
    std::set<std::string> macros;
};

// Appends `text` (file `name`) to `out`, expanding includes recursively:
// those inside comments or in a conditional branch known to be skipped are
// not expanded, and `#line` directives keep every line's file and number.
void expand(const std::string& text, const std::string& name, Assembly& as, std::string& out, int depth) {
    if (depth > 16) throw GlError(name + ": #include nested too deeply");
    const std::size_t number = fileNumber(as.files, name);
    out += "#line 1 " + std::to_string(number) + "\n";
    std::istringstream in(text);
    std::string line;
    int lineNo = 0;
    bool inBlock = false;
    std::vector<Group> groups;
    while (std::getline(in, line)) {
        ++lineNo;
        // Comments read as spaces, as the preprocessor reads them.
        const auto [directive, rest] = directiveOf(withoutComments(line, inBlock));
        const bool skipped = skipping(groups);
        if (directive == "ifdef" || directive == "ifndef") {
            const bool defined = as.macros.count(firstWord(rest)) > 0;
            const Branch b = (directive == "ifdef") == defined ? Branch::Taken : Branch::Skipped;
            groups.push_back({b, b == Branch::Taken, false});
        } else if (directive == "if") {
            const Branch b = evaluate(rest, as.macros);
            groups.push_back({b, b == Branch::Taken, false});
        } else if (directive == "elif" && !groups.empty()) {
            Group& g = groups.back();
            g.anyUnknown |= g.branch == Branch::Unknown;
            Branch b = g.anyTaken ? Branch::Skipped : evaluate(rest, as.macros);
            if (b == Branch::Taken && g.anyUnknown) b = Branch::Unknown; // an unknown branch before may have been taken
            g.branch = b;
            g.anyTaken |= b == Branch::Taken;
        } else if (directive == "else" && !groups.empty()) {
            Group& g = groups.back();
            g.anyUnknown |= g.branch == Branch::Unknown;
            g.branch = g.anyTaken ? Branch::Skipped : g.anyUnknown ? Branch::Unknown : Branch::Taken;
            g.anyTaken = true;
        } else if (directive == "endif" && !groups.empty()) {
            groups.pop_back();
        } else if (directive == "define" && !skipped) { // (in an unknown branch: maybe defined, taken as defined)
            as.macros.insert(firstWord(rest));
        } else if (directive == "undef" && !skipped) {
            as.macros.erase(firstWord(rest));
        } else if (directive == "include") {
            if (skipped) { // the driver's preprocessor would skip it too, but may not know the directive
                out += "\n";
                continue;
            }
            const std::size_t a = rest.find('"'), b = a == std::string::npos ? a : rest.find('"', a + 1);
            if (b == std::string::npos)
                throw GlError(name + ":" + std::to_string(lineNo) + ": malformed #include (expected \"path\")");
            const std::string path = rest.substr(a + 1, b - a - 1);
            if (!as.included.count(path)) {
                as.included.insert(path);
                expand(embeddedShader(path), path, as, out, depth + 1);
                out += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(number) + "\n";
            } else {
                out += "\n";
            }
            continue;
        } else if (directive == "pragma" && firstWord(rest) == "once") {
            out += "\n";
            continue;
        } else if (directive == "version") {
            // Only the top of the assembled text may hold one: assembleShader
            // took it from the stage's own source; an included file's is dropped.
            out += "\n";
            continue;
        }
        out += line;
        out += '\n';
    }
}

// The stage's own `#version` line, if its first directive-or-code line is
// one (comments and blank lines may come before it), and its line number.
std::pair<std::string, int> ownVersion(const std::string& text) {
    std::istringstream in(text);
    std::string line;
    bool inBlock = false;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        const std::string code = withoutComments(line, inBlock);
        if (code.find_first_not_of(" \t\r") == std::string::npos) continue;
        const auto [directive, rest] = directiveOf(code);
        if (directive == "version") return {"#version " + rest, lineNo};
        break;
    }
    return {"", 0};
}

// Rewrites "N:L(C): ..." (Mesa) and "N(L) : ..." (NVIDIA) to "file:L: ...".
std::string restoreNames(const std::string& log, const std::vector<std::string>& files) {
    std::istringstream in(log);
    std::string line, out;
    while (std::getline(in, line)) {
        std::size_t i = 0;
        while (i < line.size() && std::isdigit(static_cast<unsigned char>(line[i]))) ++i;
        if (i > 0 && i < line.size() && (line[i] == ':' || line[i] == '(')) {
            const std::size_t n = std::stoul(line.substr(0, i));
            std::size_t j = i + 1, k = j;
            while (k < line.size() && std::isdigit(static_cast<unsigned char>(line[k]))) ++k;
            if (n < files.size() && k > j) {
                std::string rest = line.substr(k);
                if (!rest.empty() && rest[0] == ')') rest = rest.substr(1);
                line = files[n] + ":" + line.substr(j, k - j) + rest;
            }
        }
        out += line + " | ";
    }
    if (out.size() >= 3) out.resize(out.size() - 3);
    return out;
}

const char* stageName(GLenum type) {
    switch (type) {
    case GL_VERTEX_SHADER: return "vertex";
    case GL_FRAGMENT_SHADER: return "fragment";
    case GL_GEOMETRY_SHADER: return "geometry";
    case GL_COMPUTE_SHADER: return "compute";
    case GL_TESS_CONTROL_SHADER: return "tessellation control";
    case GL_TESS_EVALUATION_SHADER: return "tessellation evaluation";
    default: return "unknown";
    }
}

} // namespace

void registerShaders(const ShaderFile* files, std::size_t count) {
    Registry& r = registry();
    const std::lock_guard<std::mutex> lock(r.mutex);
    for (std::size_t i = 0; i < count; ++i) {
        const std::string text(files[i].text, files[i].size);
        const auto [it, added] = r.files.emplace(files[i].path, text);
        if (!added && it->second != text)
            throw InvalidArgument(std::string("shader '") + files[i].path + "' is registered twice with different text");
    }
}

const std::string& embeddedShader(const std::string& path) {
    Registry& r = registry();
    const std::lock_guard<std::mutex> lock(r.mutex);
    auto it = r.files.find(path);
    if (it == r.files.end()) throw InvalidArgument("no embedded shader '" + path + "'");
    return it->second;
}

std::vector<std::string> embeddedShaderPaths() {
    Registry& r = registry();
    const std::lock_guard<std::mutex> lock(r.mutex);
    std::vector<std::string> paths;
    for (const auto& entry : r.files) paths.push_back(entry.first);
    return paths;
}

std::string assembleShader(const ShaderStage& stage, const std::string& versionLine, const std::string& defines,
                           std::vector<std::string>* files) {
    Assembly as;
    const std::string& text = stage.source.empty() ? embeddedShader(stage.path) : stage.source;
    const std::string name = stage.path.empty() ? std::string("<source>") : stage.path;
    const std::string own = ownVersion(text).first;
    std::string out = (own.empty() ? versionLine : own) + "\n" + defines;
    if (!defines.empty() && defines.back() != '\n') out += '\n';
    // The macros the resolver's #if evaluation knows: the caller's defines
    // and GLSL's own, then those the files define as they are read.
    as.macros = {"GL_core_profile", "__VERSION__", "__LINE__", "__FILE__"};
    {
        std::istringstream in(defines);
        std::string line;
        bool inBlock = false;
        while (std::getline(in, line)) {
            const auto [directive, rest] = directiveOf(withoutComments(line, inBlock));
            if (directive == "define") as.macros.insert(firstWord(rest));
        }
    }
    if (stage.source.empty()) as.included.insert(stage.path);
    expand(text, name, as, out, 0);
    if (files) *files = as.files;
    return out;
}

namespace {
// The library's constants, defined in every program it builds, ahead of the
// caller's defines: GLSL takes them from the C++ (vpt.glsl's defaults serve
// a user's shader built elsewhere).
std::string libraryDefines() {
    std::ostringstream out;
    out.precision(17);
    out << "#define VDS_FOUR_PI " << detail::kFourPi << "\n";
    return out.str();
}
} // namespace

Program buildProgram(const std::vector<ShaderStage>& stages, const std::string& defines) {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    const std::string version = (major > 4 || (major == 4 && minor >= 5)) ? "#version 450 core" : "#version 430 core";
    Program program = Program::create();
    std::vector<Shader> shaders;
    std::string names;
    for (const auto& stage : stages) {
        std::vector<std::string> files;
        const std::string text = assembleShader(stage, version, libraryDefines() + defines, &files);
        Shader shader = Shader::create(stage.type);
        const char* src = text.c_str();
        glShaderSource(shader.id(), 1, &src, nullptr);
        glCompileShader(shader.id());
        GLint ok = 0;
        glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
        if (!ok) {
            GLint length = 0;
            glGetShaderiv(shader.id(), GL_INFO_LOG_LENGTH, &length);
            std::string log(std::size_t(std::max(length, 1)), '\0');
            glGetShaderInfoLog(shader.id(), length, nullptr, log.data());
            log.resize(std::strlen(log.c_str()));
            throw GlError(std::string(stageName(stage.type)) + " shader " + files.front() +
                          " does not compile: " + restoreNames(log, files));
        }
        glAttachShader(program.id(), shader.id());
        names += (names.empty() ? "" : ", ") + files.front();
        shaders.push_back(std::move(shader));
    }
    glLinkProgram(program.id());
    GLint ok = 0;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &length);
        std::string log(std::size_t(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program.id(), length, nullptr, log.data());
        log.resize(std::strlen(log.c_str()));
        throw GlError("program (" + names + ") does not link: " + restoreNames(log, {}));
    }
    for (auto& s : shaders) glDetachShader(program.id(), s.id());
    return program;
}

} // namespace vds
