#include "bullet/btHydrostaticsHistory.h"

#include <algorithm>
#include <cmath>

namespace {
void put(std::array<double, btHydrostaticsHistory::kValues>& x, int at, const Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i) x[std::size_t(at + i)] = v[i];
}
Eigen::Vector3d get(const std::array<double, btHydrostaticsHistory::kValues>& x, int at) {
    return Eigen::Vector3d(x[std::size_t(at)], x[std::size_t(at + 1)], x[std::size_t(at + 2)]);
}
}  // namespace

std::array<double, btHydrostaticsHistory::kValues> btHydrostaticsHistory::pack(const btHydrostaticsSnapshot& s) {
    std::array<double, kValues> x{};
    const buoyancy::HydrostaticsResult& h = s.hydrostatics;
    put(x, 0, h.force);
    put(x, 3, h.torque);
    put(x, 6, h.centre_of_buoyancy);
    x[9] = h.submerged_volume;
    x[10] = h.waterline_area;
    x[11] = h.wetted_area;
    put(x, 12, s.com);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) x[std::size_t(15 + 3 * i + j)] = s.rotation(i, j);
    put(x, 24, s.dragForce);
    put(x, 27, s.dragTorque);
    put(x, 30, s.linearVelocity);
    put(x, 33, s.angularVelocity);
    const buoyancy::WaterplaneMoments& w = h.waterplane;
    x[36] = w.x;
    x[37] = w.z;
    x[38] = w.xx;
    x[39] = w.xz;
    x[40] = w.zz;
    return x;
}

btHydrostaticsSnapshot btHydrostaticsHistory::unpack(const std::array<double, kValues>& x) {
    btHydrostaticsSnapshot s;
    buoyancy::HydrostaticsResult& h = s.hydrostatics;
    h.force = get(x, 0);
    h.torque = get(x, 3);
    h.centre_of_buoyancy = get(x, 6);
    // Magnitudes: an extrapolation below zero (a body leaving the water fast) is clamped.
    h.submerged_volume = std::max(x[9], 0.0);
    h.waterline_area = std::max(x[10], 0.0);
    h.wetted_area = std::max(x[11], 0.0);
    s.com = get(x, 12);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) s.rotation(i, j) = x[std::size_t(15 + 3 * i + j)];
    s.dragForce = get(x, 24);
    s.dragTorque = get(x, 27);
    s.linearVelocity = get(x, 30);
    s.angularVelocity = get(x, 33);
    buoyancy::WaterplaneMoments& w = h.waterplane;
    w.x = x[36];
    w.z = x[37];
    w.xx = std::max(x[38], 0.0);
    w.xz = x[39];
    w.zz = std::max(x[40], 0.0);
    return s;
}

void btHydrostaticsHistory::push(std::uint64_t substep, double time, const btHydrostaticsSnapshot& snapshot) {
    for (int i = kRecords - 1; i > 0; --i) m_records[std::size_t(i)] = m_records[std::size_t(i - 1)];
    m_records[0].substep = substep;
    m_records[0].time = time;
    m_records[0].x = pack(snapshot);
    m_records[0].waterplane = snapshot.hydrostatics.waterplane.valid;
    if (m_count < kRecords) ++m_count;
}

bool btHydrostaticsHistory::spaced(std::uint64_t substep, double time, int interval, std::uint64_t maxAhead) const {
    if (m_count < kRecords || interval < 2) return false;
    const std::uint64_t k = std::uint64_t(interval);
    const Record& newest = m_records[0];
    if (substep <= newest.substep || substep - newest.substep > maxAhead) return false;
    // Equal substep lengths: the records equally spaced in time, and `time` where that spacing puts it.
    const double span = newest.time - m_records[1].time;
    const double slack = 1e-6 * std::abs(span);
    if (!(span > 0)) return false;
    for (int i = 0; i + 1 < kRecords; ++i) {
        const Record &a = m_records[std::size_t(i)], &b = m_records[std::size_t(i + 1)];
        if (a.substep - b.substep != k || std::abs((a.time - b.time) - span) > slack) return false;
    }
    const double expected = newest.time + span * double(substep - newest.substep) / double(k);
    return std::abs(time - expected) <= slack;
}

bool btHydrostaticsHistory::canPredict(std::uint64_t substep, double time, int interval) const {
    return interval >= 2 && spaced(substep, time, interval, std::uint64_t(interval) - 1);
}

