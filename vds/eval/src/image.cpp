// PNG files through libpng's simplified API (png_image): libpng converts any
// PNG to RGBA8 on reading and does the chunk work on writing.
#include <vds/eval/image.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <new>

#include <png.h>

#include <vds/atomic_file.h>
#include <vds/error.h>

namespace vds::eval {

namespace {

// A png_image that gives back what libpng holds for it however we leave.
struct PngImage : png_image {
    PngImage() : png_image{} { version = PNG_IMAGE_VERSION; }
    ~PngImage() { png_image_free(this); }
    PngImage(const PngImage&) = delete;
    PngImage& operator=(const PngImage&) = delete;
};

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};

} // namespace

void writePng(const Image& image, const std::string& path) {
    if (image.width == 0 || image.height == 0 || image.rgba.size() != std::size_t(image.width) * image.height * 4)
        throw InvalidArgument(path + ": image is empty or its size disagrees with its pixels");
    AtomicFile out(path);
    PngImage png;
    png.width = image.width;
    png.height = image.height;
    png.format = PNG_FORMAT_RGBA;
    // Checks fflush and fclose and says why it failed; AtomicFile syncs and renames.
    if (!png_image_write_to_file(&png, out.path().c_str(), 0, image.rgba.data(), 0, nullptr))
        throw IoError(path + ": cannot write PNG (" + png.message + ")");
    out.commit();
}

Image readPng(const std::string& path) {
    // Opened here, not by libpng, so that a missing file is an IoError and
    // only what is wrong inside the file is a FormatError.
    const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
    if (!file) throw IoError(path + ": cannot open (" + std::strerror(errno) + ")");
    PngImage png;
    if (!png_image_begin_read_from_stdio(&png, file.get()))
        throw FormatError(path + ": not a PNG file (" + png.message + ")");
    png.format = PNG_FORMAT_RGBA;
    Image image;
    try {
        image = Image(png.width, png.height);
    } catch (const std::bad_alloc&) {
        throw OutOfMemory(path + ": a " + std::to_string(png.width) + "x" + std::to_string(png.height) +
                          " image does not fit in memory");
    }
    if (!png_image_finish_read(&png, nullptr, image.rgba.data(), 0, nullptr))
        throw FormatError(path + ": truncated or corrupt PNG (" + png.message + ")");
    return image;
}

} // namespace vds::eval
