// Refraction through closed solids: two-surface refraction from a local
// slicemap pair (Eisemann & Décoret 2006, section 3.3) or a VDS, multiple-
// surface refraction by marching voxels with per-voxel normals (Chang et al.
// 2014, section 5.2), and an exact ray tracer. The CPU functions mirror
// shaders/voxel/refraction.glsl operation for operation.
#include <vds/voxel/refraction.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>

#include <GL/gl.h>
#include <GL/glext.h>
#include <glm/geometric.hpp>

#include <vds/error.h>
#include <vds/detail/parallel.h>

#include <vds/gl/shader.h>

#include "plane_targets.h"

namespace vds::voxel {

glm::vec2 RefractionView::rayXY(std::uint32_t i, std::uint32_t j) const {
    const float fx = (float(i) + 0.5f) / float(width);
    const float fy = (float(j) + 0.5f) / float(height);
    return {lo.x + (hi.x - lo.x) * fx, lo.y + (hi.y - lo.y) * fy};
}

namespace {

constexpr glm::vec3 kChannelAbsorption(1.0f, 0.35f, 0.2f);

float squareWaveIntegral(float x) {
    const float m = x - 2.0f * std::floor(x * 0.5f);
    return 1.0f - std::fabs(1.0f - m);
}

float filteredSquareWave(float x, float w) {
    if (!(w > 1e-4f)) {
        const float m = x - 2.0f * std::floor(x * 0.5f);
        return m < 1.0f ? 1.0f : -1.0f;
    }
    return (squareWaveIntegral(x + 0.5f * w) - squareWaveIntegral(x - 0.5f * w)) / w;
}

// GLSL's refract and reflect (N facing against I).
glm::vec3 refractGlsl(const glm::vec3& i, const glm::vec3& n, float eta) {
    const float c = glm::dot(n, i);
    const float k = 1.0f - eta * eta * (1.0f - c * c);
    if (k < 0.0f) return glm::vec3(0.0f);
    return eta * i - (eta * c + std::sqrt(k)) * n;
}
glm::vec3 reflectGlsl(const glm::vec3& i, const glm::vec3& n) { return i - 2.0f * glm::dot(n, i) * n; }

glm::vec4 toBackground(const glm::vec3& p, const glm::vec3& d, float insideLength, float backgroundZ) {
    if (!(d.z > 0.0f)) return {0.0f, 0.0f, insideLength, 0.0f};
    const float t = (backgroundZ - p.z) / d.z;
    return {p.x + d.x * t, p.y + d.y * t, insideLength, 1.0f};
}

float depthSlope(float minus, float centre, float plus, bool hasMinus, bool hasPlus, float h) {
    if (hasMinus && hasPlus) return (plus - minus) / (2.0f * h);
    if (hasPlus) return (plus - centre) / h;
    if (hasMinus) return (centre - minus) / h;
    return 0.0f;
}

void requireView(const RefractionView& view) {
    if (view.width == 0 || view.height == 0 || view.width > 16384 || view.height > 16384)
        throw InvalidArgument("the refraction view must be 1 to 16384 pixels on each side");
}

using Column = std::function<glm::vec4(const glm::vec2&)>;

glm::vec4 twoSurface(const Column& column, const glm::vec2& xy, float h, const RefractionView& view,
                     const RefractionParameters& r) {
    const glm::vec4 c = column(xy);
    if (c.w == 0.0f) return toBackground({xy, view.startZ}, {0, 0, 1}, 0.0f, view.backgroundZ);
    const glm::vec4 l = column(xy - glm::vec2(h, 0)), rt = column(xy + glm::vec2(h, 0));
    const glm::vec4 b = column(xy - glm::vec2(0, h)), t = column(xy + glm::vec2(0, h));
    const float fx = depthSlope(l.x, c.x, rt.x, l.w != 0.0f, rt.w != 0.0f, h);
    const float fy = depthSlope(b.x, c.x, t.x, b.w != 0.0f, t.w != 0.0f, h);
    const glm::vec3 n1 = glm::normalize(glm::vec3(fx, fy, -1.0f));
    const glm::vec3 t1 = refractGlsl({0, 0, 1}, n1, 1.0f / r.eta);
    const glm::vec3 p2 = glm::vec3(xy, c.x) + t1 * c.z;
    glm::vec4 c2 = column(glm::vec2(p2));
    glm::vec2 at(p2);
    if (c2.w == 0.0f) {
        c2 = c;
        at = xy;
    }
    const glm::vec4 l2 = column(at - glm::vec2(h, 0)), r2 = column(at + glm::vec2(h, 0));
    const glm::vec4 b2 = column(at - glm::vec2(0, h)), t2 = column(at + glm::vec2(0, h));
    const float gx = depthSlope(l2.y, c2.y, r2.y, l2.w != 0.0f, r2.w != 0.0f, h);
    const float gy = depthSlope(b2.y, c2.y, t2.y, b2.w != 0.0f, t2.w != 0.0f, h);
    const glm::vec3 n2 = glm::normalize(glm::vec3(-gx, -gy, 1.0f));
    glm::vec3 out = refractGlsl(t1, -n2, r.eta);
    if (out == glm::vec3(0.0f)) out = reflectGlsl(t1, -n2);
    return toBackground(p2, out, c.z, view.backgroundZ);
}

RefractionImage trace(const RefractionView& view, const RefractionParameters& parameters,
                      const std::function<glm::vec4(const glm::vec2&)>& ray) {
    requireView(view);
    RefractionImage image;
    image.width = view.width;
    image.height = view.height;
    image.hits.resize(std::size_t(view.width) * view.height);
    image.rgba.resize(image.hits.size() * 4);
    vds::detail::parallelFor(0, view.height, 1, [&](std::size_t rowBegin, std::size_t rowEnd) {
        for (std::size_t j = rowBegin; j < rowEnd; ++j)
            for (std::uint32_t i = 0; i < view.width; ++i) {
                const std::size_t k = j * view.width + i;
                image.hits[k] = ray(view.rayXY(i, std::uint32_t(j)));
                const glm::vec3 c = refractionColour(image.hits[k], parameters);
                for (int ch = 0; ch < 3; ++ch)
                    image.rgba[4 * k + std::size_t(ch)] =
                        std::uint8_t(std::lround(std::clamp(c[ch], 0.0f, 1.0f) * 255.0f));
                image.rgba[4 * k + 3] = 255;
            }
    });
    return image;
}

// The inner slices of one column by the inner-voxel rule, one pass.
int innerSlices(const std::uint32_t* front, const std::uint32_t* back, std::uint32_t words) {
    int inner = 0, pending = 0, state = 0;
    for (std::uint32_t w = 0; w < words; ++w)
        for (int k = 0; k < 32; ++k) {
            const bool f = (front[w] >> k) & 1u, b = (back[w] >> k) & 1u;
            if (f || b) {
                if (state == 2 && b && !f) inner += pending;
                pending = 0;
                inner += 1;
                state = f && b ? 2 : (f ? 1 : 0);
            } else if (state == 1) {
                inner += 1;
            } else if (state == 2) {
                pending += 1;
            }
        }
    return inner;
}

glm::vec4 slicemapColumn(const Slicemap& map, const glm::vec2& xy) {
    const VoxelGrid& g = map.grid;
    const glm::vec3 v = g.toCells({xy, g.box.lo.z});
    const float fx = std::floor(v.x), fy = std::floor(v.y);
    if (!(fx >= 0.0f && fx < float(g.dims.x) && fy >= 0.0f && fy < float(g.dims.y))) return glm::vec4(0.0f);
    const std::size_t c = std::size_t(fy) * g.dims.x + std::size_t(fx);
    const float near = map.nearDepth[c], far = map.farDepth[c], perDepth = map.slicesPerDepth[c];
    if (!(near <= far)) return glm::vec4(0.0f);
    const int inner = innerSlices(&map.front[c * map.words], &map.back[c * map.words], map.words);
    const float front = g.box.lo.z + near / g.scale.z;
    const float back = g.box.lo.z + far / g.scale.z;
    const float sliceLength = perDepth > 0.0f ? 1.0f / (perDepth * g.scale.z) : 0.0f;
    return {front, back, float(inner) * sliceLength, 1.0f};
}

glm::vec4 spriteColumn(const Sprite& sprite, const glm::vec2& xy) {
    const SpriteGrid& g = sprite.grid;
    const float depthLo = g.box.lo.z, depthExtent = g.box.hi.z - g.box.lo.z;
    const glm::vec3 t = g.toTexture({xy, depthLo});
    const float fs = std::floor(t.x * float(g.width)), ft = std::floor(t.y * float(g.height));
    if (!(fs >= 0.0f && fs < float(g.width) && ft >= 0.0f && ft < float(g.height))) return glm::vec4(0.0f);
    const std::size_t column = std::size_t(ft) * g.width + std::size_t(fs);
    int winding = 0;
    float entry = 0.0f, first = -1.0f, last = 0.0f, length = 0.0f;
    for (std::uint32_t k = sprite.offsets[column]; k < sprite.offsets[column + 1]; ++k) {
        const float e = sprite.crossings[k];
        if (e == 1.0f) break; // as the GLSL, which cannot tell it from the padding
        const float d = crossingDepth(e);
        const int next = winding + (crossingEnters(e) ? 1 : -1);
        if (winding == 0 && next != 0) {
            entry = d;
            if (first < 0.0f) first = d;
        } else if (winding != 0 && next == 0) {
            length += d - entry;
            last = d;
        }
        winding = next;
    }
    if (first < 0.0f) return glm::vec4(0.0f);
    return {depthLo + first * depthExtent, depthLo + last * depthExtent, length * depthExtent, 1.0f};
}

glm::vec4 voxelMarch(const SlicedVoxels& voxels, const glm::vec2& xy, const RefractionView& view,
                     const RefractionParameters& r) {
    const VoxelGrid& g = voxels.grid;
    glm::vec3 p(xy, std::max(view.startZ, g.box.lo.z));
    glm::vec3 d(0, 0, 1);
    const float step = 0.5f / g.scale.x;
    bool inside = false;
    float insideLength = 0.0f;
    for (std::uint32_t s = 0; s < r.maxSteps; ++s) {
        const glm::vec3 v = g.toCells(p);
        const glm::vec3 f(std::floor(v.x), std::floor(v.y), std::floor(v.z));
        if (!(f.x >= 0.0f && f.y >= 0.0f && f.z >= 0.0f && f.x < float(g.dims.x) && f.y < float(g.dims.y) &&
              f.z < float(g.dims.z)))
            return toBackground(p, d, insideLength, view.backgroundZ);
        const glm::vec4 voxel = voxels.voxels[voxels.index(std::uint32_t(f.x), std::uint32_t(f.y), std::uint32_t(f.z))];
        const float len = glm::length(glm::vec3(voxel));
        if (voxel.w > 0.0f && len > 1e-6f) {
            const glm::vec3 n = glm::vec3(voxel) / len;
            const float c = glm::dot(d, n);
            if (!inside && c < 0.0f) {
                d = refractGlsl(d, n, 1.0f / r.eta);
                inside = true;
            } else if (inside && c > 0.0f) {
                const glm::vec3 out = refractGlsl(d, -n, r.eta);
                if (out == glm::vec3(0.0f)) {
                    d = reflectGlsl(d, -n);
                } else {
                    d = out;
                    inside = false;
                }
            }
        }
        p += d * step;
        if (inside) insideLength += step;
    }
    return {0.0f, 0.0f, insideLength, 0.0f};
}

} // namespace

glm::vec3 refractionColour(const glm::vec4& hit, const RefractionParameters& r) {
    if (hit.w == 0.0f) return glm::vec3(0.0f);
    const float w = r.frost * hit.z / r.checker;
    const float a = filteredSquareWave(hit.x / r.checker, w) * filteredSquareWave(hit.y / r.checker, w);
    const glm::vec3 background = glm::mix(glm::vec3(0.2f, 0.25f, 0.35f), glm::vec3(0.95f, 0.92f, 0.85f), 0.5f + 0.5f * a);
    const glm::vec3 k = -r.absorption * hit.z * kChannelAbsorption;
    return background * glm::vec3(std::exp(k.x), std::exp(k.y), std::exp(k.z));
}

RefractionImage refractOnCpu(const Slicemap& map, const RefractionView& view, const RefractionParameters& parameters) {
    if (map.slicing != Slicing::Local) throw InvalidArgument("two-surface refraction needs a locally sliced slicemap");
    return trace(view, parameters, [&](const glm::vec2& xy) {
        return twoSurface([&](const glm::vec2& q) { return slicemapColumn(map, q); }, xy, map.grid.cellSize(), view,
                          parameters);
    });
}

RefractionImage refractOnCpu(const Sprite& sprite, const RefractionView& view, const RefractionParameters& parameters) {
    if (sprite.grid.axis != Axis::Z) throw InvalidArgument("refraction needs a sprite baked along z (the view)");
    return trace(view, parameters, [&](const glm::vec2& xy) {
        return twoSurface([&](const glm::vec2& q) { return spriteColumn(sprite, q); }, xy, sprite.grid.texelSize, view,
                          parameters);
    });
}

RefractionImage refractOnCpu(const SlicedVoxels& voxels, const RefractionView& view,
                             const RefractionParameters& parameters) {
    return trace(view, parameters, [&](const glm::vec2& xy) { return voxelMarch(voxels, xy, view, parameters); });
}

RefractionImage refractExactly(MeshView mesh, const RefractionView& view, const RefractionParameters& parameters) {
    const double scale = [&] {
        const Box b = meshBounds(mesh);
        return double(std::max({b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z}));
    }();
    const double epsilon = 1e-7 * scale;
    return trace(view, parameters, [&](const glm::vec2& xy) -> glm::vec4 {
        glm::dvec3 o(xy.x, xy.y, view.startZ), d(0, 0, 1);
        int depth = 0; // surfaces entered minus left
        double insideLength = 0.0;
        for (std::uint32_t bounce = 0; bounce <= parameters.maxBounces; ++bounce) {
            double best = std::numeric_limits<double>::infinity();
            glm::dvec3 normal(0.0);
            for (std::size_t t = 0; t < mesh.triangleCount; ++t) { // Moeller-Trumbore
                const glm::dvec3 a(mesh.positions[mesh.triangles[t][0]]), b(mesh.positions[mesh.triangles[t][1]]),
                    c(mesh.positions[mesh.triangles[t][2]]);
                const glm::dvec3 e1 = b - a, e2 = c - a, pv = glm::cross(d, e2);
                const double det = glm::dot(e1, pv);
                if (det == 0.0) continue;
                const glm::dvec3 tv = o - a;
                const double u = glm::dot(tv, pv) / det;
                if (u < 0.0 || u > 1.0) continue;
                const glm::dvec3 qv = glm::cross(tv, e1);
                const double v = glm::dot(d, qv) / det;
                if (v < 0.0 || u + v > 1.0) continue;
                const double s = glm::dot(e2, qv) / det;
                if (s > epsilon && s < best) {
                    best = s;
                    normal = glm::normalize(glm::cross(e1, e2));
                }
            }
            if (!std::isfinite(best)) {
                const glm::vec4 hit = toBackground(glm::vec3(o), glm::vec3(d), float(insideLength),
                                                   view.backgroundZ);
                return depth == 0 ? hit : glm::vec4(0.0f, 0.0f, float(insideLength), 0.0f);
            }
            if (depth > 0) insideLength += best;
            o += best * d;
            const double c = glm::dot(d, normal);
            // Entering where the ray meets the outside of the surface.
            const bool entering = c < 0.0;
            const glm::dvec3 n = entering ? normal : -normal;
            const double eta = entering ? 1.0 / double(parameters.eta) : double(parameters.eta);
            const double ci = glm::dot(n, d);
            const double k = 1.0 - eta * eta * (1.0 - ci * ci);
            if (k < 0.0) {
                d = d - 2.0 * ci * n; // total internal reflection: stays on its side
            } else {
                d = glm::normalize(eta * d - (eta * ci + std::sqrt(k)) * n);
                depth += entering ? 1 : -1;
            }
        }
        return {0.0f, 0.0f, float(insideLength), 0.0f};
    });
}

// The scope (a temporary of the delegating call) keeps `gl` current while
// the delegated constructor runs, and restores the caller's context after.
GpuRefractionCaster::GpuRefractionCaster(const GlContext& gl, const Slicemap& map)
    : GpuRefractionCaster((CurrentContext(gl), map)) {}
GpuRefractionCaster::GpuRefractionCaster(const GlContext& gl, const Sprite& sprite)
    : GpuRefractionCaster((CurrentContext(gl), sprite)) {}
GpuRefractionCaster::GpuRefractionCaster(const GlContext& gl, const SlicedVoxels& voxels)
    : GpuRefractionCaster((CurrentContext(gl), voxels)) {}

GpuRefractionCaster::GpuRefractionCaster(const Slicemap& map)
    : GpuCaster("GpuRefractionCaster"), method_(RefractionMethod::SlicemapTwoSurface) {
    if (map.slicing != Slicing::Local) throw InvalidArgument("two-surface refraction needs a locally sliced slicemap");
    upload(map);
    columnStep_ = map.grid.cellSize();
}

GpuRefractionCaster::GpuRefractionCaster(const Sprite& sprite)
    : GpuCaster("GpuRefractionCaster"), method_(RefractionMethod::SpriteTwoSurface) {
    if (sprite.grid.axis != Axis::Z) throw InvalidArgument("refraction needs a sprite baked along z (the view)");
    upload(sprite);
    depthLo_ = sprite.grid.box.lo.z;
    depthExtent_ = sprite.grid.box.hi.z - sprite.grid.box.lo.z;
    columnStep_ = sprite.grid.texelSize;
}

GpuRefractionCaster::GpuRefractionCaster(const SlicedVoxels& voxels)
    : GpuCaster("GpuRefractionCaster"), method_(RefractionMethod::VoxelMarch) {
    upload(voxels.grid, GL_RGBA32F, GL_RGBA, &voxels.voxels.data()->x, voxels.memoryBytes(), "uploading voxel normals");
}

void GpuRefractionCaster::setUniforms(GLuint program) const {
    switch (method_) {
    case RefractionMethod::SlicemapTwoSurface:
        setSlicemapUniforms(program);
        glUniform1f(glGetUniformLocation(program, "u_columnStep"), columnStep_);
        break;
    case RefractionMethod::SpriteTwoSurface:
        setSpriteUniforms(program);
        glUniform1f(glGetUniformLocation(program, "u_depthLo"), depthLo_);
        glUniform1f(glGetUniformLocation(program, "u_depthExtent"), depthExtent_);
        glUniform1f(glGetUniformLocation(program, "u_columnStep"), columnStep_);
        break;
    case RefractionMethod::VoxelMarch:
    case RefractionMethod::Exact: setVolumeUniforms(program, "u_voxels"); break;
    }
}

RefractionImage renderRefraction(const GlContext& gl, const GpuRefractionCaster& caster, const RefractionView& view,
                                 const RefractionParameters& parameters) {
    requireView(view);
    const CurrentContext current(gl);
    caster.requireContext("renderRefraction: the caster");
    const std::string defines = "#define VDS_METHOD " + std::to_string(int(caster.method())) + "\n";
    const Program& program = gl.program("voxel.refraction." + std::to_string(int(caster.method())), [&] {
        return buildProgram({{GL_VERTEX_SHADER, "voxel/transmittance_plane.vert", ""},
                             {GL_FRAGMENT_SHADER, "voxel/refraction.frag", ""}},
                            defines);
    });
    const detail::PlaneTargets targets({GL_RGBA32F, GL_RGBA8}, GLsizei(view.width), GLsizei(view.height), "refraction");
    const GLuint id = program.id();
    targets.use(id);
    glUniform2f(glGetUniformLocation(id, "u_lo"), view.lo.x, view.lo.y);
    glUniform2f(glGetUniformLocation(id, "u_hi"), view.hi.x, view.hi.y);
    glUniform2f(glGetUniformLocation(id, "u_size"), float(view.width), float(view.height));
    glUniform1f(glGetUniformLocation(id, "u_startZ"), view.startZ);
    glUniform1f(glGetUniformLocation(id, "u_refraction.eta"), parameters.eta);
    glUniform1f(glGetUniformLocation(id, "u_refraction.absorption"), parameters.absorption);
    glUniform1f(glGetUniformLocation(id, "u_refraction.frost"), parameters.frost);
    glUniform1f(glGetUniformLocation(id, "u_refraction.checker"), parameters.checker);
    glUniform1f(glGetUniformLocation(id, "u_refraction.backgroundZ"), view.backgroundZ);
    glUniform1i(glGetUniformLocation(id, "u_refraction.maxSteps"), GLint(std::min<std::uint32_t>(parameters.maxSteps, 1u << 30)));
    caster.setUniforms(id);
    const detail::DrawTimes times = targets.draw("rendering refraction");

    RefractionImage image;
    image.width = view.width;
    image.height = view.height;
    image.hits.resize(std::size_t(view.width) * view.height);
    image.rgba.resize(image.hits.size() * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(targets[0].id(), 0, GL_RGBA, GL_FLOAT, GLsizei(image.hits.size() * sizeof(glm::vec4)),
                      image.hits.data());
    glGetTextureImage(targets[1].id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(image.rgba.size()), image.rgba.data());
    image.gpuMilliseconds = times.gpuMilliseconds;
    image.wallMilliseconds = times.wallMilliseconds;
    checkGl("reading refraction back");
    return image;
}

} // namespace vds::voxel
