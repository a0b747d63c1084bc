// vds — volumetric point-in-solid tests: the manual.
//
// Is this point inside that solid? vds bakes a closed triangle mesh once into
// a volumetric depth sprite (VDS: a layered depth image, every surface
// crossing of every texel's ray along one axis; Trapp & Döllner 2008) and
// answers with the volumetric parity test (VPT): count the crossings in
// front of the point. From C++ for millions of points, from any GLSL stage,
// and exactly on the triangles themselves when an answer must be exact.
//
// This header includes everything in vds::core and names, in the order a
// program uses them, every public function and type of every layer (a test,
// tests/manual/check_manual.py, fails when one is missing); each entry says
// where it lives. The headers hold the details. Nothing in vds::core needs GL.
//
// ---- Layers and linking ---------------------------------------------------
//
//   target      include              what
//   vds::core   <vds/...>            meshes, the one classify contract,
//                                    sprites and the CPU VPT, the exact and
//                                    certified classifiers, the CPU baker,
//                                    occupancy grids, the .vds file. Needs
//                                    GLM in its headers; links no GL.
//   vds::gl     <vds/gl/...>         GL contexts, objects, shaders, the GL
//                                    bakers, sprites as 3D textures, GPU
//                                    classifiers and grids.
//   vds::voxel  <vds/voxel/...>      slicemaps and solid voxelizations, the
//                                    representations the VDS is compared with.
//   vds::vds    <vds/all.h>          the umbrella: core, gl and voxel, and
//                                    `makeClassifier` / `bake` for any method.
//   vds::eval   <vds/eval/...>       accuracy and comparison reports, charts, PNG.
//
//   find_package(vds) then target_link_libraries(app PRIVATE vds::core) (or
//   vds::gl, vds::vds, ...). No linker option, no registry: what a program
//   calls is what it links.
//
// ---- Conventions ----------------------------------------------------------
//
//   Coordinates   mesh coordinates (the units of the file) unless a name says
//                 otherwise; a sprite moved by `Sprite::transform` answers in
//                 the coordinates it was moved to ("world").
//   Points        a `PointsView`: pointer, count, byte stride, float or
//                 double (`PointsView::floats`, `PointsView::doubles`; a
//                 `std::vector<glm::vec3>` converts), so points may sit
//                 inside larger records. Caller-owned, read while a call runs.
//   Labels        one byte per point: 1 inside, 0 outside, caller-owned.
//   Options       one `ClassifyOptions` {rule, threads, layout, boundary,
//                 stats} for every classify and occupancy call.
//   Errors        everything a user can cause is thrown as a subclass of
//                 `Error` (<vds/error.h>) whose what() is one line: IoError
//                 (file system), FormatError (bad file content),
//                 InvalidArgument (an option out of range, a rule a method
//                 cannot answer), InvalidMesh, GlUnavailable, GlError,
//                 OutOfMemory. Broken caller contracts (null arrays with a
//                 count) are asserted. The library never exits or prints.
//   Threads       `threads` options split work over that many threads (0: one
//                 per hardware thread), the caller included. Meshes, sprites
//                 and CPU classifiers are read-only when queried: any number
//                 of threads may query one at once.
//   Names         every enum has names (`EnumNames`, `EnumName`): `enumName`,
//                 `enumNames`, `parseEnum` (unknown names throw through
//                 `throwUnknownName`, listing the accepted ones and the
//                 `nearestName` a typo was near); the CLI and
//                 Python use the same names. Per enum: `toString`,
//                 `parseAxis`, `parseRule`, `parseBakeMethod`.
//
// ---- 1. A mesh in -----------------------------------------------------------
//
//   TriangleMesh loadMesh(path)                          <vds/mesh_io.h>
//     OBJ, PLY, STL or OFF (`MeshFormat`, `meshFormatOf(path)`); polygons
//     fanned into triangles. IoError, FormatError (naming the line or byte).
//     `parseMesh(data, size, format, name)` reads bytes in memory.
//   TriangleMesh { positions: #V vec3, triangles: #F uvec3 (indices into
//     positions, counter-clockwise seen from outside) }; MeshView is the
//     same as a non-owning view over caller arrays.    <vds/mesh.h>
//   AdaptedMesh fromEigen(V, F) / fromOpenMesh(mesh)   <vds/interop/eigen.h>,
//     <vds/interop/openmesh.h>: a MeshView of libigl's (V, F) matrices or of
//     an OpenMesh mesh, viewed in place where the layout is vds's own and
//     copied otherwise (<vds/interop/adapted_mesh.h>); header-only, bring
//     your own Eigen or OpenMesh. Python takes numpy arrays.
//   MeshReport validateMesh(mesh)                      <vds/mesh_check.h>
//     (the report itself: <vds/mesh.h>) the one account of a mesh: boundary, non-manifold, odd and flipped
//     edges, inside-out parts, the generalized winding number's boundary
//     (`windingBoundaryText(n)` its words), degenerate triangles, non-finite
//     vertices, bad indices; `closed()` says whether the mesh bounds a solid
//     by parity, `oriented()` by winding, `misoriented()` whether the rules
//     disagree on a closed mesh, `status()` the one word ("closed",
//     "mis-oriented", "open"; `solidStatus(report)` a sprite's, and
//     `statusWord(status, validation)` a sprite's word back), `summary()`
//     says it in one line. `requireUsable(report, name)` and
//     `requireInsideDefined(report, name, rule, flags)` throw InvalidMesh where a
//     mesh cannot be used or its inside is not defined by a rule;
//     `insideWarning(report, rule, flags)` is the one-line warning otherwise,
//     `insideNote(report, rule, flags)` what to tell of a defined inside;
//     `openMeshMessage(report, name, rule, flags)`, `openSpriteMessage` and
//     `misorientedMessage(report, name)` are the one wording for a mesh or
//     sprite that bounds no solid by a rule (`MeshFlags`: the flags a
//     caller has, named only where it has them);
//     `flat()` / `requireVolume(report, name)` the one for a flat sheet,
//     which bounds no volume (bake, classify, voxelize, compare refuse it).
//   MeshValidation(mesh)   validation that keeps what it found beside its
//     `report()`, for `chooseViewAxis(mesh, validation, resolution)`.
//   Box meshBounds(mesh)    the axis-aligned bounds.
//   sampleSurface(mesh, count, seed, points, triangles)     <vds/sample.h>
//     area-weighted points on the triangles (SurfaceSamples), the same bit
//     for bit everywhere from a seed (`sampleUniform`: the generator, written
//     down); InvalidMesh for a mesh with no area.
//   loadPoints(path) / parsePoints(data, size, PointFormat, name)
//     points from text, PLY vertices or .npy.
//
// ---- 2. The one question: Classifier and Method -----------------------------
//
//   <vds/classify.h> is the contract every way of answering implements:
//   class Classifier {                                   (abstract)
//     method(), memoryBytes(), summary(), rules() / answers(rule),
//     classify(PointsView, labels, ClassifyOptions)    labels every point,
//     contains(p, rule)                                one point,
//     occupancy(Grid, cells, ClassifyOptions)          every cell centre;
//   }
//   A method that cannot answer `options.rule` throws InvalidArgument before
//   touching a point (`requireRule`), never answering another rule.
//   `options.stats` (ClassifyStats {certain, exact}) says how points were
//   answered. `Scalar` is the points' scalar type. ClassifyOptions holds
//   what a query asks (rule, threads, stats); how a method answers is fixed
//   when its classifier is made (a sprite's SpriteQueryOptions {QueryLayout,
//   BoundaryEvaluation}, a certified classifier's resolution).
//
//   The engine layer under the contract: free functions and classes each
//   method's Classifier is a thin shell over, for callers who hold the
//   method's own data and want no Classifier object — classify(sprite, ...)
//   and occupancy(sprite | mesh, ...) on the CPU, GpuClassifier::classify
//   and GpuOccupancy on the GPU (GL buffers in and out). They give the
//   Classifier's answers; a Classifier is the one door for everything else
//   (the CLI, Python, evaluation and benchmarks dispatch through it).
//   enum class Method: sprite, exact, certified, sprite-gpu, slicemap,
//     slicemap-local, solid, solid-compute, slicemap-gpu, slicemap-local-gpu,
//     solid-gpu, solid-compute-gpu, certified-gpu, and custom (a Classifier
//     written outside the library). `methodInfo(method)` / `methodTable()` give each a
//     `MethodInfo` {name, Layer, gpu, exact, needsClosedMesh, fromSprite,
//     rules, defaultResolution, summary, builtIn()}: the one table the CLI,
//     Python, evaluation and benchmarks read. `cpuForm` / `gpuForm` map a
//     method to its CPU or GPU twin.
//   std::unique_ptr<Classifier> makeClassifier(mesh, method, MethodOptions)
//   makeClassifier(gl, mesh, method, options) / makeClassifier([gl,] sprite, method)
//     builds any method (umbrella, <vds/all.h>); MethodOptions {resolution,
//     axis, bakeMethod, slices, threads, sourceName}.
//   Rules (<vds/rule.h>): Rule::Parity (odd crossings in front: the paper's
//     test), Rule::Winding (entering +1, leaving -1, non-zero inside),
//     Rule::GeneralizedWinding (the generalized winding number above 1/2:
//     open and messy meshes). `insideByRule(winding, rule)`;
//     `generalizedWindingInside(w)` labels a generalized winding number
//     (above 1/2 by more than `kGeneralizedWindingTie`: ties are outside).
//
// ---- 3. Bake a sprite -------------------------------------------------------
//
//   Sprite bakeCpu(mesh, BakeOptions)                     <vds/bake.h>
//     exact ray casting on every core, no GL. BakeOptions: resolution
//     (texels on the longer side of the view, 1..16384, default 1024),
//     axis (Axis X, Y, Z, <vds/axis.h>; unset, the default: the one with
//     the fewest layers at that resolution, `chooseViewAxis(mesh,
//     resolution)`, whose AxisChoice says what it counted), method
//     (BakeMethod: Auto, the default, Lists, Peel, Cpu; Auto is the GL
//     fragment lists on a GPU and the CPU baker on a software renderer or
//     without GL: `chooseBakeMethod([gl,] &why)`),
//     progress callback, timings. Unusable meshes throw InvalidMesh; open or
//     non-manifold ones are baked and marked `SolidStatus::Open`.
//   Sprite bakeOnGl(gl, mesh, options[, glOptions])        <vds/gl/bake.h>
//     the GL methods (Lists: fragment lists; Peel: depth peeling) on the
//     caller's context; the same layers as the CPU baker up to the
//     rasterizer's sub-texel snapping. GlBakeOptions: the GL bakers' own
//     knobs (maxListNodes, the fragment lists' node pool).
//   chooseViewAxisOnGl(gl, mesh, resolution)  the auto axis counted in the
//                        GL bakers' own raster on a GPU.  <vds/gl/bake.h>
//   Baker(mesh, options)  a deforming mesh: validated once, then
//                        `updateVertices` and `rebake`, each re-bake equal
//                        to a fresh bake bit for bit.     <vds/gl/baker.h>
//   Sprite bake([gl,] mesh, options)                       <vds/all.h>
//     any BakeMethod; without a context the GL methods use a private one.
//   BakeOptions::timings -> BakeTimings: wall and GPU time of each BakePhase
//     (validation, compile, upload, raster, scan, sort, texture, read-back,
//     assembly); `report()` prints them (`vds bake --verbose`).
//
// ---- 4. Keep it ---------------------------------------------------------------
//
//   writeSprite(sprite, path) / Sprite readSprite(path)      <vds/vds_file.h>
//     One OpenEXR deep image, lossless, checksummed; written atomically
//     (temporary file, then rename); the reader refuses damaged files with
//     FormatError before allocating for sizes the file cannot hold.
//   std::vector<char> encodeSprite(sprite) / Sprite decodeSprite(data, size)
//     the same bytes in memory.
//
// ---- 5. Ask it ----------------------------------------------------------------
//
//   Sprite { grid (SpriteGrid: `makeGrid(box, axis, resolution)`, its axis
//     permutation `axisPermutation(axis)`), offsets, crossings (each
//     `encodeCrossing(depth, entering)`: `crossingDepth`, `crossingEnters`),
//     boundaryEdges (`meshBoundaryEdges(mesh)`), status, transform }
//                                                            <vds/sprite.h>
//   bool Sprite::contains(p, rule)   one point; points outside the sprite's
//     box are outside. Errors lie within about half a texel diagonal of the
//     surface (docs/accuracy.md). Sprite::transform(mat4) moves it without
//     baking again; `sweepsByColumns(sprite.grid)` says whether grids are
//     still swept through it column by column (the fast occupancy path).
//   classify(sprite, PointsView, labels, ClassifyOptions, SpriteQueryOptions)
//     the engine: batches on threads; the same answers as `contains`.
//     QueryLayout::Auto builds a 16-byte-a-column table for large batches;
//     BoundaryEvaluation::Caps builds the boundary's caps for the call.
//   SpriteClassifier(sprite, SpriteQueryOptions)   the same as a Classifier
//     (Method::Sprite), which keeps the caps between batches.
//
// ---- 6. Ask it for a whole grid ------------------------------------------------
//
//   Grid{box, dims}; cell (i, j, k) centre lo + (i+1/2, j+1/2, k+1/2)
//     * (hi - lo) / dims, labels in C order [i][j][k]       <vds/grid.h>
//     `cubicGrid(box, n)` (sized by `cubicCells(extent, n)`, as voxel grids
//     and a sprite's texels are), `checkGrid(grid)` (at most `kMaxGridCells`),
//     `packLabels(cells, count, bits)` (eight cells a byte, numpy's packbits order).
//   occupancy(mesh, grid, cells, options)     exact labels by one sweep per
//     column, equal to the exact classifier on every cell centre.
//   occupancy(sprite, grid, cells, options)   the sprite's labels, one walk
//     per column; equal to `contains` on every cell.      <vds/occupancy.h>
//   occupancy(classifier, grid, cells, options)  any method.
//   readNpy / parseNpy / npyPoints / npyHeader / writeNpy / NpyArray:
//     numpy .npy in and out                                <vds/npy.h>
//   AtomicFile(target): every output is written to a temporary file beside
//     its target and renamed over it by `commit()`, so a failed run leaves
//     the old file or none, never half of one.           <vds/atomic_file.h>
//
// ---- 7. Exact answers ---------------------------------------------------------
//
//   ExactClassifier(mesh, axis)                               <vds/exact.h>
//     the yardstick: exact orientation predicates with a top-left tie rule
//     on the triangles themselves; `contains`, `winding`,
//     `generalizedWinding` (the Antipodal split: integer ray count plus a
//     boundary term over the boundary edges). Construction O(n log n).
//   CertifiedClassifier(mesh, CertifiedOptions{resolution, axis, threads})
//     the exact classifier's answers at close to a sprite's speed: per
//     texel, bands where the surface may be; outside them the answer is
//     proven, inside them the exact classifier decides; `bands()` gives
//     them as CertifiedBands (offsets, CertifiedBand {lo, hi, windingAbove},
//     box, depth axis, certified rules) for GPU forms. <vds/certified.h>
//   SignedDistance(mesh, rule)                             <vds/distance.h>
//     exact distances to the triangles (an SAH hierarchy as wide as the CPU's
//     SIMD, 8 lanes with AVX2, else 4; the closest
//     point in double): `distance` (signed: negative exactly where the exact
//     classifier of the rule says inside), `unsignedDistance`,
//     `closestPoints` (a ClosestPoint each: point, distance, triangle, its
//     Feature and index), `grid` (a signed distance grid over a Grid, full
//     or a band clamped to +-band), with DistanceOptions{threads,
//     maxDistance} and DistanceGridOptions{threads, band, far} (FarCells::
//     Exact, or Propagated: a closest-feature transform within a bound).
//     `closestPointOnTriangle(p, a, b, c)`: the one closest-point kernel.
//   SpriteDistance bakeDistance(mesh, box, n, rule)         <vds/distance.h>
//     the distance grid a sprite carries (`Sprite::distance`, file format 3,
//     `vds bake --distance N`), for `vdsDistance` in GLSL (`GpuSprite::distanceGrid`);
//     `spriteDistanceGrid(box, n)` its cells, for callers filling it in slabs.
//   SparseBand sparseBand(distance, mesh, grid, SparseBandOptions{threads, W})
//     a narrow band stored sparsely: BandBlock's of 8^3 cells near the
//     surface, whole blocks inside or outside as tiles, every cell the dense
//     band's; grids up to 2^40 cells (`voxelSizeGrid(box, h)`). <vds/sparse_band.h>
//   writeVdb(path, band or grid + labels, VdbOptions{name, source})  <vds/vdb.h>
//     the optional vds::vdb (OpenVDB where found): a band as a level set,
//     occupancy labels as a BoolGrid; `vdbAvailable()` says whether it can,
//     `vdbLibrary()` with which OpenVDB, `vdsVersion()` the version it records.
//
// ---- 8. On the GPU (vds::gl) --------------------------------------------------
//
//   GlContext            the context the library works in: the
//                        application's own, wrapped by
//                        `GlContext::adoptCurrent()` (EGL, GLX, a GLFW or SDL
//                        window; not owned), or a headless EGL context of the
//                        library's own, `GlContext()` (NVIDIA's EGL device,
//                        Mesa's llvmpipe without a GPU); GlUnavailable with
//                        the reasons when none can be had. `glAvailable()`
//                        is the cheap probe, GlInfo names the renderer,
//                        GlLimits what GL allows there (asked once a context),
//                        `checkGl(what)` turns a GL error into GlError.
//                        CurrentContext scopes restore the caller's context
//                        (a NativeContext: the EGL or GLX handles); a
//                        ContextStamp is what a GL object remembers of its
//                        context and thread.
//                        The rules (how a context is passed, what is
//                        restored) head <vds/gl/context.h>.
//   GlObject (Buffer, Texture, Framebuffer, VertexArray, Query, Shader,
//                        Program; `BufferTraits`, `TextureTraits`,
//                        `FramebufferTraits`, `VertexArrayTraits`,
//                        `QueryTraits`, `ShaderTraits`, `ProgramTraits`) and
//                        Fence: owning GL names.       <vds/gl/objects.h>
//   buildProgram(stages, defines)  from ShaderStage sources, `#include`s
//                        resolved against the embedded shaders
//                        (`assembleShader`, `embeddedShader`,
//                        `embeddedShaderPaths`, `registerShaders` with
//                        ShaderFile entries).            <vds/gl/shader.h>
//   GpuMesh              a mesh in GL buffers.            <vds/gl/mesh.h>
//   GpuSprite(sprite)    the paper's R32F 3D texture and placement, for
//                        shaders/vds/vpt.glsl (`vdsContains(...)` in any
//                        stage; the same answers as the CPU), and the
//                        boundary edges for `vdsContainsGeneralized(...)`
//                        (`boundary()`, a GpuBoundary, sets the VdsBoundary
//                        uniform) and its distance grid (`distanceGrid()`, a
//                        GpuDistanceGrid, for `vdsDistance`);
//                        GpuSpriteParts picks what is uploaded. <vds/gl/sprite.h>
//   GpuClassifier        the VPT over many points in a compute shader: host
//                        arrays in and out, or points and labels already in
//                        GL buffers (no host round trip). HostTransfer says
//                        how host arrays cross: mapped, or copied to GPU
//                        memory (Auto: copied on a hardware renderer).
//   GpuSpriteClassifier  the same as a Classifier (Method::SpriteGpu).
//                                                        <vds/gl/classifier.h>
//   GpuCertifiedClassifier(gl, mesh, CertifiedOptions)  Method::CertifiedGpu:
//                        the exact classifier's labels, the certified bands'
//                        in a compute shader, the unsure points compacted on
//                        the GPU and answered exactly on the host; host
//                        arrays, or GL buffers in and out.
//   GpuCertifiedBands(certified)  the bands in GL, for shaders/vds/certified.glsl
//                        (`vdsContainsCertain(...)`: 1 inside, 0 outside, -1
//                        unsure, in any stage). <vds/gl/certified.h>
//   GpuOccupancy         occupancy grids in a compute shader, into a GL
//                        buffer or host memory.          <vds/gl/occupancy.h>
//   uploadDistanceTexture(grid, cells)  a signed distance grid as a 3D
//                        texture for `vdsDistance` in vpt.glsl (within half
//                        a cell's diagonal of the exact distance). <vds/gl/distance.h>
//   GpuBake bakeToGpu(gl, mesh, options, parts[, glOptions])  a GpuSprite straight from
//                        the fragment-list bake, nothing read back. <vds/gl/bake.h>
//   setStyleUniforms(program, solids, StyleOptions)  the uniforms of
//                        shaders/vds/styles.glsl (clip, lens and styles bound
//                        to solids): StyleSolid {sprite, StyleRole, style,
//                        rule}, StyleCombine; sprites on texture units from a
//                        base unit the caller chooses.   <vds/gl/styles.h>
//   GpuBitGrid, GpuSlicemap  voxel grids uploaded for the application's own
//                        shaders (voxel/solid.glsl, voxel/slicemap.glsl).
//                                                      <vds/voxel/gpu_grid.h>
//
// ---- 9. The representations the VDS competes with (vds::voxel) ----------------
//
//   Representation (slicemap, slicemap-local, solid, solid-compute),
//     `parseRepresentation`, `methodOf`, `representationOf`;
//     Model buildModel(gl, mesh, representation, ModelOptions) a Classifier
//     (the CPU lookup); GpuModelClassifier(gl, model) its GLSL lookup;
//     `modelMemoryBytes(box, representation, options)` without building.
//                                                <vds/voxel/representation.h>
//   VoxelGrid (a Grid with the voxelizers' float lattice) makeVoxelGrid(box,
//     resolution), makeSlicemapGrid(box, resolution, slices) (slicemapGridOver
//     from the columns), BitGrid
//     makeBitGrid(grid), `snapToSubcells`, `requireClosed(mesh, what)`
//                                                        <vds/voxel/grid.h>
//   Slicemap buildSlicemap(gl, mesh, box, resolution, SlicemapOptions),
//     Slicing (`parseSlicing`), `defaultSlices`, `slicemapInside`
//                                                    <vds/voxel/slicemap.h>
//   BitGrid voxelizeSolid(gl, mesh, grid, SolidMethod) (`parseSolidMethod`)
//     <vds/voxel/solid.h>; voxelizeSurface(gl, mesh, grid) <vds/voxel/surface.h>;
//     SlicedVoxels voxelizeSlices(gl, mesh, grid, SlicingOptions) <vds/voxel/slicing.h>
//   Light and shadows: LightFrame makeLightFrame(direction), toLightSpace
//     <vds/voxel/light_frame.h>; transmittance through a solid
//     (TransmittanceSource, TransmittanceParameters, ReceiverPlane,
//     TransmittanceImage, transmittanceOf, transmittanceOnCpu,
//     GpuTransmittanceCaster, renderTransmittance, slicemapSurfacesInFront,
//     absorptionInFront, spriteThicknessInFront, ExactCrossings,
//     exactCrossingsInFront)                      <vds/voxel/transmittance.h>;
//     refraction (RefractionMethod, RefractionView, RefractionParameters,
//     RefractionImage, refractionColour, refractOnCpu, refractExactly,
//     GpuRefractionCaster, renderRefraction)        <vds/voxel/refraction.h>;
//     both casters upload through one base, voxel::GpuCaster
//     (a GpuSlicemap, a sprite's texture or a 3D texture) <vds/voxel/caster.h>
//
// ---- 10. Measuring (vds::eval) ------------------------------------------------
//
//   EvalReport evaluate(mesh, EvalOptions)  the sprite against the exact
//     classifier by resolution (EvalRow; `toTable`, `toJson`) <vds/eval/accuracy.h>
//   CompareResult compare(mesh, CompareOptions)  the VDS against slicemaps
//     and solid voxels at equal resolution and memory (CompareRow: a Method
//     and a Rule); `errorChart(result)` an SVG     <vds/eval/compare.h>
//   SurfaceDistance(mesh), pointTriangleDistance   <vds/eval/distance.h>
//   Image, readPng, writePng                       <vds/eval/image.h>
//
//   Lifetime: a context is current on the thread that made it; destroying
//   or moving one never changes another current context; no GL call happens
//   once the process exits.
#pragma once

#include <vds/atomic_file.h>
#include <vds/axis.h>
#include <vds/bake.h>
#include <vds/certified.h>
#include <vds/classify.h>
#include <vds/distance.h>
#include <vds/enum_names.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/grid.h>
#include <vds/mesh.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>
#include <vds/occupancy.h>
#include <vds/rule.h>
#include <vds/sample.h>
#include <vds/sparse_band.h>
#include <vds/sprite.h>
#include <vds/vds_file.h>
