#pragma once
/// @file btInteractiveWaterSurface.h
/// A damped wave-equation height field that floating bodies disturb: the two-way part the paper
/// took from Water Surface Wavelets, in a simple form. The free-surface elevation η over a rectangle of
/// cells obeys ∂²η/∂t² = c² ∇²η − γ ∂η/∂t (linear shallow-water waves of speed c, damping rate γ),
/// integrated with symplectic Euler on a 5-point Laplacian with reflecting (zero-flux) walls: Σ η is
/// conserved exactly by every step.
///
/// Coupling (the seam): when a body's displaced volume grows by dV at (x, z), the water it pushes away
/// is put in a ring of cells outside its footprint (past a two-cell gap) and taken uniformly from the whole
/// grid (the sea around it); the wave equation carries the ring away. btInteractiveWaterCoupler feeds
/// this from every btBuoyancyAction's last result once per substep and steps the grid. The water volume
/// V_w = Σ_cells (η − h)·A_cell is therefore conserved at every step: the water a body displaces is not
/// created or lost, only moved (the level far away is unchanged, as in an open sea).

#include <BulletBuoyancy/water/btWaterSurface.h>

#include <vector>

/// Damped wave-equation water grid, centred at (centreX, centreZ).
class btInteractiveWaterSurface : public btWaterSurface {
public:
    /// @param sizeX,sizeZ  extent of the grid, m, > 0 (outside it the edge value holds)
    /// @param resolution   cells along x, 4..4096 (cells along z: round(sizeZ / dx), ≥ 4; dx = sizeX/resolution)
    /// @param waveSpeed    c, m/s, > 0 (shallow water: sqrt(g·depth)); typical 2
    /// @param damping      γ, 1/s, ≥ 0; typical 0.1
    /// @param height       rest level h, m
    /// @param centreX,centreZ  world centre of the grid, m
    /// @throws std::invalid_argument naming the bad parameter
    btInteractiveWaterSurface(double sizeX, double sizeZ, int resolution, double waveSpeed, double damping,
                              double height = 0.0, double centreX = 0.0, double centreZ = 0.0);

    /// Bilinear in the cell centres (clamped at the walls). `t` is ignored: the field is the current state.
    void heights(const double* x, const double* z, std::size_t n, double t, double* outHeight) const override;
    /// Vertical velocity ∂η/∂t of the surface (no horizontal flow), m/s.
    void velocities(const double* x, const double* y, const double* z, std::size_t n, double t, double* outVx,
                    double* outVy, double* outVz) const override;
    /// Global min/max of η.
    void heightBounds(double minX, double minZ, double maxX, double maxZ, double t, double& outMin,
                      double& outMax) const override;
    bool isTimeVarying() const override { return true; }
    /// The lattice of the cell centres (bilinear between them; clamped beyond the outer centres, still bilinear).
    bool bilinearLattice(double t, btWaterLattice& out) const override {
        (void)t;
        out.originX = m_minX + 0.5 * m_dx;
        out.originZ = m_minZ + 0.5 * m_dx;
        out.spacingX = out.spacingZ = m_dx;
        return true;
    }

    /// A body's displaced volume changed by dV (m³, may be negative) at (x, z) over a footprint of radius
    /// `radius` (m): η rises by dV in a ring that starts two cells outside the footprint (out of the bilinear
    /// reach of anything within `radius`) and is max(2 cells, radius/2) wide, and drops by dV uniformly over
    /// the grid (a level offset, O(ring) work). Σ (η − h) is unchanged. Points outside the grid are ignored.
    void addVolumeChange(double x, double z, double dV, double radius);
    /// Advance the wave equation by dt (s, ≥ 0), in internal steps with c·dt/dx ≤ 0.5 (stable).
    void step(double dt);

    /// V_w = Σ (η − h)·A_cell, m³ (0 at rest; conserved by step and addVolumeChange).
    double waterVolume() const;
    int cellsX() const { return m_nx; }
    int cellsZ() const { return m_nz; }
    /// Cell side, m.
    double cellSize() const { return m_dx; }
    /// Elevation of cell (i, j) (centre at minX + (i+½)dx, minZ + (j+½)dx), m.
    double cellHeight(int i, int j) const { return m_eta[std::size_t(j) * m_nx + i] + m_offset; }
    /// Set every cell to level h and at rest.
    void reset();

    /// Everything that carries from one step to the next, for save and restore (btInteractiveWaterCoupler::saveState).
    struct Dynamic {
        std::vector<double> eta;       ///< #cells elevations before the level offset, m (row by row along x)
        std::vector<double> velocity;  ///< #cells vertical velocities, m/s
        double offset = 0;             ///< the uniform level change of every cell, m
        double min = 0, max = 0;       ///< the height range heightBounds answers, m
    };
    /// The grid's dynamic state, bit for bit.
    Dynamic dynamicState() const;
    /// Set a state saved by dynamicState from a grid of the same cell counts.
    /// @throws std::invalid_argument when an array's size is not cellsX() · cellsZ() (the grid unchanged)
    void setDynamicState(const Dynamic& state);

private:
    void updateRange();

    int m_nx, m_nz;
    double m_dx, m_minX, m_minZ, m_c, m_gamma, m_h;
    std::vector<double> m_eta, m_vel, m_lap;
    std::vector<int> m_ring;  // scratch of addVolumeChange
    double m_min, m_max;
    double m_offset = 0;      // uniform level change of every cell (the sink of addVolumeChange), m
};
