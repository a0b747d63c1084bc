// vds: RGBA8 images and PNG files (libpng), for samples, eval and tests.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace vds::eval {

struct Image {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<std::uint8_t> rgba; ///< width*height*4 bytes, rows top to bottom

    Image() = default;
    Image(std::uint32_t w, std::uint32_t h) : width(w), height(h), rgba(std::size_t(w) * h * 4, 0) {}
    std::uint8_t* at(std::uint32_t x, std::uint32_t y) { return &rgba[(std::size_t(y) * width + x) * 4]; }
    const std::uint8_t* at(std::uint32_t x, std::uint32_t y) const { return &rgba[(std::size_t(y) * width + x) * 4]; }
};

/// Writes a PNG atomically (temporary file, then rename). Throws `IoError`.
void writePng(const Image& image, const std::string& path);
/// Reads a PNG as RGBA8. Throws `IoError` or `FormatError`.
Image readPng(const std::string& path);

} // namespace vds::eval
