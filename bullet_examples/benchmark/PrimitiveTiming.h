#pragma once
/// @file PrimitiveTiming.h
/// One flat-water evaluation of a Bullet primitive's hydrostatics, the way a body of that shape gets it: the closed
/// form where the library has one (btSphereShape: the cap; btBoxShape: the exact clip; btCapsuleShape: exact slices) and the mesh path its
/// tessellation would take (btCapsuleShape, and the sphere and box for comparison). Poses with random attitudes and
/// centre depths within the shape's size; thread CPU time; volume error against the exact solid.

#include <iosfwd>
#include <string>
#include <vector>

namespace buoyancy::bench {

/// One row of primitives.csv.
struct PrimitiveRow {
    std::string shape;      ///< "box 1.0x0.4x0.8", "sphere r0.5", "capsule r0.3 h1.0"
    std::string path;       ///< "closed form", "exact slices" (btCapsuleShape) or "mesh"
    int triangles = 0;      ///< triangles of the mesh path (0 for a closed form)
    double nsPerEvaluation = 0;    ///< mean thread CPU time of one evaluation, ns
    double maxVolumeErrorPct = 0;  ///< largest |V − V_exact| over the poses, % of the solid's volume
};

/// Time every row (`quick`: fewer repetitions).
std::vector<PrimitiveRow> runPrimitiveTiming(bool quick, std::ostream& log);

/// Write primitives.csv: shape,path,triangles,ns_per_evaluation,max_volume_error_pct.
void writePrimitiveCsv(const std::string& path, const std::vector<PrimitiveRow>& rows);

/// Markdown section for summary.md (with the reference figures the comparison is made against).
std::string primitiveMarkdown(const std::vector<PrimitiveRow>& rows);

}  // namespace buoyancy::bench
