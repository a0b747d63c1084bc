// vds — volumetric point-in-solid tests: the manual.
//
// Is this point inside that solid? vds bakes a closed triangle mesh once into
// a volumetric depth sprite (VDS: a layered depth image, every surface
// crossing of every texel's ray along one axis; Trapp & Döllner 2008) and
// answers with the volumetric parity test (VPT): count the crossings in
// front of the point. From C++ for millions of points, from any GLSL stage,
// and exactly on the triangles themselves when an answer must be exact.
//
// This header includes everything in vds::core and says, in the order a
// program uses them, what each entry point takes and gives. The other
// headers hold the details; nothing here needs GL.
//
// ---- Layers and linking ---------------------------------------------------
//
//   vds::core   this header's world: meshes, sprites, the CPU VPT, the exact
//               classifier, the CPU baker, the .vds file. Needs GLM in its
//               headers; links no GL (a server or a Python process that only
//               classifies never loads libEGL).
//   vds::gl     headless EGL contexts, GL objects, shaders, GPU bakers and
//               classifiers, sprites as 3D textures (<vds/gl/context.h>,
//               <vds/gl/sprite.h>, <vds/gl/shader.h>). Linking it makes the GL
//               bake methods available to `bake()` below.
//   vds::voxel  slicemaps and solid voxelizations, the representations the
//               VDS is compared with (<vds/voxel/...>).
//   vds::eval   accuracy and comparison reports, images, charts (<vds/eval/...>).
//   vds::vds    all of the above.
//
//   find_package(vds) then target_link_libraries(app PRIVATE vds::core).
//
// ---- Conventions ----------------------------------------------------------
//
//   Coordinates   mesh coordinates (the units of the file) unless a name says
//                 otherwise; a sprite moved by `Sprite::transform` answers in
//                 the coordinates it was moved to ("world").
//   Arrays        the caller owns every array it passes; calls read or write
//                 them only while they run. Arrays of points are given as
//                 pointer + count (`glm::vec3*`, packed x y z floats), or as
//                 pointer + count + stride in bytes (`const float*`), so
//                 points may sit inside larger records.
//   Labels        one byte per point: 1 inside, 0 outside.
//   Errors        everything a user can cause is thrown as a subclass of
//                 `vds::Error` (<vds/error.h>) whose what() is one line:
//                 IoError (file system), FormatError (bad file content),
//                 InvalidArgument (an option out of range), InvalidMesh,
//                 GlUnavailable, GlError, OutOfMemory. Broken caller
//                 contracts (null arrays with a count) are asserted. The
//                 library never exits or prints.
//   Threads       functions with `threads` options split work over that many
//                 threads (0: one per hardware thread), the caller included.
//                 Sprites, meshes and classifiers are read-only when
//                 queried: any number of threads may query one at once.
//
// ---- 1. A mesh in -----------------------------------------------------------
//
//   TriangleMesh loadMesh(path)                          <vds/mesh_io.h>
//     OBJ, PLY, STL or OFF; polygons fanned into triangles. IoError,
//     FormatError (naming the line or byte).
//   TriangleMesh { positions: #V vec3, triangles: #F uvec3 (indices into
//     positions, counter-clockwise seen from outside) }; MeshView is the
//     same as a non-owning view over caller arrays.    <vds/mesh.h>
//   MeshReport validateMesh(mesh)
//     counts boundary, non-manifold and flipped edges, degenerate
//     triangles, non-finite vertices, bad indices; `closed()` says whether
//     the mesh bounds a solid, `summary()` says it in one line.
//
// ---- 2. Bake a sprite -------------------------------------------------------
//
//   Sprite bake(mesh, BakeOptions, GlContext* gl = nullptr)   <vds/bake.h>
//     BakeOptions: resolution (texels on the longer side of the view,
//     1..16384, default 1024), axis (X, Y, Z; `chooseViewAxis(mesh)` picks
//     the one with the fewest layers), method (Lists: GL fragment lists,
//     default; Peel: GL depth peeling; Cpu: exact ray casting, no GL),
//     progress callback. All three methods give the same layers (GL ones up
//     to the rasterizer's sub-texel snapping). Unusable meshes throw
//     InvalidMesh; open or non-manifold ones are baked and marked
//     `SolidStatus::Open`. GL methods need vds::gl linked and a GL context
//     (given, or made for the call); the caller's current context is the
//     same afterwards.
//   Sprite bakeCpu(mesh, options)      the Cpu method, on every core.
//   BakeOptions::timings -> BakeTimings: wall and GPU time of each phase
//     (validation, compile, upload, raster, scan, sort, texture, read-back,
//     assembly); `report()` prints them (`vds bake --verbose`).
//
// ---- 3. Keep it ---------------------------------------------------------------
//
//   writeSprite(sprite, path) / Sprite readSprite(path)      <vds/vds_file.h>
//     One OpenEXR deep image, lossless, checksummed; written atomically
//     (temporary file, then rename); the reader refuses damaged files with
//     FormatError before allocating for sizes the file cannot hold.
//   std::vector<char> encodeSprite(sprite) / Sprite decodeSprite(data, size)
//     the same bytes in memory.
//
// ---- 4. Ask it ----------------------------------------------------------------
//
//   bool Sprite::contains(p, Rule rule = Rule::Parity)        <vds/sprite.h>
//     Rule::Parity: odd crossings in front of p (the paper's test);
//     Rule::Winding: entering crossings +1, leaving -1, inside if non-zero
//     (nested or overlapping shells); Rule::GeneralizedWinding: the
//     generalized winding number above 1/2 (open meshes; the exact
//     classifier and sprites answer it for any mesh, a sprite from the
//     boundary edges it stores; the GPU classifier and vpt.glsl too, in
//     float, from the edges GpuSprite uploads).
//     Points outside
//     the sprite's box are outside. Errors of a sprite lie within about half
//     a texel diagonal of the surface (docs/accuracy.md).
//   classify(sprite, points, count, labels, ClassifyOptions{rule, threads, layout})
//   classify(sprite, xyz, count, strideBytes, labels, options)
//     batches on threads; the same answers as `contains`. QueryLayout::Auto
//     builds a 16-byte-a-column table for large batches (one cache miss a
//     point).
//
// ---- 4b. Ask it for a whole grid ------------------------------------------------
//
//   Grid{box, dims}; cell (i, j, k) centre lo + (i+1/2, j+1/2, k+1/2)
//     * (hi - lo) / dims, labels in C order [i][j][k]      <vds/occupancy.h>
//   voxelize(mesh, grid, cells, ClassifyOptions{rule, threads})
//     exact labels by one sweep per column: equal to the exact classifier
//     on every cell centre.
//   occupancy(sprite, grid, cells, options)   the sprite's labels, one walk
//     per column; equal to `contains` on every cell.
//   packLabels(cells, count, bits)   eight cells a byte (numpy's packbits).
//   readNpy / npyPoints / writeNpy   numpy .npy in and out    <vds/npy.h>
//   Sprite::transform(mat4)  moves, rotates or scales the sprite (affine,
//     invertible) without baking again.
//
// ---- 5. Exact answers ---------------------------------------------------------
//
//   ExactClassifier(mesh, axis)                               <vds/exact.h>
//     the yardstick: exact orientation predicates with a top-left tie rule
//     on the triangles themselves; `contains`, `winding`,
//     `generalizedWinding` (the Antipodal split: integer ray count plus a
//     boundary term over the boundary edges), `classify` (pointer + count,
//     or + stride). Construction O(n log n); queries thread safe.
//   CertifiedClassifier(mesh, CertifiedOptions{resolution, axis, threads})
//     the exact classifier's answers at close to a sprite's speed: per
//     texel, bands where the surface may be; outside them the answer is
//     proven, inside them the exact classifier decides. <vds/certified.h>
//
// ---- 6. On the GPU (vds::gl) --------------------------------------------------
//
//   GlContext            a headless EGL context (NVIDIA's EGL device,
//                        Mesa's llvmpipe without a GPU); GlUnavailable with
//                        the reasons when none can be had. `glAvailable()`
//                        is the cheap probe.               <vds/gl/context.h>
//   GpuSprite(sprite)    the paper's R32F 3D texture and placement, for
//                        shaders/vds/vpt.glsl (`vdsContains(...)` in any
//                        stage; the same answers as the CPU), and the
//                        boundary edges for `vdsContainsGeneralized(...)`
//                        (setBoundaryUniforms).              <vds/gl/sprite.h>
//   GpuClassifier        the VPT over many points in a compute shader: host
//                        arrays in and out, or points and labels already in
//                        GL buffers (no host round trip).
//   bakeToGpu(mesh, options, gl)  a GpuSprite straight from the fragment-list
//                        bake, nothing read back.            <vds/gl/bake.h>
//   Lifetime: a context is current on the thread that made it; destroying
//   or moving one never changes another current context; `CurrentContext`
//   scopes restore the caller's; no GL call happens once the process exits.
#pragma once

#include <vds/axis.h>
#include <vds/bake.h>
#include <vds/certified.h>
#include <vds/classify.h>
#include <vds/enum_names.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/grid.h>
#include <vds/mesh.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>
#include <vds/occupancy.h>
#include <vds/rule.h>
#include <vds/sprite.h>
#include <vds/vds_file.h>
