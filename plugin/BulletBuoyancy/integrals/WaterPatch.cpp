/// @file WaterPatch.cpp
/// Per-body grid of water heights with Catmull-Rom interpolation (declared in WaterPatch.h).

#include <BulletBuoyancy/integrals/WaterPatch.h>

#include <BulletBuoyancy/integrals/VertexPassKernels.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace buoyancy {

WaterPatch::Lattice WaterPatch::lattice(double cx, double cz, double r, int nodes) {
    if (nodes < 5 || nodes > 64)
        throw std::invalid_argument("WaterPatch: nodes must be in 5..64 (got " + std::to_string(nodes) + ")");
    if (!std::isfinite(cx) || !std::isfinite(cz) || !std::isfinite(r) || !(r > 0))
        throw std::invalid_argument("WaterPatch: non-finite footprint or radius <= 0");
    Lattice l;
    l.h = 2.0 * r / double(nodes - 4);
    const double invH = 1.0 / l.h;
    // Anchor node 1 on the world lattice k·h at or below cx − r: the same body drifting keeps its nodes.
    l.x0 = (std::floor((cx - r) * invH) - 1.0) * l.h;
    l.z0 = (std::floor((cz - r) * invH) - 1.0) * l.h;
    return l;
}

void WaterPatch::nodePositions(const Lattice& l, int nodes, std::vector<double>& qx, std::vector<double>& qz) {
    const std::size_t n = std::size_t(nodes) * std::size_t(nodes);
    qx.resize(n);
    qz.resize(n);
    for (int j = 0; j < nodes; ++j)
        for (int i = 0; i < nodes; ++i) {
            qx[std::size_t(j) * nodes + i] = l.x0 + i * l.h;
            qz[std::size_t(j) * nodes + i] = l.z0 + j * l.h;
        }
}

void WaterPatch::build(const btWaterSurface& water, double cx, double cz, double r, double time, int nodes,
                       btWaterQueryCache& cache) {
    const Lattice l = lattice(cx, cz, r, nodes);
    nodePositions(l, nodes, m_qx, m_qz);
    m_f.resize(m_qx.size());
    water.heightsCached(m_qx.data(), m_qz.data(), m_qx.size(), time, m_f.data(), cache);
    finishBuild(l, nodes);
}

void WaterPatch::buildFromHeights(double cx, double cz, double r, int nodes, const double* heights) {
    const Lattice l = lattice(cx, cz, r, nodes);
    m_f.assign(heights, heights + std::size_t(nodes) * std::size_t(nodes));
    finishBuild(l, nodes);
}

