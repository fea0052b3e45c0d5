#include "evaluation/core/png_image.hpp"

#include <png.h>

#include <csetjmp>
#include <cstdio>

#include "common/core/io_error.hpp"

namespace ltm::eval {

namespace {

struct Sink {
    std::string bytes;
    char error[200] = "";
};

void append(png_structp png, png_bytep data, png_size_t n) {
    static_cast<Sink*>(png_get_io_ptr(png))->bytes.append(reinterpret_cast<const char*>(data), n);
}

void flush(png_structp) {}

// libpng is C: its errors return through longjmp to encode_png, never by a C++ exception.
void fail(png_structp png, png_const_charp message) {
    auto* sink = static_cast<Sink*>(png_get_error_ptr(png));
    std::snprintf(sink->error, sizeof sink->error, "%s", message);
    png_longjmp(png, 1);
}

void warn(png_structp, png_const_charp) {}

}  // namespace

std::string encode_png(const RgbImage& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3) {
        throw common::IoError("PNG", "empty or inconsistent image");
    }
    Sink sink;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, fail, warn);
    if (png == nullptr) throw common::IoError("PNG", "out of memory");
    png_infop info = png_create_info_struct(png);
    if (info == nullptr || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        throw common::IoError("PNG", std::string("encoding failed: ") + sink.error);
    }
    png_set_write_fn(png, &sink, append, flush);
    png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < image.height; ++y) {
        png_write_row(png, &const_cast<std::uint8_t&>(
                               image.rgb[static_cast<std::size_t>(y) * image.width * 3]));
    }
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return std::move(sink.bytes);
}

}  // namespace ltm::eval
