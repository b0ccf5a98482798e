#pragma once
/// @file WaterPatch.h
/// Fewer wave queries per body (design.md 2.5, 2.8): instead of asking the water surface for the height
/// under every vertex or sample (a Gerstner query is a Newton inversion, ≈ 0.3–0.6 µs), ask it once per node
/// of a small M×M grid over the body's footprint and interpolate (Catmull-Rom bicubic: exact for quadratics,
/// error O(h³) for smooth waves). The grid is anchored to a world lattice of spacing h, so a drifting body
/// queries the same world points substep after substep (the surface's warm-start cache stays valid).
/// The error this adds is measured against exact per-point queries in tests/integrals and docs/benchmarks.

#include <cstddef>
#include <cstdint>
#include <vector>

class btWaterSurface;
struct btWaterQueryCache;

namespace buoyancy {

/// A per-body grid of water heights (one per body; not shared between threads: the queries fill a per-cell cache).
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

    /// Where build() puts the nodes of a footprint: node (0, 0) at world (x0, z0), spacing h, m.
    struct Lattice {
        double x0 = 0, z0 = 0, h = 0;
        bool operator==(const Lattice& o) const { return x0 == o.x0 && z0 == o.z0 && h == o.h; }
    };
    /// The lattice build() uses for this footprint (same arguments and the same checks).
    static Lattice lattice(double cx, double cz, double r, int nodes);
    /// The M×M node positions of a lattice, row by row (x fastest), into qx, qz (resized).
    static void nodePositions(const Lattice& l, int nodes, std::vector<double>& qx, std::vector<double>& qz);
    /// build() with the nodes' heights already queried (#nodes², row by row, at nodePositions(lattice(...))): the
    /// same patch build() makes from those heights.
    void buildFromHeights(double cx, double cz, double r, int nodes, const double* heights);

    /// Interpolated height at world (x, z), m. Points outside the footprint are clamped to its border cells.
    double height(double x, double z) const;
    /// Batch form of height().
    void heights(const double* x, const double* z, std::size_t n, double* outHeight) const;

    /// The interpolant's cells, for evaluating it in batches outside this class (VertexPassKernels.h). World (x, z)
    /// maps to the grid as u = (x − x0)·invH, v = (z − z0)·invH, clamped to [1, nodes − 2]; cell (i, j) = (⌊u⌋, ⌊v⌋),
    /// each at most nodes − 3, holds 16 power-basis coefficients C[4p + q] of tu^p tv^q (tu = u − i, tv = v − j) at
    /// coefficients + 16 ((j − 1)(nodes − 3) + i − 1).
    struct CellGrid {
        double x0 = 0, z0 = 0;  ///< world position of node (0, 0), m
        double invH = 1;        ///< 1 / spacing, 1/m
        int nodes = 0;          ///< nodes per side M
        const double* coefficients = nullptr;  ///< 16 per cell, row by row; valid until the next build()
    };
    /// Every cell's coefficients computed (once per build), and where they are.
    CellGrid cellGrid() const;

    /// Second-order Taylor data of the interpolant at world (x, z) (clamped like height()): value f (m), gradient
    /// (fx, fz) and second derivatives (fxx, fxz, fzz, 1/m). Used by the exact-mesh moment tree (design.md 2.5).
    void taylor(double x, double z, double& f, double& fx, double& fz, double& fxx, double& fxz, double& fzz) const;
    /// Scale of the interpolant's curvature (≈ the largest spectral norm of its Hessian), 1/m: 1.25 × (largest axial +
    /// largest mixed second difference of the nodes) / h². Used to classify moment-tree nodes (design.md 2.5) as
    /// |f(p + δ) − f(p) − ∇f(p)·δ| ≲ ½ curvatureBound() |δ|²; not a strict bound (see WaterPatch.cpp).
    double curvatureBound() const { return m_curvature; }
    /// Scale of the interpolant's third derivatives, 1/m²: 1.25 × the largest of |Δxxx| + 3|Δxxz| + 3|Δxzz| + |Δzzz| (third
    /// differences of the nodes) over h³, so that the second-order expansion about p misses f(p + δ) by
    /// ≲ thirdDerivativeBound() |δ|³ / 6 (the moment tree's node criterion, design.md 2.5). Not a strict bound either.
    double thirdDerivativeBound() const { return m_third; }

    /// Scale of the interpolant's slope |∇f| over the patch, dimensionless: the largest node differences along x and
    /// along z over h, combined as a gradient, plus ½ curvatureBound() h. Used by the temporal level of detail to
    /// weigh a horizontal drift of the body (HydrostaticsHistory::poseDeviation); not a strict bound.
    double slopeBound() const { return m_slope; }

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
    /// The cell holding world (x, z) (clamped to the border cells), its local coordinates tu, tv ∈ [0, 1], and its 16
    /// power-basis coefficients C[4p + q] of tu^p tv^q, computed on first use after build().
    const double* cell(double x, double z, double& tu, double& tv) const;
    /// Compute cell c's (column i, row j, 1-based node indices) 16 coefficients and stamp it.
    void computeCell(std::size_t c, int i, int j) const;
    /// Compute every cell not yet computed since the last build.
    void computeAllCells() const;

    int m_m = 0;
    double m_x0 = 0, m_z0 = 0, m_h = 1, m_invH = 1;
    double m_min = 0, m_max = 0;
    double m_curvature = 0;
    double m_third = 0;
    double m_slope = 0;
    bool m_finite = true;
    /// The rest of build() once the lattice and the node heights m_f are in place.
    void finishBuild(const Lattice& l, int nodes);
    std::vector<double> m_qx, m_qz, m_f;
    mutable std::vector<double> m_coef;             ///< 16 coefficients per cell (cell())
    mutable std::vector<std::uint32_t> m_cellStamp; ///< build epoch each cell's coefficients belong to
    std::uint32_t m_epoch = 0;                      ///< incremented by build()
    mutable std::uint32_t m_allCellsEpoch = 0;      ///< the build epoch whose cells computeAllCells() has all computed
};

}  // namespace buoyancy
