// Test support: rendered images against stored references, within stated
// limits (the model is Magnum's CompareImageToFile): the largest and the
// mean per-channel difference, over every pixel.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include <vds/error.h>
#include <vds/eval/image.h>

namespace vds::test {

struct ImageDelta {
    int max = 0;            ///< largest difference of one channel, 0..255
    double mean = 0.0;      ///< mean over every channel of every pixel
    std::size_t pixels = 0; ///< pixels with any channel differing
};

inline ImageDelta compareImages(const eval::Image& a, const eval::Image& b) {
    ImageDelta d;
    double sum = 0.0;
    for (std::size_t p = 0; p < a.rgba.size() / 4; ++p) {
        int pixelMax = 0;
        for (int c = 0; c < 4; ++c) {
            const int delta = std::abs(int(a.rgba[4 * p + std::size_t(c)]) - int(b.rgba[4 * p + std::size_t(c)]));
            pixelMax = std::max(pixelMax, delta);
            sum += delta;
        }
        d.max = std::max(d.max, pixelMax);
        d.pixels += pixelMax > 0;
    }
    d.mean = a.rgba.empty() ? 0.0 : sum / double(a.rgba.size());
    return d;
}

/// Whether `actual` matches the PNG at `referencePath` within `maxThreshold`
/// (per channel) and `meanThreshold`. With VDS_SAVE_REFERENCE_IMAGES=1 in
/// the environment, `actual` replaces the reference instead (to regenerate it).
inline ::testing::AssertionResult imageMatchesReference(const eval::Image& actual, const std::string& referencePath,
                                                        int maxThreshold, double meanThreshold) {
    const char* save = std::getenv("VDS_SAVE_REFERENCE_IMAGES");
    if (save && std::string(save) == "1") {
        eval::writePng(actual, referencePath);
        return ::testing::AssertionSuccess() << "saved " << referencePath;
    }
    eval::Image expected;
    try {
        expected = eval::readPng(referencePath);
    } catch (const Error& e) {
        return ::testing::AssertionFailure() << e.what();
    }
    if (expected.width != actual.width || expected.height != actual.height)
        return ::testing::AssertionFailure() << "size " << actual.width << "x" << actual.height << ", reference "
                                             << expected.width << "x" << expected.height;
    const ImageDelta d = compareImages(actual, expected);
    if (d.max > maxThreshold || d.mean > meanThreshold)
        return ::testing::AssertionFailure() << "max delta " << d.max << " (limit " << maxThreshold << "), mean delta "
                                             << d.mean << " (limit " << meanThreshold << "), " << d.pixels
                                             << " pixels differ, against " << referencePath;
    return ::testing::AssertionSuccess();
}

} // namespace vds::test
