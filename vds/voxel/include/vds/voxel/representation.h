// vds::voxel: one entry point for every voxel representation that answers
// point-in-solid queries, each a `Classifier` (<vds/classify.h>) beside the
// VDS:
//   auto model = vds::voxel::buildModel(gl, mesh, vds::voxel::Representation::SlicemapLocal, {256});
//   model.classify(points, labels.data());          // Method::SlicemapLocal, on the CPU
//   vds::voxel::GpuModelClassifier(gl, model).classify(points, labels.data()); // in GLSL
//
// Representations (details in their headers and docs/voxel.md):
//  - Slicemap:      front/back slicemap pair, uniform slicing    (<vds/voxel/slicemap.h>)
//  - SlicemapLocal: front/back slicemap pair, local slicing      (<vds/voxel/slicemap.h>)
//  - Solid:         solid voxels by rasterization, per-fragment XOR (<vds/voxel/solid.h>)
//  - SolidCompute:  solid voxels in compute, flip + prefix XOR   (<vds/voxel/solid.h>)
// All are laid over the mesh's bounding box with cubic cells, `resolution`
// of them along the box's longest side (vds::cubicCells, as for a sprite's
// texels); slicemaps get the box depth in cells as slices, rounded up to a
// multiple of 32 and capped at 1024.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <memory>
#include <variant>

#include <glm/vec3.hpp>

#include <vds/classify.h>
#include <vds/enum_names.h>
#include <vds/gl/context.h>
#include <vds/mesh.h>
#include <vds/voxel/grid.h>
#include <vds/voxel/slicemap.h>

namespace vds::voxel {

enum class Representation : std::uint8_t { Slicemap, SlicemapLocal, Solid, SolidCompute };

} // namespace vds::voxel

template <> struct vds::EnumNames<vds::voxel::Representation> {
    static constexpr const char* kind = "voxel representation";
    static constexpr EnumName<voxel::Representation> table[] = {{"slicemap", voxel::Representation::Slicemap},
                                                                {"slicemap-local", voxel::Representation::SlicemapLocal},
                                                                {"solid", voxel::Representation::Solid},
                                                                {"solid-compute", voxel::Representation::SolidCompute}};
};

namespace vds::voxel {

/// Parses "slicemap", "slicemap-local", "solid", "solid-compute" (`parseEnum`);
/// throws `InvalidArgument` naming the accepted names.
Representation parseRepresentation(const std::string& name);
/// The name `parseRepresentation` accepts (`enumName`).
const char* toString(Representation r);

struct ModelOptions {
    std::uint32_t resolution = 128; ///< cells along the box's longest side, 1..16384
    std::uint32_t slices = 0;       ///< slicemaps only: 0 = box depth in cells (see SlicemapOptions)
};

/// The `Method` of a representation's CPU lookup (Slicemap -> Method::Slicemap, ...).
Method methodOf(Representation representation);
/// The representation behind a voxel method, CPU or GPU form; throws
/// `InvalidArgument` for a method that is not a voxel representation.
Representation representationOf(Method method);

/// `Model::memoryBytes` of `representation` built over `box` with
/// `options`, without building it (for picking a resolution within a
/// memory budget).
std::size_t modelMemoryBytes(const Box& box, Representation representation, const ModelOptions& options);

/// A built representation in host memory, the CPU lookup as a `Classifier`
/// (parity only: `Classifier::classify` refuses the other rules); queries
/// are thread safe.
class Model final : public Classifier {
public:
    Model(Representation representation, Slicemap slicemap, double buildSeconds);
    Model(Representation representation, BitGrid solid, double buildSeconds);

    Representation representation() const { return representation_; }

    Method method() const override { return methodOf(representation_); }
    /// `contains(p, rule)`: the inside test of a point in mesh coordinates,
    /// points outside the grid outside; rules other than parity are refused.
    using Classifier::contains;

    /// Wall-clock seconds of the build on the GPU, read-back included (the
    /// first build on a context also compiles its shaders).
    double buildSeconds() const { return buildSeconds_; }
    /// Bytes the point query reads (host), see Slicemap::memoryBytes / BitGrid::memoryBytes.
    std::size_t memoryBytes() const override;
    /// Bytes of the GL objects the GLSL lookup reads.
    std::size_t gpuBytes() const;
    /// Cells: columns along x and y, and slices or voxels along z.
    glm::uvec3 cells() const;
    /// Edge of a cell across the columns, mesh units.
    float cellSize() const;
    /// One line, e.g. "solid-compute: 128x96x80 voxels, 122880 bytes".
    std::string summary() const override;

    /// The slicemap pair, or nullptr for solid voxels.
    const Slicemap* slicemap() const { return std::get_if<Slicemap>(&data_); }
    /// The solid voxels, or nullptr for a slicemap.
    const BitGrid* solid() const { return std::get_if<BitGrid>(&data_); }

protected:
    void classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                        const ClassifyOptions& options) const override;

private:
    /// The lookup of one point (parity).
    bool inside(const glm::vec3& p) const;

    Representation representation_;
    std::variant<Slicemap, BitGrid> data_;
    double buildSeconds_ = 0.0;
};

/// Builds a representation of the closed mesh over its bounding box on
/// `gl` (made current for the call; the caller's context is current again on
/// return). Throws `InvalidMesh` for an open or unusable mesh,
/// `InvalidArgument` for a bad resolution or slice count, `OutOfMemory` for
/// a grid GL cannot hold.
Model buildModel(const GlContext& gl, MeshView mesh, Representation representation, const ModelOptions& options = {});

/// The GLSL lookups (shaders/voxel/solid.glsl and slicemap.glsl, in
/// shaders/voxel/classify.comp) over a model, as a `Classifier` of the
/// model's GPU method (Method::SlicemapGpu, ...): the model is uploaded to
/// `gl` once; the answers equal the model's CPU lookup. Belongs to `gl`,
/// which must outlive it; every call makes `gl` current and restores the
/// caller's. Not thread safe.
class GpuModelClassifier final : public Classifier {
public:
    GpuModelClassifier(const GlContext& gl, Model model);
    ~GpuModelClassifier() override;
    Method method() const override;
    /// Bytes of the GL objects the lookup reads.
    std::size_t memoryBytes() const override { return model_.gpuBytes(); }
    std::string summary() const override;
    const Model& model() const { return model_; }

protected:
    void classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                        const ClassifyOptions& options) const override;

private:
    struct Resources;
    const GlContext& gl_;
    Model model_;
    std::unique_ptr<Resources> gpu_;
};

} // namespace vds::voxel
