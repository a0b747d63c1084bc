// Transmittance through semi-transparent casters from a slicemap
// (Eisemann & Décoret 2006, section 3.1), per-voxel absorption (Chang et al.
// 2014, section 4) and a volumetric depth sprite, with CPU references.
#include <vds/voxel/transmittance.h>

#include <algorithm>
#include <bitset>
#include <cmath>
#include <string>
#include <utility>

#include <GL/gl.h>
#include <GL/glext.h>
#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <vds/error.h>
#include <vds/detail/parallel.h>

#include <vds/gl/shader.h>

#include "plane_targets.h"

namespace vds::voxel {

namespace {

int bitsBefore(const std::uint32_t* words, std::uint32_t wordCount, std::uint32_t slice) {
    int n = 0;
    for (std::uint32_t w = 0; w < wordCount && w * 32 < slice; ++w) {
        std::uint32_t word = words[w];
        const std::uint32_t keep = slice - w * 32;
        if (keep < 32) word &= (1u << keep) - 1u;
        n += int(std::bitset<32>(word).count());
    }
    return n;
}

} // namespace

std::uint32_t slicemapSurfacesInFront(const Slicemap& map, const glm::vec3& p) {
    const glm::vec3 v = map.grid.toCells(p);
    const float fx = std::floor(v.x), fy = std::floor(v.y);
    if (!(fx >= 0.0f && fx < float(map.grid.dims.x) && fy >= 0.0f && fy < float(map.grid.dims.y))) return 0;
    const std::size_t column = std::size_t(fy) * map.grid.dims.x + std::size_t(fx);
    const std::uint32_t slices = map.slices();
    float near = 0.0f, far = float(slices), perDepth = 1.0f;
    if (map.slicing == Slicing::Local) {
        near = map.nearDepth[column];
        far = map.farDepth[column];
        perDepth = map.slicesPerDepth[column];
    }
    if (!(near <= far) || !(v.z >= near)) return 0;
    std::uint32_t slice = slices;
    if (v.z <= far) {
        const float s = std::floor((v.z - near) * perDepth);
        slice = std::min(std::uint32_t(int(s)), slices - 1);
    }
    return std::uint32_t(bitsBefore(&map.front[column * map.words], map.words, slice) +
                         bitsBefore(&map.back[column * map.words], map.words, slice));
}

float absorptionInFront(const SlicedVoxels& voxels, const glm::vec3& p) {
    const VoxelGrid& g = voxels.grid;
    const glm::vec3 v = g.toCells(p);
    const float fx = std::floor(v.x), fy = std::floor(v.y);
    if (!(fx >= 0.0f && fx < float(g.dims.x) && fy >= 0.0f && fy < float(g.dims.y))) return 0.0f;
    if (!(v.z > 0.0f)) return 0.0f;
    const std::uint32_t end = v.z >= float(g.dims.z) ? g.dims.z : std::uint32_t(std::floor(v.z));
    float sum = 0.0f;
    for (std::uint32_t k = 0; k < end; ++k) sum += voxels.absorption(std::uint32_t(fx), std::uint32_t(fy), k);
    return sum;
}

float spriteThicknessInFront(const Sprite& sprite, const glm::vec3& p) {
    if (sprite.grid.axis != Axis::Z) throw InvalidArgument("spriteThicknessInFront needs a sprite baked along z");
    const SpriteGrid& g = sprite.grid;
    const glm::vec3 t = g.toTexture(p);
    if (!(t.z > 0.0f)) return 0.0f;
    const float fs = std::floor(t.x * float(g.width));
    const float ft = std::floor(t.y * float(g.height));
    if (!(fs >= 0.0f && fs < float(g.width) && ft >= 0.0f && ft < float(g.height))) return 0.0f;
    const std::size_t column = std::size_t(ft) * g.width + std::size_t(fs);
    const float r = std::min(t.z, 1.0f);
    int winding = 0;
    float entry = 0.0f, length = 0.0f;
    for (std::uint32_t k = sprite.offsets[column]; k < sprite.offsets[column + 1]; ++k) {
        const float e = sprite.crossings[k];
        const float d = crossingDepth(e);
        if (!(d < r)) break;
        const int next = winding + (crossingEnters(e) ? 1 : -1);
        if (winding == 0 && next != 0) entry = d;
        else if (winding != 0 && next == 0) length += d - entry;
        winding = next;
    }
    if (winding != 0) length += r - entry;
    return length * (g.box.hi.z - g.box.lo.z);
}

ExactCrossings exactCrossingsInFront(MeshView mesh, const glm::vec3& p) {
    struct Hit {
        double z;
        int step;
    };
    std::vector<Hit> hits;
    const double qx = p.x, qy = p.y;
    for (std::size_t t = 0; t < mesh.triangleCount; ++t) {
        glm::dvec3 v[3];
        for (int k = 0; k < 3; ++k) v[k] = glm::dvec3(mesh.positions[mesh.triangles[t][k]]);
        double w[3], sum = 0.0;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3& a = v[(k + 1) % 3];
            const glm::dvec3& b = v[(k + 2) % 3];
            w[k] = (b.x - a.x) * (qy - a.y) - (b.y - a.y) * (qx - a.x);
            sum += w[k];
        }
        if (sum == 0.0) continue; // parallel to the light: never crossed
        // Inside, or on an edge the top-left rule gives this triangle (edge
        // a -> b of the counter-clockwise order claims its points if it runs
        // downwards, or exactly rightwards), so a ray through a shared edge
        // or vertex of a closed mesh counts one crossing per sheet.
        const double orientation = sum > 0.0 ? 1.0 : -1.0;
        bool inside = true;
        for (int k = 0; k < 3 && inside; ++k) {
            const double e = w[k] * orientation;
            glm::dvec3 a = v[(k + 1) % 3], b = v[(k + 2) % 3];
            if (orientation < 0.0) std::swap(a, b);
            inside = e > 0.0 || (e == 0.0 && (b.y < a.y || (b.y == a.y && b.x > a.x)));
        }
        if (!inside) continue;
        const double z = (w[0] * v[0].z + w[1] * v[1].z + w[2] * v[2].z) / sum;
        if (!(z < double(p.z))) continue;
        // sum > 0: counter-clockwise in xy, the normal points to +z, along
        // the light: the light leaves the solid there.
        hits.push_back({z, sum > 0.0 ? -1 : 1});
    }
    std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.z < b.z; });
    ExactCrossings out;
    out.surfaces = std::uint32_t(hits.size());
    int winding = 0;
    double entry = 0.0;
    for (const Hit& h : hits) {
        const int next = winding + h.step;
        if (winding == 0 && next != 0) entry = h.z;
        else if (winding != 0 && next == 0) out.thickness += h.z - entry;
        winding = next;
    }
    if (winding != 0) out.thickness += double(p.z) - entry;
    return out;
}

