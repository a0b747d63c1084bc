#include "gl_thread.h"

#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace vds::python {

std::atomic<bool> glLostInFork{false};
const char* const kLostInFork =
    "GL was in use when this process was forked from its parent, and a forked child cannot use the driver "
    "the parent started: use multiprocessing's \"spawn\" start method, or call vds._release_gl() before forking";
std::atomic<std::uint64_t> nextGlId{1};

namespace {
GlThread*& glThreadSlot() {
    static GlThread* thread = new GlThread; // leaked on purpose (GlThread's comment)
    return thread;
}
} // namespace

GlThread& glThread() { return *glThreadSlot(); }

/// In a child made by fork() the GL thread does not exist (only the forking
/// thread is copied): the child leaves the parent's objects alone (leaked)
/// and gets a GL thread of its own, which refuses GL where the parent's was
/// live (`glLostInFork`) and otherwise starts on the child's first GL call.
void forgetGlThreadInChild() {
    if (glThreadSlot()->live()) glLostInFork = true;
    glThreadSlot() = new GlThread;
}

void releaseGl() {
    py::gil_scoped_release released;
    glThread().stop();
}


} // namespace vds::python
