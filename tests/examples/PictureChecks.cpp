#include "PictureChecks.h"

#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace buoyancy::test {

bool analysePicture(const std::string& path, PictureStats& out, int xFrom) {
    int w = 0, h = 0, n = 0;
    unsigned char* p = stbi_load(path.c_str(), &w, &h, &n, 3);
    if (!p) return false;
    out = PictureStats{};
    out.width = w;
    out.height = h;
    std::set<int> colours;
    long lower = 0, water = 0;
    for (int y = 0; y < h; ++y)
        for (int x = xFrom; x < w; ++x) {
            const unsigned char* c = p + 3 * (std::size_t(y) * w + x);
            const int r = c[0], g = c[1], b = c[2];
            colours.insert((r >> 5) << 6 | (g >> 5) << 3 | (b >> 5));
            if (r > b + 60 && r > 120) ++out.warm;
            if (y >= h / 2) {
                ++lower;
                if (b > r + 40 && b > 90) ++water;
            }
        }
    stbi_image_free(p);
    out.waterLower = lower ? double(water) / double(lower) : 0.0;
    out.distinctColours = int(colours.size());
    return true;
}

bool Picture::load(const std::string& path) {
    int n = 0;
    unsigned char* p = stbi_load(path.c_str(), &width, &height, &n, 3);
    if (!p) return false;
    rgb.assign(p, p + std::size_t(width) * height * 3);
    stbi_image_free(p);
    return true;
}

Eigen::Vector3d Picture::at(int x, int y) const {
    x = std::clamp(x, 0, width - 1);
    y = std::clamp(y, 0, height - 1);
    const std::uint8_t* c = &rgb[3 * (std::size_t(y) * width + x)];
    return {double(c[0]), double(c[1]), double(c[2])};
}

Eigen::Vector3d Picture::meanAround(const Eigen::Vector2d& centre, int radius) const {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    const int cx = int(std::floor(centre.x())), cy = int(std::floor(centre.y()));
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) sum += at(cx + dx, cy + dy);
    return sum / double((2 * radius + 1) * (2 * radius + 1));
}

}  // namespace buoyancy::test
