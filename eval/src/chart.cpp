// The error-against-memory chart of a comparison, drawn into an RGBA image:
// axes with ticks and values, one polyline per method, a legend. Text uses a
// built-in 3x5 pixel font (digits, letters, a few signs), drawn twice as large.
#include <vds/eval/compare.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

namespace vds::eval {
namespace {

struct Colour {
    std::uint8_t r, g, b;
};

const std::map<std::string, Colour>& methodColours() {
    static const std::map<std::string, Colour> colours = {
        {"vds-parity", {31, 119, 180}},    {"vds-winding", {23, 190, 207}}, {"slicemap", {255, 127, 14}},
        {"slicemap-local", {214, 39, 40}}, {"solid", {44, 160, 44}},        {"solid-compute", {148, 103, 189}}};
    return colours;
}

// 3x5 glyphs, rows top to bottom, '#' set.
const std::map<char, const char*>& font() {
    static const std::map<char, const char*> glyphs = {
        {'0', "####.##.##.####"}, {'1', ".#.##..#..#.###"}, {'2', "###..#####..###"}, {'3', "###..####..####"},
        {'4', "#.##.####..#..#"}, {'5', "####..###..####"}, {'6', "####..####.####"}, {'7', "###..#..#.#..#."},
        {'8', "####.#####.####"}, {'9', "####.####..####"}, {'a', ".#.#.#####.##.#"}, {'b', "##.#.###.#.###."},
        {'c', ".###..#..#...##"}, {'d', "##.#.##.##.###."}, {'e', "####..##.#..###"}, {'f', "####..##.#..#.."},
        {'g', ".###..#.##.#.##"}, {'h', "#.##.#####.##.#"}, {'i', "###.#..#..#.###"}, {'j', "..#..#..##.#.#."},
        {'k', "#.##.###.#.##.#"}, {'l', "#..#..#..#..###"}, {'m', "#.########.##.#"}, {'n', "##.#.##.##.##.#"},
        {'o', ".#.#.##.##.#.#."}, {'p', "##.#.###.#..#.."}, {'q', ".#.#.##.###..##"}, {'r', "##.#.###.#.##.#"},
        {'s', ".###...#...###."}, {'t', "###.#..#..#..#."}, {'u', "#.##.##.##.####"}, {'v', "#.##.##.##.#.#."},
        {'w', "#.##.########.#"}, {'x', "#.##.#.#.#.##.#"}, {'y', "#.##.#.#..#..#."}, {'z', "###..#.#.#..###"},
        {'.', ".............#."}, {'-', "......###......"}, {'%', "#.#..#.#.#..#.#"}, {':', "....#.....#...."},
        {'/', "..#..#.#.#..#.."}, {'(', ".#.#..#..#...#."}, {')', ".#...#..#..#.#."}, {' ', "..............."},
    };
    return glyphs;
}

class Canvas {
public:
    explicit Canvas(Image& image) : image_(image) {}

    void pixel(int x, int y, Colour c) {
        if (x < 0 || y < 0 || x >= int(image_.width) || y >= int(image_.height)) return;
        std::uint8_t* p = image_.at(std::uint32_t(x), std::uint32_t(y));
        p[0] = c.r;
        p[1] = c.g;
        p[2] = c.b;
        p[3] = 255;
    }
    void fill(int x0, int y0, int x1, int y1, Colour c) {
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) pixel(x, y, c);
    }
    void line(double x0, double y0, double x1, double y1, Colour c, int thickness = 1) {
        const int steps = int(std::max(std::fabs(x1 - x0), std::fabs(y1 - y0))) + 1;
        for (int k = 0; k <= steps; ++k) {
            const double t = double(k) / steps;
            const int x = int(std::lround(x0 + t * (x1 - x0))), y = int(std::lround(y0 + t * (y1 - y0)));
            fill(x - thickness / 2, y - thickness / 2, x + (thickness - 1) / 2, y + (thickness - 1) / 2, c);
        }
    }
    void disc(double cx, double cy, double r, Colour c) {
        for (int y = int(cy - r); y <= int(cy + r) + 1; ++y)
            for (int x = int(cx - r); x <= int(cx + r) + 1; ++x)
                if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r) pixel(x, y, c);
    }
    void ring(double cx, double cy, double r, Colour c) {
        for (int y = int(cy - r) - 1; y <= int(cy + r) + 1; ++y)
            for (int x = int(cx - r) - 1; x <= int(cx + r) + 1; ++x) {
                const double d = std::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy));
                if (std::fabs(d - r) <= 1.0) pixel(x, y, c);
            }
    }
    // Text at (x, y) top-left, glyphs 3x5 scaled by 2, 8 pixels apart.
    void text(int x, int y, const std::string& s, Colour c) {
        for (char ch : s) {
            const auto it = font().find(char(std::tolower(static_cast<unsigned char>(ch))));
            if (it != font().end())
                for (int k = 0; it->second[k]; ++k)
                    if (it->second[k] == '#')
                        fill(x + 2 * (k % 3), y + 2 * (k / 3), x + 2 * (k % 3) + 1, y + 2 * (k / 3) + 1, c);
            x += 8;
        }
    }
    static int textWidth(const std::string& s) { return int(s.size()) * 8; }

private:
    Image& image_;
};

