#pragma once
/// @file FrameLabel.h
/// A text label stamped into an RGBA picture with a small built-in 5×7 bitmap font (no font library): the
/// "t = 2.5 s" of every `buoyancy run --png` frame, so that a strip of frames says when each was taken.

#include <cstdint>
#include <string>
#include <vector>

namespace buoyancy::render {

/// Where and how a label is drawn: light text on a dark box in the picture's top-left corner.
struct LabelStyle {
    int left = 6;             ///< box's left edge, pixels from the picture's left
    int top = 6;              ///< box's top edge, pixels from the picture's top
    int scale = 2;            ///< pixels per font dot (1: 5×7-pixel glyphs)
    int padding = 4;          ///< box margin around the text, pixels
    std::uint8_t text[3] = {255, 255, 255}; ///< text colour, sRGB 0..255
    std::uint8_t box[3] = {20, 24, 32};     ///< box colour, sRGB 0..255
};

/// A label's box, pixels (top-left origin).
struct LabelBox {
    int left = 0, top = 0, width = 0, height = 0;
};

/// The box `text` takes in `style` (the characters the font lacks take a blank cell).
LabelBox labelBox(const std::string& text, const LabelStyle& style = {});

/// Draw `text` into `rgba` (width × height pixels, 4 bytes a pixel, rows top first), clipped to the picture.
/// The font has the digits, `t s m . , = - + : ( )` and the space; other characters are left blank.
/// @return the box drawn (before clipping)
LabelBox stampLabel(std::vector<std::uint8_t>& rgba, int width, int height, const std::string& text,
                    const LabelStyle& style = {});

/// "t = 2.5 s": the time rounded to 0.01 s, trailing zeros dropped, at least one decimal.
std::string timeLabel(double seconds);

}  // namespace buoyancy::render
