// The same program through the public manual: it builds, so the refusal of
// outside_program.cpp is the wall's and nothing else's.
#include <vds/vds.h>

int main() { return vds::kMaxResolution > 0 ? 0 : 1; }
