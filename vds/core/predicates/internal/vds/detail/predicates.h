// vds internal: exact orientation predicates on float coordinates.
//
// Predicates. Coordinates are floats, permuted to (s,t,r) by the view axis (a
// cyclic permutation: orientations keep their sign) and read as doubles,
// which is exact. Two signs decide everything:
//  - orient2d(a,b,c) in (s,t), twice the projected signed area. It is the r
//    component of the normal (b-a)x(c-a): < 0 means the triangle faces the
//    viewer (the ray enters there); 0 means it is parallel to the axis and is
//    never crossed.
//  - orient3d(a,b,c,p) = det[a-p; b-p; c-p] = orient2d(a,b,c) * (r_plane - p.r),
//    r_plane being the plane's depth at p's (s,t) (multilinearity of det).
//    With (a,b,c) counter-clockwise in projection, the crossing lies strictly
//    in front of p iff orient3d < 0.
// Each is evaluated in double first and accepted when it exceeds Shewchuk's
// forward error bound (Shewchuk 1997, "Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates", ccwerrboundA and
// o3derrboundA; valid here: no double overflow or underflow is possible from
// float inputs). Otherwise it is evaluated exactly: the determinant is
// expanded into monomials of the input coordinates; a product of two floats
// is exact in double (at most 48 significant bits, exponents within range) and
// a product of three is exactly the pair (x, fma(xy, z, -x)) with x = fl(xy*z)
// (Two-Product; the exact product is a multiple of 2^-447, far above double's
// smallest subnormal, so the error term is representable). The 6 (orient2d)
// or 48 (orient3d) doubles are summed exactly by Grow-Expansion (Shewchuk,
// theorem 10), which yields a non-overlapping expansion sorted by magnitude:
// its sign is that of its last non-zero component.
#pragma once

#include <cmath>

namespace vds::detail {

constexpr double kEpsilon = 0x1p-53; // half an ulp of 1.0: the rounding unit
constexpr double kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;

inline int signOf(double x) { return (x > 0.0) - (x < 0.0); }

/// Exact signs by expansion arithmetic (predicates.cpp): the fallbacks of
/// `orient2d` and `orient3d` when the filter cannot decide.
int orient2dExact(const float* a, const float* b, const float* c);
int orient3dExact(const float* a, const float* b, const float* c, const float* p);

/// Sign of (b-a) x (c-a) in (s,t) = coordinates [0], [1]: > 0 counter-clockwise.
inline int orient2d(const float* a, const float* b, const float* c) {
    const double left = (double(a[0]) - double(c[0])) * (double(b[1]) - double(c[1]));
    const double right = (double(a[1]) - double(c[1])) * (double(b[0]) - double(c[0]));
    const double det = left - right;
    double magnitude;
    if (left > 0.0) {
        if (right <= 0.0) return signOf(det);
        magnitude = left + right;
    } else if (left < 0.0) {
        if (right >= 0.0) return signOf(det);
        magnitude = -left - right;
    } else {
        return signOf(det);
    }
    const double bound = kOrient2dBound * magnitude;
    if (det >= bound || -det >= bound) return signOf(det);
    return orient2dExact(a, b, c);
}

/// Sign of det[a-p; b-p; c-p] over (s,t,r): for a, b, c counter-clockwise in
/// (s,t), > 0 when p lies below the plane (smaller r), < 0 above it.
inline int orient3d(const float* a, const float* b, const float* c, const float* p) {
    const double adx = double(a[0]) - p[0], bdx = double(b[0]) - p[0], cdx = double(c[0]) - p[0];
    const double ady = double(a[1]) - p[1], bdy = double(b[1]) - p[1], cdy = double(c[1]) - p[1];
    const double adz = double(a[2]) - p[2], bdz = double(b[2]) - p[2], cdz = double(c[2]) - p[2];
    const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
    const double cdxady = cdx * ady, adxcdy = adx * cdy;
    const double adxbdy = adx * bdy, bdxady = bdx * ady;
    const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * std::fabs(adz) +
                             (std::fabs(cdxady) + std::fabs(adxcdy)) * std::fabs(bdz) +
                             (std::fabs(adxbdy) + std::fabs(bdxady)) * std::fabs(cdz);
    const double bound = kOrient3dBound * permanent;
    if (det > bound || -det > bound) return signOf(det);
    return orient3dExact(a, b, c, p);
}

} // namespace vds::detail
