#pragma once
/// @file PictureChecks.h
/// Simple pixel expectations for rendered pictures (the offscreen PNGs and the browser's screenshot): water
/// colour in the lower part, body pixels, more than one colour.

#include <string>

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

}  // namespace buoyancy::test