bool btHydrostaticsHistory::canCheck(std::uint64_t substep, double time, int interval) const {
    return interval >= 2 && spaced(substep, time, interval, std::uint64_t(interval)) &&
           substep - m_records[0].substep == std::uint64_t(interval);
}

btHydrostaticsSnapshot btHydrostaticsHistory::extrapolate(std::uint64_t substep, int interval) const {
    // Newton's backward-difference formula on four equally spaced samples (see the header).
    const double a = double(substep - m_records[0].substep) / double(interval);
    const double c1 = a, c2 = 0.5 * a * (a + 1.0), c3 = c2 * (a + 2.0) / 3.0;
    std::array<double, kValues> y;
    for (std::size_t i = 0; i < y.size(); ++i) {
        const double x0 = m_records[0].x[i], x1 = m_records[1].x[i], x2 = m_records[2].x[i], x3 = m_records[3].x[i];
        y[i] = x0 + c1 * (x0 - x1) + c2 * (x0 - 2.0 * x1 + x2) + c3 * (x0 - 3.0 * (x1 - x2) - x3);
    }
    btHydrostaticsSnapshot s = unpack(y);
    s.hydrostatics.waterplane.valid = true;
    for (const Record& r : m_records) s.hydrostatics.waterplane.valid = s.hydrostatics.waterplane.valid && r.waterplane;
    return s;
}

double btHydrostaticsHistory::poseDeviation(const Eigen::Vector3d& com, const Eigen::Matrix3d& rotation,
                                            const btHydrostaticsSnapshot& predicted, double radius, double waterSlope) {
    const Eigen::Vector3d d = com - predicted.com;
    return std::abs(d.y()) + waterSlope * std::hypot(d.x(), d.z()) +
           radius * (rotation - predicted.rotation).norm() / std::sqrt(2.0);
}

double btHydrostaticsHistory::correctedPoseDeviation(const Eigen::Vector3d& com, const Eigen::Matrix3d& rotation,
                                                     const btHydrostaticsSnapshot& predicted, double radius,
                                                     double waterSlope) {
    const Eigen::Vector3d d = com - predicted.com;
    const double turn = radius * (rotation - predicted.rotation).norm() / std::sqrt(2.0);  // radius × angle
    const double rise = std::abs(d.y()) + turn;
    return waterSlope * (std::hypot(d.x(), d.z()) + turn) + (radius > 0 ? 8.0 * rise * rise / radius : rise);
}

double btHydrostaticsHistory::velocityDeviation(const Eigen::Vector3d& linearVelocity,
                                                const Eigen::Vector3d& angularVelocity,
                                                const btHydrostaticsSnapshot& predicted, double radius) {
    return (linearVelocity - predicted.linearVelocity).norm() +
           radius * (angularVelocity - predicted.angularVelocity).norm();
}

void btHydrostaticStiffnessCorrection(btHydrostaticsSnapshot& predicted, const Eigen::Vector3d& com,
                                      const Eigen::Matrix3d& rotation, double rhoG) {
    // See the header. The linear part restores the pose; what the waves drive is left to the extrapolation
    // (F = −C δ + G(t) predicted as −C δ + E[G]): extrapolating all of F leads a bobbing body's motion and pumps
    // energy into it (measured: temporal_lod.csv, energy column).
    buoyancy::HydrostaticsResult& h = predicted.hydrostatics;
    const double dy = com.y() - predicted.com.y();
    double dVolume = -h.waterline_area * dy;  // m³
    if (h.waterplane.valid) {
        const Eigen::Matrix3d M = rotation * predicted.rotation.transpose();  // ≈ I + [φ]×
        const Eigen::Vector3d phi(0.5 * (M(2, 1) - M(1, 2)), 0.5 * (M(0, 2) - M(2, 0)), 0.5 * (M(1, 0) - M(0, 1)));
        const buoyancy::WaterplaneMoments& w = h.waterplane;
        dVolume -= phi.z() * w.x - phi.x() * w.z;
        Eigen::Vector3d dTorque(rhoG * (w.z * dy + phi.z() * w.xz - phi.x() * w.zz), 0.0,
                                -rhoG * (w.x * dy + phi.z() * w.xx - phi.x() * w.xz));
        if (h.submerged_volume > 0) dTorque += phi.cross(h.centre_of_buoyancy - predicted.com).cross(h.force);
        h.torque += dTorque;
    }
    h.force.y() += rhoG * dVolume;
    h.submerged_volume = std::max(h.submerged_volume + dVolume, 0.0);
}
