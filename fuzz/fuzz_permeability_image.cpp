/// @file fuzz_permeability_image.cpp
/// libFuzzer target: permeability texture decoding (graph/PermeabilityTexture.h: stb_image in our process,
/// then our red-channel conversion) on arbitrary bytes, then lookups of the decoded image.
/// Contract checked: bad input ends as std::invalid_argument with a message naming the file; an accepted
/// image has 1..16384 texels per side, width·height values, each finite in [0, 1]; lookups at any UV
/// (huge, negative, NaN) by both filters give values in [0, 1].
#include "FuzzContract.h"

#include <BulletBuoyancy/graph/PermeabilityTexture.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

using buoyancy::fuzz::violated;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    buoyancy::PermeabilityImage image;
    try {
        image = buoyancy::decodePermeabilityImage(data, size, "fuzz.png");
    } catch (const std::invalid_argument& e) {
        if (std::string(e.what()).rfind("fuzz.png: ", 0) != 0) violated("error does not name the file");
        return 0;
    }
    if (image.width < 1 || image.height < 1 || image.width > buoyancy::kMaxPermeabilityImageSide ||
        image.height > buoyancy::kMaxPermeabilityImageSide)
        violated("image size outside 1..16384");
    if (image.value.size() != std::size_t(image.width) * std::size_t(image.height)) violated("value count");
    for (float v : image.value)
        if (!(v >= 0.0f && v <= 1.0f)) violated("texel value outside [0, 1]");
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    const std::vector<Eigen::Vector2d> uvs = {{0, 0},     {1, 1},      {0.5, 0.5}, {-0.25, 3.75}, {1e300, -1e300},
                                              {nan, 0.5}, {0.5, inf},  {1e-300, 0.999999999}};
    for (auto filter : {buoyancy::TextureFilter::Bilinear, buoyancy::TextureFilter::Nearest}) {
        for (const auto& uv : uvs) {
            const double v = image.sample(uv.x(), uv.y(), filter);
            if (!(v >= 0.0 && v <= 1.0)) violated("lookup outside [0, 1]");
        }
        for (double v : buoyancy::permeabilityFromImage(uvs, image, filter))
            if (!(v >= 0.0 && v <= 1.0)) violated("permeabilityFromImage outside [0, 1]");
    }
    return 0;
}
