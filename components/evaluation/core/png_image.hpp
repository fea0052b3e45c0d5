#pragma once
// PNG encoding of an RGB raster with libpng (in a library of its own: only the run report needs
// it).
#include <string>

#include "evaluation/core/top_view_image.hpp"

namespace ltm::eval {

// The PNG file's bytes. Throws common::IoError (one line) on an empty image or a libpng error.
std::string encode_png(const RgbImage& image);

}  // namespace ltm::eval
