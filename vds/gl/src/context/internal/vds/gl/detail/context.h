// vds::gl internal: what the library's rooms ask of a context beyond
// <vds/gl/context.h> (context.cpp).
#pragma once

#include <vds/gl/context.h>

namespace vds::detail {

/// False once the process has begun to exit (see the lifetime rules of
/// <vds/gl/context.h>): GL objects and contexts then skip their GL and EGL calls.
bool glUsable() noexcept;

/// True on llvmpipe, softpipe, SwiftShader and software platforms: how
/// `GlInfo::software` is read when a context is made or adopted.
bool isSoftwareRenderer(const GlInfo& info);

} // namespace vds::detail
