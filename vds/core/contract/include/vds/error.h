// vds: the library's error policy.
//
// Library code never terminates the process. Broken caller contracts are
// `assert`ed; everything a user can cause (a bad file, a bad mesh, no GL, a
// shader that does not compile, a request too large to hold) is thrown as one
// of the exceptions below. Only a program's `main` turns them into exit codes
// and one-line messages.
#pragma once

#include <stdexcept>
#include <string>

namespace vds {

/// Base of every exception the library throws. `what()` is one line, fit to be
/// printed as is after the program's name.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A file could not be opened, read, written or renamed.
class IoError : public Error {
public:
    using Error::Error;
};

/// A file was read but its content is truncated, corrupt or inconsistent.
class FormatError : public Error {
public:
    using Error::Error;
};

/// An argument a user chose is out of range (resolution 0, unknown axis, ...).
class InvalidArgument : public Error {
public:
    using Error::Error;
};

/// A mesh that cannot be processed: empty, non-finite coordinates, bad indices.
class InvalidMesh : public Error {
public:
    using Error::Error;
};

/// No OpenGL 4.3+ core context could be created (no EGL, no driver, ...).
class GlUnavailable : public Error {
public:
    using Error::Error;
};

/// A GL call failed at run time, or a shader did not compile or link; the
/// message carries the driver's log with file names restored.
class GlError : public Error {
public:
    using Error::Error;
};

/// A request needs more memory than can be had (host, GL buffer limits).
class OutOfMemory : public Error {
public:
    using Error::Error;
};

} // namespace vds
