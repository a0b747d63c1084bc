#include <vds/eval/image.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include <png.h>
#include <unistd.h>

#include <vds/atomic_file.h>
#include <vds/error.h>

namespace vds::eval {

namespace {
struct FileCloser {
    void operator()(std::FILE* f) const { if (f) std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

[[noreturn]] void pngError(png_structp png, png_const_charp message) {
    auto* text = static_cast<std::string*>(png_get_error_ptr(png));
    *text = message;
    png_longjmp(png, 1);
}
void pngWarning(png_structp, png_const_charp) {}
} // namespace

void writePng(const Image& image, const std::string& path) {
    if (image.width == 0 || image.height == 0 || image.rgba.size() != std::size_t(image.width) * image.height * 4)
        throw InvalidArgument(path + ": image is empty or its size disagrees with its pixels");
    AtomicFile out(path);
    {
        File f(std::fopen(out.path().c_str(), "wb"));
        if (!f) throw IoError(path + ": cannot write (" + std::strerror(errno) + ")");
        std::string error;
        png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, pngError, pngWarning);
        png_infop info = png ? png_create_info_struct(png) : nullptr;
        if (!info) {
            png_destroy_write_struct(&png, nullptr);
            throw OutOfMemory("libpng: cannot allocate");
        }
        if (setjmp(png_jmpbuf(png))) {
            png_destroy_write_struct(&png, &info);
            throw IoError(path + ": " + error);
        }
        png_init_io(png, f.get());
        png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
                     PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        png_write_info(png, info);
        for (std::uint32_t y = 0; y < image.height; ++y)
            png_write_row(png, const_cast<png_bytep>(image.at(0, y)));
        png_write_end(png, nullptr);
        png_destroy_write_struct(&png, &info);
        if (std::fflush(f.get()) != 0) throw IoError(path + ": cannot write (" + std::strerror(errno) + ")");
    }
    out.commit();
}

Image readPng(const std::string& path) {
    File f(std::fopen(path.c_str(), "rb"));
    if (!f) throw IoError(path + ": cannot open (" + std::strerror(errno) + ")");
    png_byte signature[8] = {};
    if (std::fread(signature, 1, 8, f.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0)
        throw FormatError(path + ": not a PNG file");
    std::string error;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, pngError, pngWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
        png_destroy_read_struct(&png, nullptr, nullptr);
        throw OutOfMemory("libpng: cannot allocate");
    }
    Image image;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw FormatError(path + ": " + error);
    }
    png_init_io(png, f.get());
    png_set_sig_bytes(png, 8);
    png_read_info(png, info);
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
    png_read_update_info(png, info);
    const std::uint32_t w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    image = Image(w, h);
    for (std::uint32_t y = 0; y < h; ++y) png_read_row(png, image.at(0, y), nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return image;
}

} // namespace vds::eval