std::string byteLabel(double bytes) {
    char buf[32];
    if (bytes >= double(1 << 30))
        std::snprintf(buf, sizeof buf, "%gg", bytes / double(1 << 30));
    else if (bytes >= double(1 << 20))
        std::snprintf(buf, sizeof buf, "%gm", bytes / double(1 << 20));
    else if (bytes >= 1024.0)
        std::snprintf(buf, sizeof buf, "%gk", bytes / 1024.0);
    else
        std::snprintf(buf, sizeof buf, "%g", bytes);
    return buf;
}

// A "nice" upper bound: 1, 2 or 5 times a power of ten, at least v.
double niceCeil(double v) {
    if (!(v > 0.0)) return 1.0;
    const double p = std::pow(10.0, std::floor(std::log10(v)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * p >= v) return m * p;
    return 10.0 * p;
}

} // namespace

Image errorChart(const CompareResult& result, std::uint32_t width, std::uint32_t height) {
    width = std::max<std::uint32_t>(width, 400);
    height = std::max<std::uint32_t>(height, 300);
    Image image(width, height);
    Canvas canvas(image);
    const Colour white{255, 255, 255}, black{0, 0, 0}, grey{215, 215, 215}, dark{90, 90, 90};
    canvas.fill(0, 0, int(width) - 1, int(height) - 1, white);
    const int left = 70, right = int(width) - 190, top = 40, bottom = int(height) - 50;

    double lo = 1e300, hi = 0.0, errMax = 0.0;
    for (const CompareRow& r : result.rows) {
        if (r.memoryBytes == 0) continue;
        lo = std::min(lo, double(r.memoryBytes));
        hi = std::max(hi, double(r.memoryBytes));
        errMax = std::max(errMax, 100.0 * r.errorRate);
    }
    if (!(hi > 0.0)) {
        lo = 1024.0;
        hi = 1 << 20;
    }
    // x: log2 of bytes, whole powers of two; y: error % from 0.
    const double x0 = std::floor(std::log2(lo)), x1 = std::max(std::ceil(std::log2(hi)), x0 + 1.0);
    const double yMax = niceCeil(errMax * 1.05);
    const auto px = [&](double bytes) { return left + (std::log2(bytes) - x0) / (x1 - x0) * (right - left); };
    const auto py = [&](double percent) { return bottom - percent / yMax * (bottom - top); };

    // Grid, ticks and values.
    const int xStep = x1 - x0 > 12 ? 2 : 1;
    for (double e = x0; e <= x1; e += xStep) {
        const double x = px(std::exp2(e));
        canvas.line(x, top, x, bottom, grey);
        canvas.line(x, bottom, x, bottom + 5, black);
        const std::string label = byteLabel(std::exp2(e));
        canvas.text(int(x) - Canvas::textWidth(label) / 2, bottom + 10, label, black);
    }
    for (int k = 0; k <= 5; ++k) {
        const double v = yMax * k / 5.0, y = py(v);
        canvas.line(left, y, right, y, grey);
        canvas.line(left - 5, y, left, y, black);
        char buf[16];
        std::snprintf(buf, sizeof buf, "%g", v);
        canvas.text(left - 10 - Canvas::textWidth(buf), int(y) - 5, buf, black);
    }
    canvas.line(left, top, left, bottom, black, 2);
    canvas.line(left, bottom, right, bottom, black, 2);
    canvas.text(left, top - 28, "error % (all points) against memory (bytes): " + result.meshName, black);
    canvas.text((left + right) / 2 - Canvas::textWidth("memory") / 2, bottom + 30, "memory", dark);

    // Series: resolution rows as lines with dots, memory rows as rings. The
    // twins that often coincide (parity/winding, raster/compute) are drawn
    // thick first and thin on top, so both stay visible.
    const auto thick = [](const std::string& method) { return method == "vds-parity" || method == "solid"; };
    for (const auto& [method, colour] : methodColours()) {
        std::vector<const CompareRow*> line;
        for (const CompareRow& r : result.rows)
            if (r.method == method && r.series == "resolution" && r.memoryBytes > 0) line.push_back(&r);
        std::sort(line.begin(), line.end(),
                  [](const CompareRow* a, const CompareRow* b) { return a->memoryBytes < b->memoryBytes; });
        for (std::size_t k = 1; k < line.size(); ++k)
            canvas.line(px(double(line[k - 1]->memoryBytes)), py(100.0 * line[k - 1]->errorRate),
                        px(double(line[k]->memoryBytes)), py(100.0 * line[k]->errorRate), colour,
                        thick(method) ? 6 : 2);
        for (const CompareRow* r : line)
            canvas.disc(px(double(r->memoryBytes)), py(100.0 * r->errorRate), thick(method) ? 6.0 : 4.0, colour);
        for (const CompareRow& r : result.rows)
            if (r.method == method && r.series == "memory" && r.memoryBytes > 0)
                canvas.ring(px(double(r.memoryBytes)), py(100.0 * r.errorRate), thick(method) ? 9.0 : 7.0, colour);
    }

    // Legend.
    int y = top;
    for (const auto& [method, colour] : methodColours()) {
        canvas.line(right + 20, y + 4, right + 44, y + 4, colour, thick(method) ? 6 : 2);
        canvas.disc(right + 32, y + 4, thick(method) ? 6.0 : 4.0, colour);
        canvas.text(right + 52, y, method, black);
        y += 22;
    }
    y += 10;
    canvas.disc(right + 32, y + 4, 4.0, dark);
    canvas.text(right + 52, y, "resolution", black);
    y += 22;
    canvas.ring(right + 32, y + 4, 7.0, dark);
    canvas.text(right + 52, y, "memory budget", black);
    return image;
}

} // namespace vds::eval
