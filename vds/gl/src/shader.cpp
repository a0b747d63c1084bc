#include <vds/gl/shader.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include <GL/glext.h>

#include <vds/error.h>

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

// Appends `text` (file `name`) to `out`, expanding includes recursively.
void expand(const std::string& text, const std::string& name, std::vector<std::string>& files,
            std::set<std::string>& included, std::string& out, int depth) {
    if (depth > 16) throw GlError(name + ": #include nested too deeply");
    const std::size_t number = fileNumber(files, name);
    out += "#line 1 " + std::to_string(number) + "\n";
    std::istringstream in(text);
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        std::size_t p = line.find_first_not_of(" \t");
        if (p != std::string::npos && line.compare(p, 8, "#include") == 0) {
            const std::size_t a = line.find('"', p), b = a == std::string::npos ? a : line.find('"', a + 1);
            if (b == std::string::npos)
                throw GlError(name + ":" + std::to_string(lineNo) + ": malformed #include (expected \"path\")");
            const std::string path = line.substr(a + 1, b - a - 1);
            if (!included.count(path)) {
                included.insert(path);
                expand(embeddedShader(path), path, files, included, out, depth + 1);
                out += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(number) + "\n";
            } else {
                out += "\n";
            }
            continue;
        }
        if (p != std::string::npos && line.compare(p, 12, "#pragma once") == 0) {
            out += "\n";
            continue;
        }
        out += line;
        out += '\n';
    }
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
    std::vector<std::string> names;
    std::set<std::string> included;
    std::string out = versionLine + "\n" + defines;
    if (!defines.empty() && defines.back() != '\n') out += '\n';
    const std::string& text = stage.source.empty() ? embeddedShader(stage.path) : stage.source;
    const std::string name = stage.path.empty() ? std::string("<source>") : stage.path;
    if (stage.source.empty()) included.insert(stage.path);
    expand(text, name, names, included, out, 0);
    if (files) *files = names;
    return out;
}

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
        const std::string text = assembleShader(stage, version, defines, &files);
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
