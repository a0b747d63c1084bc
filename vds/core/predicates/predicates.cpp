// vds: the exact fallbacks of the orientation predicates (see predicates.h
// for the argument): Shewchuk 1997, "Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates", Grow-Expansion.
#include <vds/detail/predicates.h>

#include <cassert>

namespace vds::detail {
namespace {

// Knuth's Two-Sum: x + y == a + b exactly, x = fl(a + b).
inline void twoSum(double a, double b, double& x, double& y) {
    x = a + b;
    const double bv = x - a;
    const double av = x - bv;
    y = (a - av) + (b - bv);
}

// An exact sum of doubles as a Shewchuk expansion (Grow-Expansion with zero
// elimination): components non-overlapping, in increasing magnitude.
class ExactSum {
public:
    void add(double b) {
        assert(count_ < kCapacity);
        double q = b;
        int kept = 0;
        for (int i = 0; i < count_; ++i) {
            double sum, error;
            twoSum(q, parts_[i], sum, error);
            q = sum;
            if (error != 0.0) parts_[kept++] = error;
        }
        if (q != 0.0 || kept == 0) parts_[kept++] = q;
        count_ = kept;
    }
    // x * y * z exactly, for floats x, y, z: x*y is exact in double.
    void addProduct(double sign, float x, float y, float z) {
        const double xy = double(x) * double(y);
        const double hi = xy * double(z);
        const double lo = std::fma(xy, double(z), -hi);
        add(sign * hi);
        add(sign * lo);
    }
    int sign() const { return count_ == 0 ? 0 : signOf(parts_[count_ - 1]); }

private:
    static constexpr int kCapacity = 64;
    double parts_[kCapacity];
    int count_ = 0;
};

// det[a-p; b-p; c-p] = det[a;b;c] - det[p;b;c] - det[a;p;c] - det[a;b;p].
void addDet3(ExactSum& sum, double sign, const float* u, const float* v, const float* w) {
    sum.addProduct(sign, u[0], v[1], w[2]);
    sum.addProduct(-sign, u[0], v[2], w[1]);
    sum.addProduct(-sign, u[1], v[0], w[2]);
    sum.addProduct(sign, u[1], v[2], w[0]);
    sum.addProduct(sign, u[2], v[0], w[1]);
    sum.addProduct(-sign, u[2], v[1], w[0]);
}

} // namespace

int orient2dExact(const float* a, const float* b, const float* c) {
    // Expanded: a.s*b.t - a.t*b.s + b.s*c.t - b.t*c.s + c.s*a.t - c.t*a.s;
    // each product of two floats is exact in double.
    ExactSum sum;
    sum.add(double(a[0]) * double(b[1]));
    sum.add(-(double(a[1]) * double(b[0])));
    sum.add(double(b[0]) * double(c[1]));
    sum.add(-(double(b[1]) * double(c[0])));
    sum.add(double(c[0]) * double(a[1]));
    sum.add(-(double(c[1]) * double(a[0])));
    return sum.sign();
}

int orient3dExact(const float* a, const float* b, const float* c, const float* p) {
    ExactSum sum;
    addDet3(sum, 1.0, a, b, c);
    addDet3(sum, -1.0, p, b, c);
    addDet3(sum, -1.0, a, p, c);
    addDet3(sum, -1.0, a, b, p);
    return sum.sign();
}

} // namespace vds::detail
