#pragma once
// Measures a method's errors on a mesh against the independent polyhedral oracle (tests/oracles), over a set
// of poses and water levels: the accuracy goals are checked with it, and the numbers it prints are
// the ones quoted in closing notes.

#include <BulletBuoyancy/integrals/BuoyancyMethod.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <string>
#include <vector>

namespace buoyancy_test {

/// Worst errors of one method on one mesh.
struct AccuracyReport {
    std::string method;           ///< method actually used
    int texture = 0;              ///< N (0 for exact-mesh)
    std::size_t samples = 0;      ///< surface samples (0 for exact-mesh)
    bool generated_uvs = false;   ///< true when the atlas was generated
    double dry_volume_pct = 0;    ///< |V − V_exact| / V_exact, %
    double centre_pct_diag = 0;   ///< |c − c_exact| / bbox diagonal, %
    double inertia_pct = 0;       ///< ‖I − I_exact‖_F / ‖I_exact‖_F, %
    double sub_volume_pct = 0;    ///< max over poses |V_sub − exact| / V_exact, %
    double cob_pct_diag = 0;      ///< max over poses with > 1 % submerged |C_B − exact| / diagonal, %
    int poses = 0;                ///< poses evaluated
};

/// Evaluate `method` (texture N, 0 = the method's default) on `mesh` at `depthCount` water levels spread over
/// the body's height for each of several tilts (0°, 23° about x, 41° about an oblique axis, 90° about z).
AccuracyReport measureAccuracy(const buoyancy::TriangleMesh& mesh, buoyancy::BuoyancyMethod method, int texture,
                               int depthCount = 9);

/// When the environment variable BUOYANCY_ACCURACY_REPORT names a file, append one Markdown table row
/// "| mesh | triangles | label | method | N | samples | UVs | dry V % | centre % | inertia % | sub V % | CoB % |" to it
/// (docs/accuracy.md is made this way: see scripts/accuracy-report.sh).
void recordAccuracyRow(const std::string& mesh, std::size_t triangles, const std::string& label,
                       const AccuracyReport& r);

/// One line for logs: "exact-coverage 128² (9304 samples): dry V 0.0012 %, ...".
std::string describe(const AccuracyReport& r);

}  // namespace buoyancy_test
