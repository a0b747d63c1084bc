// The error-against-memory chart of a comparison as an SVG document: axes
// with ticks and values, one line per method, a legend. The viewer draws the
// lines and the text, so the chart stays sharp at any size and its numbers
// can be read (each dot has a tooltip with its row's figures).
#include <vds/eval/compare.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <locale>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace vds::eval {
namespace {

const char* methodColour(const std::string& method) {
    static const std::pair<const char*, const char*> colours[] = {
        {"sprite", "#1f77b4"},     {"sprite/winding", "#17becf"}, {"slicemap", "#ff7f0e"},
        {"slicemap-local", "#d62728"}, {"solid", "#2ca02c"},       {"solid-compute", "#9467bd"},
        {"sprite/generalized-winding", "#8c564b"}};
    for (const auto& [name, colour] : colours)
        if (method == name) return colour;
    return "#5a5a5a";
}

std::string escapeXml(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        default: out += c;
        }
    }
    return out;
}

std::string format(const char* spec, double value) {
    char buf[64];
    std::snprintf(buf, sizeof buf, spec, value);
    return buf;
}

std::string byteLabel(double bytes) {
    if (bytes >= double(1 << 30)) return format("%.4g GiB", bytes / double(1 << 30));
    if (bytes >= double(1 << 20)) return format("%.4g MiB", bytes / double(1 << 20));
    if (bytes >= 1024.0) return format("%.4g KiB", bytes / 1024.0);
    return format("%.4g B", bytes);
}

