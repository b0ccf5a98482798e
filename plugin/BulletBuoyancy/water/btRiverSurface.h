#pragma once
/// @file btRiverSurface.h
/// A river: flat water at a level whose current varies with position (design.md 2.8 "Rivers"). The current flows
/// along a centreline, a polyline in the horizontal plane, inside a channel of a given width; outside the channel the
/// water is still. The surface itself is the horizontal plane y = height (no slope along the flow, so the exact flat
/// clipping applies), and the current is steady and the same at every depth.
///
/// Velocity at a horizontal point p = (x, z) (design.md 2.8 gives the derivation):
/// - d = the distance from p to the centreline (the first and last segments continue straight beyond the end points,
///   so the channel does not close at the ends: bound the river with a water body's region);
/// - speed u(d) = u_max (1 − (2d/w)²) for d < w/2, 0 from the banks (d ≥ w/2) on: a parabola across the channel,
///   u_max on the centreline, 0 at the banks, 3/4 u_max at d = w/4;
/// - direction: the segments' unit tangents t_k blended by their distances d_k to p,
///   t̂ = Σ_k ω_k t_k / |Σ_k ω_k t_k| with ω_k = (1 − (d_k − d)/b)² for d_k − d < b, else 0, and b = w/2: the tangent
///   of the nearest segment away from the corners, turning continuously across a corner (the bisector's direction
///   on it) over about half a width on each side.
/// - velocity (u(d) t̂_x, 0, u(d) t̂_z), m/s.
///
/// Coordinates are the water frame's horizontal x, z (the world's x, z for a y-up world). A query costs O(number of
/// segments) per point; queries are const, allocate nothing and may run concurrently.

#include <BulletBuoyancy/water/btWaterSurface.h>

#include <cstddef>
#include <vector>

/// A point of a river's centreline in the horizontal plane, m.
struct btRiverPoint {
    double x = 0.0;  ///< m (water frame x)
    double z = 0.0;  ///< m (water frame z)
};

/// Parameters of btRiverSurface.
struct btRiverSettings {
    double height = 0.0;                   ///< water level h, m (water frame y); typical 0
    /// The centreline, upstream first: at least 2 points, finite, no two consecutive ones closer than 1e-6 m.
    /// The current flows from each point towards the next.
    std::vector<btRiverPoint> centreline;
    double width = 10.0;                   ///< channel width w, m, finite and > 0 (the current is 0 at d ≥ w/2)
    double surfaceSpeed = 1.0;             ///< u_max, the speed on the centreline, m/s, finite and ≥ 0; typical 0.5–3
};

/// Flat water with a current along a polyline channel (see the file comment for the velocity field).
class btRiverSurface : public btWaterSurface {
public:
    /// @throws std::invalid_argument naming the bad setting (e.g. "centreline[2]: repeats centreline[1] ...")
    explicit btRiverSurface(const btRiverSettings& settings);

    /// The level h at every point, m.
    void heights(const double* x, const double* z, std::size_t n, double t, double* outHeight) const override;
    /// The current at every point (independent of y and t), m/s: the file comment's field.
    void velocities(const double* x, const double* y, const double* z, std::size_t n, double t, double* outVx,
                    double* outVy, double* outVz) const override;
    /// Both bounds are the level h, m.
    void heightBounds(double minX, double minZ, double maxX, double maxZ, double t, double& outMin,
                      double& outMax) const override;
    /// Always true: the surface is the plane y = h (the current does not make it a uniform-current flat water: the
    /// velocity is queried at every point).
    bool isFlat(double t, double& outHeight) const override;

    /// d, the horizontal distance from (x, z) to the centreline (its end segments extended), m.
    double distanceToCentreline(double x, double z) const;
    /// u(d) = u_max (1 − (2d/w)²) for d < w/2, else 0, m/s; d, m (its sign is ignored).
    double speedAtDistance(double d) const;
    /// The unit flow direction t̂ at (x, z) (the blended tangent), whether or not the point is in the channel.
    /// @param[out] outX,outZ  its water frame x and z components
    void flowDirection(double x, double z, double& outX, double& outZ) const;

    /// The settings as given.
    const btRiverSettings& settings() const { return m_s; }
    /// Water level h, m.
    double level() const { return m_s.height; }

private:
    /// Distance from (x, z) to segment k (the first and last extended to rays), m.
    double segmentDistance(std::size_t k, double x, double z) const;
    /// d (m) and the index of the nearest segment (the first of equals).
    double nearestSegment(double x, double z, std::size_t& outSegment) const;
    /// t̂ at (x, z) given its distance d (m) and nearest segment.
    void blendedTangent(double x, double z, double d, std::size_t nearest, double& outX, double& outZ) const;

    btRiverSettings m_s;
    std::vector<double> m_tx, m_tz, m_length;  ///< per segment: unit tangent, length (m)
};
