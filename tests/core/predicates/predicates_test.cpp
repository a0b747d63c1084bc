// The exact predicates (vds/core/predicates/predicates.h) against an independent
// exact oracle: CGAL's orientation over exact rationals (Simple_cartesian
// of GMP's mpq), on random, nearly degenerate and exactly degenerate float
// inputs of wide exponent range, where the double filter cannot decide and
// the expansion arithmetic must.
#include <cmath>
#include <cstdint>
#include <random>

#include <CGAL/Gmpq.h>
#include <CGAL/Simple_cartesian.h>
#include <gtest/gtest.h>

#include <vds/detail/predicates.h>

namespace vds::detail {
namespace {

using Exact = CGAL::Simple_cartesian<CGAL::Gmpq>;

int cgal2d(const float* a, const float* b, const float* c) {
    return int(CGAL::orientation(Exact::Point_2(a[0], a[1]), Exact::Point_2(b[0], b[1]), Exact::Point_2(c[0], c[1])));
}
// CGAL's orientation(a, b, c, p) is the sign of det[b-a; c-a; p-a], which is
// minus det[a-p; b-p; c-p] (translate by a - p, rotate the rows).
int cgal3d(const float* a, const float* b, const float* c, const float* p) {
    const auto point = [](const float* q) { return Exact::Point_3(q[0], q[1], q[2]); };
    return -int(CGAL::orientation(point(a), point(b), point(c), point(p)));
}

struct Inputs {
    std::mt19937 rng{20261125};
    // A float of random sign and magnitude 2^e, e in [lo, hi], 24 random bits.
    float any(int lo, int hi) {
        const float m = std::uniform_real_distribution<float>(1.0f, 2.0f)(rng);
        const int e = std::uniform_int_distribution<int>(lo, hi)(rng);
        return (rng() & 1 ? -1.0f : 1.0f) * std::ldexp(m, e);
    }
    // `x` moved by up to `ulps` float steps either way.
    float nudge(float x, int ulps) {
        const int n = std::uniform_int_distribution<int>(-ulps, ulps)(rng);
        for (int k = 0; k < std::abs(n); ++k) x = std::nextafter(x, n > 0 ? INFINITY : -INFINITY);
        return x;
    }
};

TEST(Predicates, Orient2dEqualsCgalsExactOrientation) {
    Inputs in;
    int zeros = 0, nonzero = 0;
    for (int trial = 0; trial < 60000; ++trial) {
        float a[2], b[2], c[2];
        const int kind = trial % 5;
        const bool wide = kind == 0 || (trial / 5) % 2 == 0;
        const int lo = wide ? -20 : -4, hi = wide ? 20 : 4;
        for (int k = 0; k < 2; ++k) {
            a[k] = in.any(lo, hi);
            b[k] = in.any(lo, hi);
        }
        if (kind == 0) {
            c[0] = in.any(lo, hi);
            c[1] = in.any(lo, hi);
        } else if (kind == 4) {
            // On the line y = 3x, x of 22 bits over a wide exponent range (so
            // 3x is a float): exactly collinear, or c one step off the line.
            // The differences round in double: the filter must send these on.
            for (float* q : {a, b, c}) {
                q[0] = in.any(-20, 20);
                q[0] = std::ldexp(std::round(std::ldexp(q[0], 21 - std::ilogb(q[0]))), std::ilogb(q[0]) - 21);
                q[1] = 3.0f * q[0];
            }
            c[1] = in.nudge(c[1], 1);
        } else if (kind == 3) {
            // On a 1/8 grid, c the midpoint of ab or b itself: exactly collinear.
            for (int k = 0; k < 2; ++k) {
                a[k] = std::round(a[k] * 8.0f) / 8.0f;
                b[k] = std::round(b[k] * 8.0f) / 8.0f;
                c[k] = trial % 8 == 3 ? b[k] : (a[k] + b[k]) * 0.5f;
            }
        } else {
            // On the line ab, rounded to float (nearly collinear), nudged by kind - 1 ulps.
            const float t = std::uniform_real_distribution<float>(-2.0f, 3.0f)(in.rng);
            for (int k = 0; k < 2; ++k) c[k] = in.nudge(float(double(a[k]) + t * (double(b[k]) - a[k])), kind - 1);
        }
        const int expected = cgal2d(a, b, c);
        ASSERT_EQ(orient2d(a, b, c), expected) << trial;
        ASSERT_EQ(orient2dExact(a, b, c), expected) << trial;
        (expected == 0 ? zeros : nonzero) += 1;
    }
    // Exactly collinear cases happen (a point equal to a or b, or t on a float grid).
    EXPECT_GT(nonzero, 40000);
    EXPECT_GT(zeros, 10000);
}

TEST(Predicates, Orient3dEqualsCgalsExactOrientation) {
    Inputs in;
    int zeros = 0, nonzero = 0;
    for (int trial = 0; trial < 40000; ++trial) {
        float a[3], b[3], c[3], p[3];
        const int kind = trial % 5;
        // Half the nearly coplanar cases spread over a wide exponent range,
        // where double rounding of the determinant flips signs.
        const bool wide = kind == 0 || (trial / 5) % 2 == 0;
        const int lo = wide ? -20 : -3, hi = wide ? 20 : 3;
        for (int k = 0; k < 3; ++k) {
            a[k] = in.any(lo, hi);
            b[k] = in.any(lo, hi);
            c[k] = in.any(lo, hi);
        }
        if (kind == 0) {
            for (float& x : p) x = in.any(lo, hi);
        } else if (kind == 4) {
            // On the plane z = x + y, integer coordinates of up to 22 bits
            // (scaled by a power of two): exactly coplanar, or p one unit off.
            // The products round in double: the filter must send these on.
            std::uniform_int_distribution<int> coordinate(-(1 << 22), 1 << 22);
            const int scale = std::uniform_int_distribution<int>(-10, 10)(in.rng);
            for (float* q : {a, b, c, p}) {
                const int x = coordinate(in.rng), y = coordinate(in.rng);
                q[0] = std::ldexp(float(x), scale);
                q[1] = std::ldexp(float(y), scale);
                q[2] = std::ldexp(float(x + y), scale);
            }
            p[2] += std::ldexp(float(std::uniform_int_distribution<int>(-1, 1)(in.rng)), scale);
        } else if (kind == 3) {
            // A vertex of the triangle, or the midpoint of an edge with a power-of-two
            // coordinate grid: exactly on the plane.
            for (int k = 0; k < 3; ++k) {
                a[k] = std::round(a[k] * 8.0f) / 8.0f;
                b[k] = std::round(b[k] * 8.0f) / 8.0f;
                c[k] = std::round(c[k] * 8.0f) / 8.0f;
                p[k] = trial % 8 == 3 ? b[k] : (a[k] + c[k]) * 0.5f;
            }
        } else {
            // On the plane by barycentric coordinates, rounded to float, nudged by kind - 1 ulps.
            std::uniform_real_distribution<double> w(-0.5, 1.5);
            const double u = w(in.rng), v = w(in.rng);
            for (int k = 0; k < 3; ++k)
                p[k] = in.nudge(float(a[k] + u * (double(b[k]) - a[k]) + v * (double(c[k]) - a[k])), kind - 1);
        }
        const int expected = cgal3d(a, b, c, p);
        ASSERT_EQ(orient3d(a, b, c, p), expected) << trial;
        ASSERT_EQ(orient3dExact(a, b, c, p), expected) << trial;
        (expected == 0 ? zeros : nonzero) += 1;
    }
    EXPECT_GT(nonzero, 25000);
    EXPECT_GT(zeros, 5000);
}

} // namespace
} // namespace vds::detail
