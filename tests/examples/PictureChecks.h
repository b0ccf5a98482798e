#pragma once
/// @file PictureChecks.h
/// Simple pixel expectations for rendered pictures (the offscreen PNGs and the browser's screenshot): water
/// colour in the lower part, body pixels, more than one colour.

#include <Eigen/Core>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace buoyancy::test {

/// What a picture holds, by pixel class.
struct PictureStats {
    int width = 0, height = 0;
    double waterLower = 0;   ///< fraction of the lower half's pixels that are water blue (b > r + 40, b > 90)
    int warm = 0;            ///< pixels of a warm body colour (r > b + 60, r > 120): the palette's first bodies
    int distinctColours = 0; ///< distinct colours after quantising to 3 bits a channel
};

/// Load a PNG and count. @return false when the file cannot be read
bool analysePicture(const std::string& path, PictureStats& out, int xFrom = 0);

/// A loaded picture for measurements at given pixels: colours as 8-bit RGB values (0..255) in doubles.
struct Picture {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb; ///< width × height × 3, rows top first

    /// Read a PNG. @return false when the file cannot be read
    bool load(const std::string& path);
    /// Colour of pixel (x, y), clamped to the picture.
    Eigen::Vector3d at(int x, int y) const;
    /// Mean colour of the (2·radius + 1)² pixels around `centre` (column, row).
    Eigen::Vector3d meanAround(const Eigen::Vector2d& centre, int radius) const;
    /// Pixels of the box (clipped to the picture) whose colour passes `test`.
    template <class Test>
    int countInBox(int left, int top, int boxWidth, int boxHeight, Test test) const {
        int n = 0;
        for (int y = std::max(top, 0); y < std::min(top + boxHeight, height); ++y)
            for (int x = std::max(left, 0); x < std::min(left + boxWidth, width); ++x) n += test(at(x, y)) ? 1 : 0;
        return n;
    }
};

}  // namespace buoyancy::test
