#pragma once
/// @file Fig9.h
/// The paper's Fig. 9: submerged volume of a sphere of radius 0.5 m against depth, for texture sizes
/// 32²…1024² (texel-centre, the paper's method, and exact-coverage) and the AQUAS-style downward-faces
/// method, with the analytic cap volume π d² (3R − d)/3 and the exact clip of the same mesh.

#include <iosfwd>
#include <string>
#include <vector>

namespace buoyancy::bench {

/// What to run.
struct Fig9Options {
    std::vector<int> textures{32, 64, 128, 256, 512, 1024}; ///< N
    int depths = 41;       ///< depth samples from 0 to 2R
    int segments = 128;    ///< sphere mesh longitude segments
    int rings = 64;        ///< sphere mesh rings
};

/// Write CSV `path` with columns method,texture,depth,volume,analytic_volume,error_pct (error against the
/// analytic volume in % of the analytic sphere volume; depth = how far the lowest point is below the water, m).
void runFig9(const Fig9Options& options, const std::string& path, std::ostream& log);

}  // namespace buoyancy::bench
