#pragma once
/// @file PermeabilityTexture.h
/// The paper's permeability texture (section 4.2, design.md 4) as an image file: the red channel / 255
/// of each texel is the open-area fraction (0 sealed … 1 fully open) of the surface it covers.
///
/// Where a surface sample looks: each sample's UV is the barycentric interpolation of its triangle's corner
/// UVs at the sample position (the closest point of that triangle), which works for every buoyancy method
/// (texture-baked samples and the per-face samples of ExactMesh alike). The lookup is bilinear between texel
/// centres with wrap-around (GL_REPEAT), or nearest texel. Image row 0 (the top) is v = 1 and the bottom row
/// is v = 0 (the OBJ / Blender convention assimp keeps: we import without flipping UVs).
///
/// Which UVs: the model's own UVs whenever every triangle has finite ones (overlapping or mirrored UVs are
/// fine here: both sides get the same paint). A model with no UVs (or non-finite ones) gets the atlas the
/// library generates (generateAtlas) at a texture size equal to the image's larger side N; export that atlas
/// (permeabilityUvs(mesh, N), then writeAtlasObj for the mesh with those UVs and writeAtlasTemplatePng for a
/// template image) and paint the texture on it.
///
/// Images are decoded with stb_image (libstb-dev, public domain / MIT): PNG, JPEG, BMP, TGA.

#include <BulletBuoyancy/bake/SurfaceSamples.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace buoyancy {

/// How a permeability texture is looked up.
enum class TextureFilter {
    Bilinear, ///< bilinear between the four nearest texel centres, wrapping at the edges (default)
    Nearest,  ///< the texel containing the UV (wrapping)
};

/// The red channel of an image as open-area fractions in [0, 1].
struct PermeabilityImage {
    int width = 0;            ///< texels along u
    int height = 0;           ///< texels along v
    std::vector<float> value; ///< width·height, row-major from the top row (v = 1) down; red / 255
    /// Value at (u, v) (any real numbers; wraps). Non-finite u or v give 0.
    double sample(double u, double v, TextureFilter filter = TextureFilter::Bilinear) const;
};

/// Largest side accepted, texels (a 16384² image already takes 1 GiB as RGBA).
constexpr int kMaxPermeabilityImageSide = 16384;

/// Decode an image held in memory. `name` prefixes every message.
/// @throws std::invalid_argument: "NAME: the file is empty (0 bytes)", "NAME: not an image stb_image can read (…)",
///         "NAME: the image has zero size (W×H)", "NAME: 1 channel (grey); a permeability texture needs RGB or
///         RGBA (its red channel is the open-area fraction)", "NAME: W×H texels, larger than 16384 per side"
PermeabilityImage decodePermeabilityImage(const unsigned char* data, std::size_t size, const std::string& name);

/// Read and decode an image file. @throws std::invalid_argument "PATH: cannot read the file" or as decodePermeabilityImage
PermeabilityImage loadPermeabilityImage(const std::string& path);

/// The UVs a permeability texture is painted in (see the file comment).
struct PermeabilityUvs {
    std::vector<Eigen::Vector2d> corner_uvs; ///< 3·#T
    bool generated = false;                  ///< true: the library's atlas (the model had no usable UVs)
};

/// The model's finite UVs, or the atlas generated for a texture of atlasSize² texels.
/// @throws std::runtime_error when the generated atlas does not fit at atlasSize (says the size that fits)
PermeabilityUvs permeabilityUvs(const TriangleMesh& mesh, int atlasSize);

/// UV of each surface sample: barycentric interpolation of its triangle's corner UVs at the point of the
/// triangle closest to the sample. @throws std::invalid_argument when a sample's triangle index is out of range
/// or the UV array does not have 3·#T entries
std::vector<Eigen::Vector2d> surfaceSampleUvs(const SurfaceSamples& samples, const TriangleMesh& mesh,
                                              const std::vector<Eigen::Vector2d>& cornerUvs);

/// Permeability of each sample from the image (values in [0, 1]).
std::vector<double> permeabilityFromImage(const std::vector<Eigen::Vector2d>& sampleUvs, const PermeabilityImage& image,
                                          TextureFilter filter = TextureFilter::Bilinear);

/// Write the mesh with the given corner UVs as a Wavefront OBJ (v, vt, f v/vt), for painting in any tool.
/// @throws std::runtime_error when the file cannot be written
void writeAtlasObj(const TriangleMesh& mesh, const std::vector<Eigen::Vector2d>& cornerUvs, const std::string& path);

/// Write a size×size RGB PNG template of the UV layout: covered texels dark green (red 0: sealed), the rest
/// black, so painting red on it makes holes. @throws std::runtime_error when the file cannot be written
void writeAtlasTemplatePng(const std::vector<Eigen::Vector2d>& cornerUvs, int size, const std::string& path);

}  // namespace buoyancy