void WaterPatch::finishBuild(const Lattice& l, int nodes) {
    m_m = nodes;
    m_h = l.h;
    m_invH = 1.0 / m_h;
    m_x0 = l.x0;
    m_z0 = l.z0;
    // Per-cell polynomial coefficients are computed on first use after this build (cell()).
    const std::size_t cells = std::size_t(nodes - 3) * std::size_t(nodes - 3);
    if (m_cellStamp.size() != cells) {
        m_cellStamp.assign(cells, 0);
        m_coef.resize(16 * cells);
        m_epoch = 0;
    }
    m_allCellsEpoch = 0;  // (epochs start at 1) none of the new build's cells computed yet
    if (++m_epoch == 0) {
        std::fill(m_cellStamp.begin(), m_cellStamp.end(), 0u);
        m_epoch = 1;
    }
    m_min = m_f[0];
    m_max = m_f[0];
    m_finite = true;
    for (double f : m_f) {
        if (!std::isfinite(f)) m_finite = false;
        m_min = std::min(m_min, f);
        m_max = std::max(m_max, f);
    }
    // Curvature scale (see curvatureBound): the largest second difference of the nodes along x, along z, and mixed,
    // over h². The interpolant's own second derivative is a combination of these (weights up to 3.75 in the worst
    // case, near 1 for smooth waves: Catmull-Rom reproduces quadratics); 1.25 × the sum is used. Not a strict bound:
    // a node of the moment tree misclassified by it contributes an error of second order in the sliver it gets wrong.
    // Slope scale (see slopeBound): the largest first difference of the nodes along x and along z over h (the mean
    // slope over a cell edge), as a gradient's length, plus half a cell of the curvature scale (how far the slope
    // moves within the cell). Both scales row by row, each difference over exactly the nodes it exists for.
    double dxx = 0, dzz = 0, dxz = 0, dx = 0, dz = 0;
    const auto F = [&](int i, int j) { return m_f[std::size_t(j) * nodes + i]; };
    for (int j = 0; j < nodes; ++j) {
        const double* row = m_f.data() + std::size_t(j) * nodes;
        for (int i = 1; i + 1 < nodes; ++i) dxx = std::max(dxx, std::abs(row[i - 1] - 2 * row[i] + row[i + 1]));
        for (int i = 0; i + 1 < nodes; ++i) dx = std::max(dx, std::abs(row[i + 1] - row[i]));
        if (j + 1 == nodes) continue;
        const double* next = row + nodes;
        for (int i = 0; i < nodes; ++i) dz = std::max(dz, std::abs(next[i] - row[i]));
        for (int i = 0; i + 1 < nodes; ++i) dxz = std::max(dxz, std::abs(next[i + 1] - row[i + 1] - next[i] + row[i]));
        if (j == 0) continue;
        const double* prev = row - nodes;
        for (int i = 0; i < nodes; ++i) dzz = std::max(dzz, std::abs(prev[i] - 2 * row[i] + next[i]));
    }
    m_curvature = 1.25 * (std::max(dxx, dzz) + dxz) * m_invH * m_invH;
    if (!std::isfinite(m_curvature)) m_finite = false;
    m_slope = std::hypot(dx, dz) * m_invH + 0.5 * m_curvature * m_h;
    if (!std::isfinite(m_slope)) m_finite = false;
    // Third-derivative scale (see thirdDerivativeBound): per 4×4 block of nodes, the third differences along x, z and
    // the two mixed ones (Δxxz over the block's first two z rows, Δxzz its first two x columns), combined as the
    // worst direction's D³f[d,d,d] ≤ |f_xxx| + 3|f_xxz| + 3|f_xzz| + |f_zzz|.
    double third = 0;
    for (int j = 0; j + 3 < nodes; ++j)
        for (int i = 0; i + 3 < nodes; ++i) {
            const double xxx = std::abs(F(i + 3, j) - 3 * F(i + 2, j) + 3 * F(i + 1, j) - F(i, j));
            const double zzz = std::abs(F(i, j + 3) - 3 * F(i, j + 2) + 3 * F(i, j + 1) - F(i, j));
            const double xxz = std::abs((F(i + 2, j + 1) - 2 * F(i + 1, j + 1) + F(i, j + 1)) -
                                        (F(i + 2, j) - 2 * F(i + 1, j) + F(i, j)));
            const double xzz = std::abs((F(i + 1, j + 2) - 2 * F(i + 1, j + 1) + F(i + 1, j)) -
                                        (F(i, j + 2) - 2 * F(i, j + 1) + F(i, j)));
            third = std::max(third, xxx + 3 * xxz + 3 * xzz + zzz);
        }
    m_third = 1.25 * third * m_invH * m_invH * m_invH;
    if (!std::isfinite(m_third)) m_finite = false;
}


void WaterPatch::computeCell(std::size_t c, int i, int j) const {
    // Power-basis coefficients of the cell's bicubic: C = M F Mᵀ, F the 4×4 nodes around it (a along x, b along z),
    // M the Catmull-Rom basis (w_a(t) = Σ_p M[p][a] tᵖ): f = Σ_pq C[p][q] tu^p tv^q, with
    //   M = [[0, 1, 0, 0], [−½, 0, ½, 0], [1, −5/2, 2, −½], [−½, 3/2, −3/2, ½]].
    // Each row of M applied to four values v0..v3 (catmullRomRow), its zero terms left out and its unit factors not
    // multiplied: the sums of the full product M v in the same order, so the same values (up to the sign of a zero).
    const auto catmullRomRow = [](double v0, double v1, double v2, double v3, double out[4]) {
        out[0] = v1;
        out[1] = v0 * -0.5 + v2 * 0.5;
        out[2] = ((v0 + v1 * -2.5) + v2 * 2.0) + v3 * -0.5;
        out[3] = ((v0 * -0.5 + v1 * 1.5) + v2 * -1.5) + v3 * 0.5;
    };
    double* C = m_coef.data() + 16 * c;
    const double* F = m_f.data() + std::size_t(j - 1) * m_m + (i - 1);  // F[b * M + a]
    double FM[4][4];  // FM[a][q] = Σ_b F[a][b] M[q][b]
    for (int a = 0; a < 4; ++a) catmullRomRow(F[a], F[m_m + a], F[2 * m_m + a], F[3 * m_m + a], FM[a]);
    for (int q = 0; q < 4; ++q) {  // C[p][q] = Σ_a M[p][a] FM[a][q]
        double column[4];
        catmullRomRow(FM[0][q], FM[1][q], FM[2][q], FM[3][q], column);
        for (int p = 0; p < 4; ++p) C[4 * p + q] = column[p];
    }
    m_cellStamp[c] = m_epoch;
}