float transmittanceOf(TransmittanceSource source, double quantity, const TransmittanceParameters& parameters) {
    switch (source) {
    case TransmittanceSource::SlicemapSurfaces:
        return quantity == 0.0 ? 1.0f : float(std::pow(1.0 - double(parameters.sigma), quantity));
    case TransmittanceSource::VoxelAbsorption: return float(std::exp(-quantity));
    case TransmittanceSource::SpriteThickness: return float(std::exp(-double(parameters.extinction) * quantity));
    }
    return 1.0f;
}

glm::vec3 ReceiverPlane::point(std::uint32_t i, std::uint32_t j) const {
    const float fx = (float(i) + 0.5f) / float(width);
    const float fy = (float(j) + 0.5f) / float(height);
    return (origin + u * fx) + v * fy;
}

namespace {

void requirePlane(const ReceiverPlane& plane) {
    if (plane.width == 0 || plane.height == 0 || plane.width > 16384 || plane.height > 16384)
        throw InvalidArgument("the receiver plane must be 1 to 16384 pixels on each side");
}

} // namespace

TransmittanceImage transmittanceOnCpu(const ReceiverPlane& plane, const LightFrame& frame,
                                      TransmittanceSource source, const TransmittanceParameters& parameters,
                                      const std::function<double(const glm::vec3&)>& quantityAt) {
    requirePlane(plane);
    TransmittanceImage image;
    image.width = plane.width;
    image.height = plane.height;
    const std::size_t n = std::size_t(plane.width) * plane.height;
    image.quantity.resize(n);
    image.transmittance.resize(n);
    vds::detail::parallelFor(0, plane.height, 1, [&](std::size_t rowBegin, std::size_t rowEnd) {
        for (std::size_t j = rowBegin; j < rowEnd; ++j)
            for (std::uint32_t i = 0; i < plane.width; ++i) {
                const double q = quantityAt(frame.toLightSpace(plane.point(i, std::uint32_t(j))));
                const std::size_t k = j * plane.width + i;
                image.quantity[k] = float(q);
                image.transmittance[k] = transmittanceOf(source, q, parameters);
            }
    });
    return image;
}

// The scope (a temporary of the delegating call) keeps `gl` current while
// the delegated constructor runs, and restores the caller's context after.
GpuTransmittanceCaster::GpuTransmittanceCaster(const GlContext& gl, const Slicemap& map)
    : GpuTransmittanceCaster((CurrentContext(gl), map)) {}
GpuTransmittanceCaster::GpuTransmittanceCaster(const GlContext& gl, const SlicedVoxels& voxels)
    : GpuTransmittanceCaster((CurrentContext(gl), voxels)) {}
