#pragma once
/// @file SurfaceSamples.h
/// The runtime form of the paper's position texture (PT) and area-vector texture (AVT): only covered
/// texels, as a structure of arrays (design.md 1). Every integral of the library is a sum over these.

#include <cstdint>
#include <string>
#include <vector>

namespace buoyancy {

/// How texels were turned into samples (design.md 1.1).
enum class BakeMethod {
    TexelCentre,   ///< the paper's method: a texel belongs to the triangle containing its centre in UV space
    ExactCoverage, ///< each triangle's UV polygon clipped against each texel square; Σ A_i = 0 exactly
};

/// Surface samples of one mesh at one texture size, body frame, double precision.
/// Sample i stands for the surface piece(s) covered by one texel: p_i is the area-weighted centroid of
/// those pieces (m), A_i = Σ area × outward unit normal of the pieces (m²).
struct SurfaceSamples {
    int texture_size = 0;              ///< N of the N×N texture the samples were baked at
    BakeMethod method = BakeMethod::ExactCoverage;
    std::vector<double> px, py, pz;    ///< #S sample positions, m (body frame)
    std::vector<double> ax, ay, az;    ///< #S area vectors A_i, m² (outward)
    std::vector<double> area;          ///< #S unsigned surface area Σ|piece| of the sample, m² (≥ |A_i|)
    std::vector<std::uint32_t> texel;  ///< #S texel index y·N + x the sample was baked from
    std::vector<std::uint32_t> triangle; ///< #S triangle holding the largest piece (for attribute lookups)

    /// Number of samples.
    std::size_t size() const { return px.size(); }
    /// Reserve room for n samples in every array.
    void reserve(std::size_t n);
    /// Append one sample.
    void push(double x, double y, double z, double Ax, double Ay, double Az, double a,
              std::uint32_t texelIndex, std::uint32_t triangleIndex);
};

/// Name used on the command line and in JSON: "texel-centre" or "exact-coverage".
const char* bakeMethodName(BakeMethod method);

}  // namespace buoyancy