void WaterPatch::computeAllCells() const {
    if (m_allCellsEpoch == m_epoch) return;
    const int cellsPerRow = m_m - 3;
    for (int j = 1; j <= cellsPerRow; ++j)
        for (int i = 1; i <= cellsPerRow; ++i) {
            const std::size_t c = std::size_t(j - 1) * std::size_t(cellsPerRow) + std::size_t(i - 1);
            if (m_cellStamp[c] != m_epoch) computeCell(c, i, j);
        }
    m_allCellsEpoch = m_epoch;
}

WaterPatch::CellGrid WaterPatch::cellGrid() const {
    computeAllCells();
    CellGrid g;
    g.x0 = m_x0;
    g.z0 = m_z0;
    g.invH = m_invH;
    g.nodes = m_m;
    g.coefficients = m_coef.data();
    return g;
}

const double* WaterPatch::cell(double x, double z, double& tu, double& tv) const {
    const double u = (x - m_x0) * m_invH, v = (z - m_z0) * m_invH;
    // Cells 1..M−3 have both neighbours; clamp outside points to the border cells.
    const double lo = 1.0, hi = double(m_m - 2);
    const double uc = std::min(std::max(u, lo), hi), vc = std::min(std::max(v, lo), hi);
    const int i = std::min(int(uc), m_m - 3), j = std::min(int(vc), m_m - 3);
    tu = uc - i;
    tv = vc - j;
    const std::size_t c = std::size_t(j - 1) * std::size_t(m_m - 3) + std::size_t(i - 1);
    if (m_cellStamp[c] != m_epoch) computeCell(c, i, j);
    return m_coef.data() + 16 * c;
}

void WaterPatch::taylor(double x, double z, double& f, double& fx, double& fz, double& fxx, double& fxz,
                        double& fzz) const {
    double tu, tv;
    const double* C = cell(x, z, tu, tv);
    // a_q(tu) = Σ_p C[p][q] tu^p and its first two derivatives, then the same in tv.
    double a0[4], a1[4], a2[4];
    for (int q = 0; q < 4; ++q) {
        const double c0 = C[q], c1 = C[4 + q], c2 = C[8 + q], c3 = C[12 + q];
        a0[q] = ((c3 * tu + c2) * tu + c1) * tu + c0;
        a1[q] = (3.0 * c3 * tu + 2.0 * c2) * tu + c1;
        a2[q] = 6.0 * c3 * tu + 2.0 * c2;
    }
    f = ((a0[3] * tv + a0[2]) * tv + a0[1]) * tv + a0[0];
    fz = ((3.0 * a0[3] * tv + 2.0 * a0[2]) * tv + a0[1]) * m_invH;
    fzz = (6.0 * a0[3] * tv + 2.0 * a0[2]) * m_invH * m_invH;
    fx = (((a1[3] * tv + a1[2]) * tv + a1[1]) * tv + a1[0]) * m_invH;
    fxz = ((3.0 * a1[3] * tv + 2.0 * a1[2]) * tv + a1[1]) * m_invH * m_invH;
    fxx = (((a2[3] * tv + a2[2]) * tv + a2[1]) * tv + a2[0]) * m_invH * m_invH;
}

double WaterPatch::height(double x, double z) const {
    double tu, tv;
    const double* C = cell(x, z, tu, tv);
    double a[4];
    for (int q = 0; q < 4; ++q) a[q] = ((C[12 + q] * tu + C[8 + q]) * tu + C[4 + q]) * tu + C[q];
    return ((a[3] * tv + a[2]) * tv + a[1]) * tv + a[0];
}

void WaterPatch::heights(const double* x, const double* z, std::size_t n, double* outHeight) const {
    // Many points: every cell's coefficients first (a body's vertices cover most of its patch), then several points per
    // instruction (VertexPassKernels.h); few: cell by cell as asked.
    const std::size_t cellsPerRow = std::size_t(m_m - 3);
    if (n >= cellsPerRow * cellsPerRow) {
        interpolatePatchHeights(cellGrid(), x, z, n, outHeight);
        return;
    }
    for (std::size_t k = 0; k < n; ++k) outHeight[k] = height(x[k], z[k]);
}

}  // namespace buoyancy
