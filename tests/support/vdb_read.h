// Reading back a .vdb that a test wrote, with OpenVDB itself: the tests of
// vds::vdb and of the tool's .vdb outputs (only where the build has OpenVDB,
// VDS_TEST_OPENVDB).
#pragma once

#include <string>

#include <gtest/gtest.h>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

namespace vds::test {

/// The one grid of the file at `path`, as `GridType` (null when it is another type).
template <class GridType> typename GridType::Ptr readOnlyGrid(const std::string& path) {
    openvdb::initialize();
    openvdb::io::File file(path);
    file.open();
    const openvdb::GridPtrVecPtr grids = file.getGrids();
    file.close();
    EXPECT_EQ(grids->size(), 1u);
    return openvdb::gridPtrCast<GridType>(grids->front());
}

} // namespace vds::test
