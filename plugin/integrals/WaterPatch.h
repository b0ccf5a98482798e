#pragma once
/// @file WaterPatch.h
/// Fewer wave queries per body (DESIGN-NOTES 2.5, 2.8): instead of asking the water surface for the height
/// under every vertex or sample (a Gerstner query is a Newton inversion, ≈ 0.3–0.6 µs), ask it once per node
/// of a small M×M grid over the body's footprint and interpolate (Catmull-Rom bicubic: exact for quadratics,
/// error O(h³) for smooth waves). The grid is anchored to a world lattice of spacing h, so a drifting body
/// queries the same world points substep after substep (the surface's warm-start cache stays valid).
/// The error this adds is measured against exact per-point queries in tests/integrals and docs/benchmarks.

#include <cstddef>
#include <vector>

class btWaterSurface;
struct btWaterQueryCache;

namespace buoyancy {

/// A per-body grid of water heights (one per body; not shared between threads).
class WaterPatch {
public:
    /// Query the surface on an M×M grid of spacing h = 2r/(M − 4) (M = nodes ≥ 5: a 1-node ghost ring for the
    /// bicubic, one cell of slack for the lattice snap) whose interior covers [cx − r, cx + r] × [cz − r, cz + r].
    /// @param water  the surface (one batch call)
    /// @param cx,cz,r  world centre and half side of the footprint, m (r > 0)
    /// @param time   s
    /// @param nodes  M, 5..64
    /// @param cache  warm-start memory for the surface's batch query (btWaterSurface::heightsCached)
    /// @throws std::invalid_argument for nodes out of range or a non-finite footprint
    void build(const btWaterSurface& water, double cx, double cz, double r, double time, int nodes,
               btWaterQueryCache& cache);

    /// Interpolated height at world (x, z), m. Points outside the footprint are clamped to its border cells.
    double height(double x, double z) const;
    /// Batch form of height().
    void heights(const double* x, const double* z, std::size_t n, double* outHeight) const;

    /// Lowest and highest node height (the interpolant may overshoot by a few per cent of the node spread), m.
    double minNode() const { return m_min; }
    /// see minNode
    double maxNode() const { return m_max; }
    /// Grid spacing h, m.
    double spacing() const { return m_h; }
    /// Nodes per side M.
    int nodes() const { return m_m; }
    /// True when every node height was finite.
    bool finite() const { return m_finite; }

private:
    int m_m = 0;
    double m_x0 = 0, m_z0 = 0, m_h = 1, m_invH = 1;
    double m_min = 0, m_max = 0;
    bool m_finite = true;
    std::vector<double> m_qx, m_qz, m_f;
};

}  // namespace buoyancy
