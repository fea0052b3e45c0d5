#pragma once
// A top view (x-y) of point clouds and paths as an RGB raster: the map in grey by how many points
// fall in a pixel, changes and paths drawn over it in their colours. Encoding is png_image's.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace ltm::eval {

using Rgb = std::array<std::uint8_t, 3>;

struct RgbImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;  // row-major, top row first, 3 bytes a pixel
    void fill(int w, int h, Rgb colour);
    void set(int x, int y, Rgb colour);  // ignored outside the image
    Rgb at(int x, int y) const;
};

struct TopViewLayer {
    std::string label;
    std::vector<Eigen::Vector3f> points;
    std::vector<Rgb> colours;  // one a point, or empty: `colour`, darker where points pile up
    Rgb colour = {60, 60, 60};
};

struct TopViewPath {
    std::string label;
    std::vector<Eigen::Vector3d> positions;
    Rgb colour = {31, 119, 180};
};

struct TopView {
    RgbImage image;
    double metres_per_pixel = 0.0;
    Eigen::Vector2d min_xy = Eigen::Vector2d::Zero();  // world x-y of the image's left bottom
    std::size_t points_drawn = 0;
};

// Fits everything (non-finite points left out) into at most `max_size` pixels on the long side,
// with a margin; an empty input gives an empty image.
TopView render_top_view(const std::vector<TopViewLayer>& layers,
                        const std::vector<TopViewPath>& paths, int max_size = 1200);

}  // namespace ltm::eval
