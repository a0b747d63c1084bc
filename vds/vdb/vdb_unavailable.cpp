// vds: .vdb output in a build without OpenVDB (<vds/vdb.h>): every call
// says so in one line.
#include <vds/vdb.h>

#include <vds/error.h>

namespace vds {

namespace {

[[noreturn]] void refuse() {
    throw InvalidArgument("this vds was built without OpenVDB (libopenvdb-dev): it cannot write .vdb files");
}

} // namespace

bool vdbAvailable() { return false; }
std::string vdbLibrary() { return "no OpenVDB"; }
std::string vdsVersion() { return VDS_VERSION; }

void writeVdb(const std::string&, const SparseBand&, const VdbOptions&) { refuse(); }
void writeVdb(const std::string&, const Grid&, const std::uint8_t*, Rule, const VdbOptions&) { refuse(); }

} // namespace vds
