#include <BulletBuoyancy/graph/WaterMassProperties.h>

#include <BulletBuoyancy/graph/NodeLevel.h>

namespace buoyancy {

Eigen::Matrix3d parallelAxisTerm(double mass, const Eigen::Vector3d& d) {
    return mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
}

MassProperties waterMassProperties(const WaterGraphState& state, double fluidDensity) {
    MassProperties mp;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    const std::size_t n = state.size();
    // Eqs. 15–16 with the free-surface centroids.
    for (std::size_t i = 0; i < n; ++i) {
        const double v = state.water(int(i));
        if (!(v > 0)) continue;
        mp.volume += v;
        mp.mass += fluidDensity * v;
        moment += fluidDensity * v * state.waterCentroid(int(i));
    }
    if (!(mp.mass > 0)) return MassProperties();
    mp.centre = moment / mp.mass;
    // Eq. 17 about the water's own centre: Σ m_n ((r_n − C_G)² E − (r_n − C_G)(r_n − C_G)ᵀ), plus (Shape
    // model) each node's water inertia about its own centroid (sphere cap / clipped box, NodeLevel.h).
    const bool shape = state.graph().inertia == WaterInertiaModel::Shape;
    for (std::size_t i = 0; i < n; ++i) {
        const double v = state.water(int(i));
        if (!(v > 0)) continue;
        mp.inertia += parallelAxisTerm(fluidDensity * v, state.waterCentroid(int(i)) - mp.centre);
        if (shape)
            mp.inertia += fluidDensity * nodeWaterInertia(state.graph().nodes[i], state.upInBody(), v);
    }
    return mp;
}

MassProperties composeMassProperties(const MassProperties& a, const MassProperties& b) {
    if (!(b.mass > 0)) return a;
    if (!(a.mass > 0)) return b;
    MassProperties c;
    c.mass = a.mass + b.mass;
    c.volume = a.volume + b.volume;
    c.area = a.area + b.area;
    c.centre = (a.mass * a.centre + b.mass * b.centre) / c.mass;
    c.inertia = a.inertia + parallelAxisTerm(a.mass, a.centre - c.centre) + b.inertia +
                parallelAxisTerm(b.mass, b.centre - c.centre);
    return c;
}

}  // namespace buoyancy
