#pragma once
/// @file PngWriter.h
/// Writing pictures as PNG through stb_image_write (Debian libstb-dev).

#include <cstdint>
#include <string>
#include <vector>

namespace buoyancy::render {

/// Write width × height RGBA pixels (top row first) to `path`, alpha dropped. @throws std::runtime_error
void writePng(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgba);

}  // namespace buoyancy::render
