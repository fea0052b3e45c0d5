#include "evaluation/core/png_image.hpp"

#include <gtest/gtest.h>
#include <png.h>

#include "common/core/io_error.hpp"

namespace ltm::eval {
namespace {

TEST(PngImage, EncodesWhatLibpngReadsBack) {
    RgbImage image;
    image.fill(7, 5, {255, 255, 255});
    image.set(2, 3, {10, 20, 30});
    image.set(6, 4, {200, 0, 100});
    const std::string bytes = encode_png(image);
    ASSERT_GT(bytes.size(), 8u);
    EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));

    png_image read{};
    read.version = PNG_IMAGE_VERSION;
    ASSERT_TRUE(png_image_begin_read_from_memory(&read, bytes.data(), bytes.size()));
    read.format = PNG_FORMAT_RGB;
    std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(read));
    ASSERT_TRUE(png_image_finish_read(&read, nullptr, pixels.data(), 0, nullptr));
    ASSERT_EQ(read.width, 7u);
    ASSERT_EQ(read.height, 5u);
    EXPECT_EQ(pixels[(3 * 7 + 2) * 3 + 0], 10);
    EXPECT_EQ(pixels[(3 * 7 + 2) * 3 + 2], 30);
    EXPECT_EQ(pixels[(4 * 7 + 6) * 3 + 0], 200);
    EXPECT_EQ(pixels[0], 255);
}

TEST(PngImage, RefusesAnEmptyImage) { EXPECT_THROW(encode_png(RgbImage{}), common::IoError); }

}  // namespace
}  // namespace ltm::eval