// A "nice" upper bound: 1, 2 or 5 times a power of ten, at least v.
double niceCeil(double v) {
    if (!(v > 0.0)) return 1.0;
    const double p = std::pow(10.0, std::floor(std::log10(v)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * p >= v) return m * p;
    return 10.0 * p;
}

// SVG elements, coordinates in pixels with one decimal.
class Svg {
public:
    Svg(std::uint32_t width, std::uint32_t height) {
        out_.imbue(std::locale::classic());
        out_ << std::fixed << std::setprecision(1);
        out_ << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
             << "\" viewBox=\"0 0 " << width << ' ' << height << "\" font-family=\"sans-serif\" font-size=\"13\">\n"
             << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    }
    void line(double x0, double y0, double x1, double y1, const char* colour, double width) {
        out_ << "<line x1=\"" << x0 << "\" y1=\"" << y0 << "\" x2=\"" << x1 << "\" y2=\"" << y1 << "\" stroke=\""
             << colour << "\" stroke-width=\"" << width << "\"/>\n";
    }
    void polyline(const std::vector<std::pair<double, double>>& points, const char* colour, double width) {
        out_ << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"" << width
             << "\" stroke-linejoin=\"round\" points=\"";
        for (std::size_t k = 0; k < points.size(); ++k)
            out_ << (k ? " " : "") << points[k].first << ',' << points[k].second;
        out_ << "\"/>\n";
    }
    /// A filled dot, or with `ring` an open circle; `tooltip` may be empty.
    void circle(double x, double y, double r, const char* colour, bool ring, const std::string& tooltip) {
        out_ << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"" << r << '"'
             << (ring ? " fill=\"none\" stroke-width=\"2\" stroke=\"" : " fill=\"") << colour << '"';
        if (tooltip.empty())
            out_ << "/>\n";
        else
            out_ << "><title>" << escapeXml(tooltip) << "</title></circle>\n";
    }
    /// `anchor`: start, middle or end; y is the text's baseline.
    void text(double x, double y, const std::string& text, const char* anchor, const char* colour = "black") {
        out_ << "<text x=\"" << x << "\" y=\"" << y << "\" text-anchor=\"" << anchor << "\" fill=\"" << colour << "\">"
             << escapeXml(text) << "</text>\n";
    }
    std::string finish() {
        out_ << "</svg>\n";
        return out_.str();
    }

private:
    std::ostringstream out_;
};

std::string tooltip(const CompareRow& r) {
    return r.name() + (r.series == "memory" ? ", budget " + byteLabel(double(r.target)) : std::string()) +
           ", resolution " + std::to_string(r.resolution) + ": " + byteLabel(double(r.memoryBytes)) + ", " +
           format("%.3f", 100.0 * r.errorRate) + " % wrong";
}

// Where the chart's frame lies and how values map into it: x is log2 of
// bytes over whole powers of two, y the error % from 0.
struct Plot {
    double left = 70, right = 0, top = 40, bottom = 0;
    double x0 = 0, x1 = 1, yMax = 1;
    double px(double bytes) const { return left + (std::log2(bytes) - x0) / (x1 - x0) * (right - left); }
    double py(double percent) const { return bottom - percent / yMax * (bottom - top); }
};

const char *const kBlack = "black", *const kGrey = "#d7d7d7", *const kDark = "#5a5a5a";

bool thick(const std::string& method) { return method == "sprite" || method == "solid"; }

// The grid, ticks, values and titles.
void drawAxes(Svg& svg, const Plot& p, const std::string& meshName) {
    const int xStep = p.x1 - p.x0 > 12 ? 2 : 1;
    for (double e = p.x0; e <= p.x1; e += xStep) {
        const double x = p.px(std::exp2(e));
        svg.line(x, p.top, x, p.bottom, kGrey, 1);
        svg.line(x, p.bottom, x, p.bottom + 5, kBlack, 1);
        svg.text(x, p.bottom + 19, byteLabel(std::exp2(e)), "middle");
    }
    for (int k = 0; k <= 5; ++k) {
        const double v = p.yMax * k / 5.0, y = p.py(v);
        svg.line(p.left, y, p.right, y, kGrey, 1);
        svg.line(p.left - 5, y, p.left, y, kBlack, 1);
        svg.text(p.left - 9, y + 4, format("%g", v), "end");
    }
    svg.line(p.left, p.top, p.left, p.bottom, kBlack, 2);
    svg.line(p.left, p.bottom, p.right, p.bottom, kBlack, 2);
    svg.text(p.left, p.top - 16, "error % (all points) against memory (bytes, log scale): " + meshName, "start");
    svg.text((p.left + p.right) / 2, p.bottom + 40, "memory", "middle", kDark);
}

// One method's rows: resolution rows as a line with dots, memory rows as
// rings. The twins that often coincide (parity/winding, raster/compute) are
// drawn thick first and thin on top, so both stay visible.
void drawSeries(Svg& svg, const Plot& p, const CompareResult& result, const std::string& method) {
    const char* colour = methodColour(method);
    std::vector<const CompareRow*> series;
    for (const CompareRow& r : result.rows)
        if (r.name() == method && r.series == "resolution" && r.memoryBytes > 0) series.push_back(&r);
    std::sort(series.begin(), series.end(),
              [](const CompareRow* a, const CompareRow* b) { return a->memoryBytes < b->memoryBytes; });
    std::vector<std::pair<double, double>> points;
    for (const CompareRow* r : series) points.emplace_back(p.px(double(r->memoryBytes)), p.py(100.0 * r->errorRate));
    if (!points.empty()) svg.polyline(points, colour, thick(method) ? 6 : 2);
    for (std::size_t k = 0; k < series.size(); ++k)
        svg.circle(points[k].first, points[k].second, thick(method) ? 6 : 4, colour, false, tooltip(*series[k]));
    for (const CompareRow& r : result.rows)
        if (r.name() == method && r.series == "memory" && r.memoryBytes > 0)
            svg.circle(p.px(double(r.memoryBytes)), p.py(100.0 * r.errorRate), thick(method) ? 9 : 7, colour, true,
                       tooltip(r));
}

void drawLegend(Svg& svg, const Plot& p, const std::vector<std::string>& methods) {
    double y = p.top;
    for (const std::string& method : methods) {
        const char* colour = methodColour(method);
        svg.line(p.right + 20, y, p.right + 44, y, colour, thick(method) ? 6 : 2);
        svg.circle(p.right + 32, y, thick(method) ? 6 : 4, colour, false, "");
        svg.text(p.right + 52, y + 4, method, "start");
        y += 22;
    }
    y += 10;
    svg.circle(p.right + 32, y, 4, kDark, false, "");
    svg.text(p.right + 52, y + 4, "resolution", "start");
    y += 22;
    svg.circle(p.right + 32, y, 7, kDark, true, "");
    svg.text(p.right + 52, y + 4, "memory budget", "start");
}

} // namespace

std::string errorChart(const CompareResult& result, std::uint32_t width, std::uint32_t height) {
    width = std::max<std::uint32_t>(width, 400);
    height = std::max<std::uint32_t>(height, 300);
    Svg svg(width, height);
    Plot plot;
    plot.right = double(width) - 190;
    plot.bottom = double(height) - 50;

    double lo = 1e300, hi = 0.0, errMax = 0.0;
    std::vector<std::string> methods; // in the order of the rows
    for (const CompareRow& r : result.rows) {
        if (std::find(methods.begin(), methods.end(), r.name()) == methods.end()) methods.push_back(r.name());
        if (r.memoryBytes == 0) continue;
        lo = std::min(lo, double(r.memoryBytes));
        hi = std::max(hi, double(r.memoryBytes));
        errMax = std::max(errMax, 100.0 * r.errorRate);
    }
    if (!(hi > 0.0)) {
        lo = 1024.0;
        hi = 1 << 20;
    }
    plot.x0 = std::floor(std::log2(lo));
    plot.x1 = std::max(std::ceil(std::log2(hi)), plot.x0 + 1.0);
    plot.yMax = niceCeil(errMax * 1.05);
    drawAxes(svg, plot, result.meshName);
    for (const std::string& method : methods) drawSeries(svg, plot, result, method);
    drawLegend(svg, plot, methods);
    return svg.finish();
}

} // namespace vds::eval
