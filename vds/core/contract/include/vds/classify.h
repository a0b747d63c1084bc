// vds: the one contract for "is this point inside?" — every method, CPU or
// GPU, exact or approximate, answers through the same shapes:
//
//   points    a `PointsView`: pointer, count, byte stride, float or double
//   labels    `count` bytes, 1 inside, 0 outside, caller-owned
//   options   one `ClassifyOptions`: rule, threads, optional stats out
//   grids     one `Grid` (box, dims, one cell-centre formula, one index order)
//
// A `Classifier` is one method made ready for one solid (from a mesh or a
// sprite). Core's methods (sprite, exact, certified) are classes here and
// in <vds/sprite.h>, <vds/exact.h>, <vds/certified.h>; the GPU and voxel
// methods live in the layers above (<vds/gl/classifier.h>,
// <vds/voxel/representation.h>), and `vds::makeClassifier` in <vds/all.h> (the
// umbrella, vds::vds) makes any of them by `Method`. A method that cannot
// answer a rule refuses it with `InvalidArgument` before touching a point,
// never answering another rule instead.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/enum_names.h>
#include <vds/grid.h>
#include <vds/rule.h>

namespace vds {

/// The scalar type of a points array.
enum class Scalar : std::uint8_t { Float32, Float64 };

/// A read-only view of `count` points: point k is three scalars (x, y, z)
/// at byte offset `k * strideBytes` from `data`, so points may sit inside
/// larger records (`strideBytes` >= 3 * scalar size). Caller-owned; read
/// only while a call runs. Coordinates are those the classifier answers in
/// (mesh coordinates; a moved sprite's world coordinates). Float64 points
/// are rounded to float, which every method classifies in.
struct PointsView {
    const void* data = nullptr;
    std::size_t count = 0;
    std::size_t strideBytes = 3 * sizeof(float);
    Scalar scalar = Scalar::Float32;

    PointsView() = default;
    /// Packed glm::vec3 (the layout of float[count][3]).
    PointsView(const glm::vec3* points, std::size_t n) : data(points), count(n) {}
    PointsView(const std::vector<glm::vec3>& points) : PointsView(points.data(), points.size()) {}
    /// Floats, x y z at `xyz + k * strideBytes` bytes.
    static PointsView floats(const float* xyz, std::size_t n, std::size_t strideBytes = 3 * sizeof(float));
    /// Doubles, x y z at `xyz + k * strideBytes` bytes.
    static PointsView doubles(const double* xyz, std::size_t n, std::size_t strideBytes = 3 * sizeof(double));

