// vds: GLSL sources embedded in the library, `#include` resolution, programs.
//
// Every GLSL file under shaders/ (shaders/vds and shaders/voxel) is compiled
// into vds::gl and installed under share/vds/shaders (the CMake variable
// `vds_SHADER_DIR` of the package names that folder): any `#include
// "vds/..."` or `"voxel/..."` resolves from the first call, with nothing to
// register. A program may add its own files with `registerShaders` (or the
// CMake function vds_embed_shaders).
//
// A stage is assembled as: the stage's own `#version` line if its source
// starts with one (comments and blank lines may come first), else the
// context's; the caller's defines; then the file, with every `#include
// "path"` replaced by that file (once per program: repeated includes and
// `#pragma once` are skipped) between `#line` directives. Includes inside
// comments, and inside conditional branches the resolver can tell are
// skipped (`#if 0`/`#if 1`, `#if [!]defined(NAME)`, `#ifdef`, `#ifndef`,
// `#elif`, `#else`, with the macros of the defines and of the text read so
// far), are not pulled in; under any other condition the include is kept
// and the driver's preprocessor decides. Each file gets its own
// source-string number, and the driver's log is rewritten so errors name
// the real file and line.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <GL/gl.h>

#include <vds/gl/objects.h>

namespace vds {

/// One embedded file: its path under shaders/ (e.g. "voxel/grid.glsl") and
/// its text, `size` bytes. The table holding it must have static storage.
struct ShaderFile {
    const char* path;
    const char* text;
    std::size_t size;
};

/// Makes `count` files known to `embeddedShader` and `#include`. Thread safe;
/// registering the same table again does nothing. Throws `InvalidArgument`
/// if a path is already known with a different text.
void registerShaders(const ShaderFile* files, std::size_t count);

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
/// `defines` is inserted after `#version`, e.g. "#define VDS_MAX_LAYERS 64\n",
/// after the library's own constants (VDS_FOUR_PI, from the C++ value).
Program buildProgram(const std::vector<ShaderStage>& stages, const std::string& defines = "");

} // namespace vds
