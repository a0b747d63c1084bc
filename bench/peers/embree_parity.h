// vds_peers_bench: Embree 3 ray parity, the inside test of trimesh's
// `contains` and of Open3D's RaycastingScene: shoot one ray from the point in
// a fixed direction, count every surface it crosses, odd is inside.
#pragma once

#include <memory>
#include <string>

#include <vds/classify.h>
#include <vds/mesh.h>


namespace vds::peers {

/// A `Classifier` of Method::Custom, parity only. Builds an Embree scene (BVH) over the mesh on `threads` threads (0: one
/// per hardware thread); queries run on as many, in a TBB arena. Throws
/// `std::runtime_error` with Embree's error code if the device or scene
/// cannot be made.
std::unique_ptr<Classifier> makeEmbreeParity(MeshView mesh, unsigned threads);

/// "Embree 3.13.5", the version compiled against.
std::string embreeVersion();

} // namespace vds::peers