    std::size_t scalarBytes() const { return scalar == Scalar::Float32 ? sizeof(float) : sizeof(double); }
    /// Point k, as float.
    glm::vec3 operator[](std::size_t k) const;
    /// Points [first, first + n) of this view.
    PointsView slice(std::size_t first, std::size_t n) const;
};

/// What a batch did, for methods that answer some points by a proof and the
/// rest by an exact fallback (`Method::Certified`,
/// `Method::CertifiedGpu`). Other methods count
/// every point under `certain` (an approximate method's answers are its own).
struct ClassifyStats {
    std::size_t certain = 0; ///< answered without the exact path
    std::size_t exact = 0;   ///< answered by the exact classifier
};

/// The one options struct of every classify and occupancy call: what each
/// query asks. How a method is built (a sprite's `SpriteQueryOptions`, a
/// certified classifier's resolution) is fixed when its classifier is made.
struct ClassifyOptions {
    Rule rule = Rule::Parity;
    unsigned threads = 0;          ///< CPU threads, 0: one per hardware thread (GPU methods ignore it)
    ClassifyStats* stats = nullptr; ///< if set, filled by the call (caller-owned)
};

/// Every way the library answers "inside?". Each has a name (`EnumNames`,
/// the CLI's `--method`, Python's `method=`) and a `MethodInfo`.
enum class Method : std::uint8_t {
    Sprite,           ///< the VPT on a volumetric depth sprite, CPU (vds::core)
    Exact,            ///< exact predicates on the triangles (vds::core)
    Certified,        ///< exact answers, most from certified bands (vds::core)
    SpriteGpu,        ///< the VPT in a compute shader (vds::gl)
    Slicemap,         ///< front/back slicemap pair, uniform slicing, CPU lookup (vds::voxel)
    SlicemapLocal,    ///< the same with local slicing (vds::voxel)
    Solid,            ///< solid voxels by rasterization, CPU lookup (vds::voxel)
    SolidCompute,     ///< solid voxels in compute, CPU lookup (vds::voxel)
    SlicemapGpu,      ///< Slicemap, looked up in a compute shader (vds::voxel)
    SlicemapLocalGpu, ///< SlicemapLocal, looked up in a compute shader (vds::voxel)
    SolidGpu,         ///< Solid, looked up in a compute shader (vds::voxel)
    SolidComputeGpu,  ///< SolidCompute, looked up in a compute shader (vds::voxel)
    CertifiedGpu,     ///< Certified with its bands in a compute shader, the rest exact on the CPU (vds::gl)
    /// A classifier defined outside the library: derive from `Classifier`,
    /// return this from `method()` and name it in `summary()`; it then
    /// works with `occupancy` and everything else that takes a Classifier
    /// (the benchmarks' Embree and CGAL peers do). `makeClassifier` refuses it.
    Custom,
};
constexpr std::size_t kMethodCount = 14;

template <> struct EnumNames<Method> {
    static constexpr const char* kind = "method";
    static constexpr EnumName<Method> table[] = {
        {"sprite", Method::Sprite},
        {"exact", Method::Exact},
        {"certified", Method::Certified},
        {"sprite-gpu", Method::SpriteGpu},
        {"slicemap", Method::Slicemap},
        {"slicemap-local", Method::SlicemapLocal},
        {"solid", Method::Solid},
        {"solid-compute", Method::SolidCompute},
        {"slicemap-gpu", Method::SlicemapGpu},
        {"slicemap-local-gpu", Method::SlicemapLocalGpu},
        {"solid-gpu", Method::SolidGpu},
        {"solid-compute-gpu", Method::SolidComputeGpu},
        {"certified-gpu", Method::CertifiedGpu},
        {"custom", Method::Custom},
    };
};

/// Which library a method needs linked.
enum class Layer : std::uint8_t { Core, Gl, Voxel };

/// What a method is: the one table every consumer (CLI, evaluation,
/// benchmarks, Python) reads instead of knowing methods by name.
struct MethodInfo {
    Method method;
    const char* name;        ///< as `enumName(method)`
    Layer layer;             ///< the library that implements it
    bool gpu;                ///< runs its queries on the GPU (needs a GL context)
    bool exact;              ///< labels equal the exact classifier's on every point
    bool needsClosedMesh;    ///< refuses open meshes (the voxel representations)
    bool fromSprite;         ///< can be made from a baked sprite, not only a mesh
    std::uint8_t rules;      ///< bit (1 << Rule) for each rule it answers
    /// The representation's own resolution default (texels or cells on the
    /// box's longest side) when the caller gives none; 0: none (exact).
    std::uint32_t defaultResolution;
    const char* summary;     ///< one line for help texts
    /// Made by `makeClassifier` (every method but Custom).
    bool builtIn() const { return method != Method::Custom; }
};

/// The table entry of `method`.
const MethodInfo& methodInfo(Method method);
/// Every method, in `Method` order.
const MethodInfo* methodTable();
/// True if `method` answers `rule`.
inline bool answers(Method method, Rule rule) { return (methodInfo(method).rules >> unsigned(rule)) & 1u; }
/// Throws `InvalidArgument` when `method` cannot answer `rule`, naming the
/// rules it does answer.
void requireRule(Method method, Rule rule);
/// The CPU form of a GPU method (SpriteGpu -> Sprite, ...), itself otherwise.
Method cpuForm(Method method);
/// The GPU form of a method, itself if it has none or is one.
Method gpuForm(Method method);

/// One method made ready for one solid. Implementations are read-only when
/// queried: a CPU classifier may be used from any number of threads at once;
/// a GPU classifier belongs to its GL context and one thread (see its header).
class Classifier {
public:
    virtual ~Classifier();

    virtual Method method() const = 0;
    /// Bytes the queries read (host memory; a GPU method's GPU memory).
    virtual std::size_t memoryBytes() const = 0;
    /// One line about what was built, e.g. "sprite 1024 x 512 x 12 along z".
    virtual std::string summary() const;
    /// Bit (1 << Rule) for each rule this classifier answers; by default its
    /// method's `MethodInfo::rules` (a Custom classifier narrows it here).
    virtual std::uint8_t rules() const;
    /// True if this classifier answers `rule`.
    bool answers(Rule rule) const { return (rules() >> unsigned(rule)) & 1u; }

    /// Labels `points`: `labels[k]` = 1 inside, 0 outside (`points.count`
    /// bytes, caller-owned). Throws `InvalidArgument` if the method cannot
    /// answer `options.rule`; fills `options.stats` if set.
    void classify(const PointsView& points, std::uint8_t* labels, const ClassifyOptions& options = {}) const;
    /// One point.
    bool contains(const glm::vec3& p, Rule rule = Rule::Parity) const;
    /// Labels every cell centre of `grid` (`Grid::cellCentre`, index order
    /// `Grid::index`): `cells` holds `grid.cellCount()` bytes. Methods that
    /// can sweep (sprite, exact, GPU sprite) walk columns; the others
    /// classify the cell centres. The same labels as `classify` of the
    /// centres. Throws like `checkGrid` and for a rule the method lacks.
    void occupancy(const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options = {}) const;

protected:
    // Copied or moved only as part of a concrete classifier (no slicing).
    Classifier() = default;
    Classifier(const Classifier&) = default;
    Classifier(Classifier&&) noexcept = default;
    Classifier& operator=(const Classifier&) = default;
    Classifier& operator=(Classifier&&) noexcept = default;

    /// Packed float points (12-byte stride at least; `options.rule` checked).
    virtual void classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                                const ClassifyOptions& options) const = 0;
    /// Default: classifies the cell centres in chunks.
    virtual void sweep(const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options) const;
};

/// `classifier.occupancy(grid, cells, options)`, the free-function shape
/// beside `occupancy(sprite, ...)` and `occupancy(mesh, ...)` (<vds/occupancy.h>).
void occupancy(const Classifier& classifier, const Grid& grid, std::uint8_t* cells,
               const ClassifyOptions& options = {});

} // namespace vds