GpuTransmittanceCaster::GpuTransmittanceCaster(const GlContext& gl, const Sprite& sprite)
    : GpuTransmittanceCaster((CurrentContext(gl), sprite)) {}

GpuTransmittanceCaster::GpuTransmittanceCaster(const Slicemap& map)
    : GpuCaster("GpuTransmittanceCaster"), source_(TransmittanceSource::SlicemapSurfaces),
      local_(map.slicing == Slicing::Local) {
    upload(map);
}

GpuTransmittanceCaster::GpuTransmittanceCaster(const SlicedVoxels& voxels)
    : GpuCaster("GpuTransmittanceCaster"), source_(TransmittanceSource::VoxelAbsorption) {
    std::vector<float> absorption(voxels.voxels.size());
    for (std::size_t k = 0; k < absorption.size(); ++k)
        absorption[k] = voxels.voxels[k].w * voxels.absorptionPerFragment;
    upload(voxels.grid, GL_R32F, GL_RED, absorption.data(), absorption.size() * sizeof(float),
           "uploading per-voxel absorption");
}

GpuTransmittanceCaster::GpuTransmittanceCaster(const Sprite& sprite)
    : GpuCaster("GpuTransmittanceCaster"), source_(TransmittanceSource::SpriteThickness) {
    if (sprite.grid.axis != Axis::Z)
        throw InvalidArgument("a transmittance sprite must be baked along z (the light, in light space)");
    upload(sprite);
    depthExtent_ = sprite.grid.box.hi.z - sprite.grid.box.lo.z;
}

void GpuTransmittanceCaster::setUniforms(GLuint program) const {
    switch (source_) {
    case TransmittanceSource::SlicemapSurfaces: setSlicemapUniforms(program); break;
    case TransmittanceSource::VoxelAbsorption: setVolumeUniforms(program, "u_absorption"); break;
    case TransmittanceSource::SpriteThickness:
        setSpriteUniforms(program);
        glUniform1f(glGetUniformLocation(program, "u_depthExtent"), depthExtent_);
        break;
    }
}

TransmittanceImage renderTransmittance(const GlContext& gl, const GpuTransmittanceCaster& caster,
                                       const LightFrame& frame, const ReceiverPlane& plane,
                                       const TransmittanceParameters& parameters) {
    requirePlane(plane);
    const CurrentContext current(gl);
    caster.requireContext("renderTransmittance: the caster");
    const bool local = caster.source() == TransmittanceSource::SlicemapSurfaces && caster.isLocal();
    const std::string defines = "#define VDS_SOURCE " + std::to_string(int(caster.source())) +
                                "\n#define VDS_SLICEMAP_LOCAL " + (local ? "1" : "0") + "\n";
    const Program& program = gl.program("voxel.transmittance." + std::to_string(int(caster.source())) + (local ? ".local" : ""), [&] {
        return buildProgram({{GL_VERTEX_SHADER, "voxel/transmittance_plane.vert", ""},
                             {GL_FRAGMENT_SHADER, "voxel/transmittance_plane.frag", ""}},
                            defines);
    });
    const detail::PlaneTargets targets({GL_RG32F}, GLsizei(plane.width), GLsizei(plane.height), "transmittance");
    const GLuint id = program.id();
    targets.use(id);
    glUniform3fv(glGetUniformLocation(id, "u_origin"), 1, &plane.origin[0]);
    glUniform3fv(glGetUniformLocation(id, "u_u"), 1, &plane.u[0]);
    glUniform3fv(glGetUniformLocation(id, "u_v"), 1, &plane.v[0]);
    glUniform2f(glGetUniformLocation(id, "u_size"), float(plane.width), float(plane.height));
    glUniformMatrix3fv(glGetUniformLocation(id, "u_toLight"), 1, GL_FALSE, glm::value_ptr(frame.toLight));
    glUniform1f(glGetUniformLocation(id, "u_sigma"), parameters.sigma);
    glUniform1f(glGetUniformLocation(id, "u_extinction"), parameters.extinction);
    caster.setUniforms(id);
    const detail::DrawTimes times = targets.draw("rendering transmittance");

    TransmittanceImage image;
    image.width = plane.width;
    image.height = plane.height;
    std::vector<float> texels(std::size_t(plane.width) * plane.height * 2);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(targets[0].id(), 0, GL_RG, GL_FLOAT, GLsizei(texels.size() * sizeof(float)), texels.data());
    image.gpuMilliseconds = times.gpuMilliseconds;
    image.wallMilliseconds = times.wallMilliseconds;
    checkGl("reading transmittance back");
    image.quantity.resize(texels.size() / 2);
    image.transmittance.resize(texels.size() / 2);
    for (std::size_t k = 0; k < image.quantity.size(); ++k) {
        image.quantity[k] = texels[2 * k];
        image.transmittance[k] = texels[2 * k + 1];
    }
    return image;
}

} // namespace vds::voxel
