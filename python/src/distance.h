// vds._vds: the distance bindings (distance.cpp), registered by the module.
#pragma once

#include <pybind11/pybind11.h>

namespace vds::python {

/// Adds SignedDistance, signed_distance, closest_points and sdf to `m`.
void registerDistance(pybind11::module_& m);
/// Adds vdb_available and write_vdb (vdb.cpp) to `m`.
void registerVdb(pybind11::module_& m);

} // namespace vds::python
