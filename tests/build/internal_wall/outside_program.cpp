// A program outside the library (as the tool, Python, the samples and the
// benchmarks are) that reaches for an internal header: the build must refuse
// it, since only the library's layers and its tests link vds_core_internal.
#include <vds/detail/parallel.h>

int main() { return 0; }
