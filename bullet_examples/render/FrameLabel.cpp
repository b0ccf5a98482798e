#include "render/FrameLabel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace buoyancy::render {

namespace {

constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphSpacing = 1;

/// One 5×7 glyph: seven rows, bit 4 of each row is the leftmost dot.
struct Glyph {
    char c;
    std::uint8_t rows[kGlyphHeight];
};

constexpr Glyph kFont[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'t', {0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06}}, {'s', {0x00, 0x00, 0x0E, 0x10, 0x0E, 0x01, 0x1E}},
    {'m', {0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11}}, {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
    {',', {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}}, {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}}, {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}},
    {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}}, {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
    {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}},
};

const Glyph* glyphOf(char c) {
    for (const Glyph& g : kFont)
        if (g.c == c) return &g;
    return nullptr;  // the space and unknown characters: blank
}

void fill(std::vector<std::uint8_t>& rgba, int width, int height, int x0, int y0, int w, int h, const std::uint8_t c[3]) {
    const int xa = std::max(x0, 0), xb = std::min(x0 + w, width), ya = std::max(y0, 0), yb = std::min(y0 + h, height);
    for (int y = ya; y < yb; ++y)
        for (int x = xa; x < xb; ++x) {
            std::uint8_t* p = &rgba[4 * (std::size_t(y) * width + x)];
            p[0] = c[0];
            p[1] = c[1];
            p[2] = c[2];
            p[3] = 255;
        }
}

}  // namespace

LabelBox labelBox(const std::string& text, const LabelStyle& style) {
    const int s = std::max(style.scale, 1);
    const int n = int(text.size());
    const int textWidth = n > 0 ? (n * (kGlyphWidth + kGlyphSpacing) - kGlyphSpacing) * s : 0;
    return {style.left, style.top, textWidth + 2 * style.padding, kGlyphHeight * s + 2 * style.padding};
}

LabelBox stampLabel(std::vector<std::uint8_t>& rgba, int width, int height, const std::string& text,
                    const LabelStyle& style) {
    const LabelBox box = labelBox(text, style);
    if (width <= 0 || height <= 0 || rgba.size() < 4 * std::size_t(width) * std::size_t(height)) return box;
    fill(rgba, width, height, box.left, box.top, box.width, box.height, style.box);
    const int s = std::max(style.scale, 1);
    int x = box.left + style.padding;
    for (char c : text) {
        if (const Glyph* g = glyphOf(c))
            for (int row = 0; row < kGlyphHeight; ++row)
                for (int col = 0; col < kGlyphWidth; ++col)
                    if (g->rows[row] & (0x10 >> col))
                        fill(rgba, width, height, x + col * s, box.top + style.padding + row * s, s, s, style.text);
        x += (kGlyphWidth + kGlyphSpacing) * s;
    }
    return box;
}

std::string timeLabel(double seconds) {
    const double t = std::round(seconds * 100.0) / 100.0;
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.2f", t == 0.0 ? 0.0 : t);  // no "-0.00"
    std::string s = buf;
    while (s.size() >= 2 && s.back() == '0' && s[s.size() - 2] != '.') s.pop_back();
    return "t = " + s + " s";
}

}  // namespace buoyancy::render
