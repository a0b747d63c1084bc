// vds: GLSL sources embedded in the library, `#include` resolution, programs.
//
// The files under shaders/ are compiled into the library (and installed under
// share/vds/shaders). A shader is assembled as: the context's `#version` line,
// the caller's defines, then the file, with every `#include "path"` replaced
// by that file (once per program: repeated includes are skipped) between
// `#line` directives. Each file gets its own source-string number, and the
// driver's log is rewritten so errors name the real file and line.
#pragma once

#include <string>
#include <vector>

#include <GL/gl.h>

#include <vds/gl_objects.h>

namespace vds {

/// The text of an embedded shader file, e.g. "vds/vpt.glsl". Throws
/// `InvalidArgument` if there is no such file.
const std::string& embeddedShader(const std::string& path);

/// Every embedded shader's path.
std::vector<std::string> embeddedShaderPaths();

/// One stage of a program: its type and either an embedded file path or
/// source text of the caller's (which may `#include` embedded files).
struct ShaderStage {
    GLenum type;
    std::string path;   ///< embedded file, used when `source` is empty
    std::string source; ///< caller's text; `path` then only names it in errors
};

/// Resolves includes for one stage. `files` receives the file name of each
/// source-string number used in the `#line` directives.
std::string assembleShader(const ShaderStage& stage, const std::string& versionLine, const std::string& defines,
                           std::vector<std::string>* files = nullptr);

/// Compiles and links a program from stages on the current context. Throws
/// `GlError` with the log (file names restored) on failure.
/// `defines` is inserted after `#version`, e.g. "#define VDS_MAX_LAYERS 64\n".
Program buildProgram(const std::vector<ShaderStage>& stages, const std::string& defines = "");

} // namespace vds
