#include "bullet/btHydrostaticsHistory.h"

#include <algorithm>
#include <cmath>

namespace {
void put(std::array<double, 36>& x, int at, const Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i) x[std::size_t(at + i)] = v[i];
}
Eigen::Vector3d get(const std::array<double, 36>& x, int at) {
    return Eigen::Vector3d(x[std::size_t(at)], x[std::size_t(at + 1)], x[std::size_t(at + 2)]);
}
}  // namespace

std::array<double, 36> btHydrostaticsHistory::pack(const btHydrostaticsSnapshot& s) {
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
    return s;
}

void btHydrostaticsHistory::push(std::uint64_t substep, double time, const btHydrostaticsSnapshot& snapshot) {
    m_records[2] = m_records[1];
    m_records[1] = m_records[0];
    m_records[0].substep = substep;
    m_records[0].time = time;
    m_records[0].x = pack(snapshot);
    if (m_count < 3) ++m_count;
}

bool btHydrostaticsHistory::spaced(std::uint64_t substep, double time, int interval, std::uint64_t maxAhead) const {
    if (m_count < 3 || interval < 2) return false;
    const std::uint64_t k = std::uint64_t(interval);
    const Record &r0 = m_records[0], &r1 = m_records[1], &r2 = m_records[2];
    if (r0.substep - r1.substep != k || r1.substep - r2.substep != k || substep <= r0.substep ||
        substep - r0.substep > maxAhead)
        return false;
    // Equal substep lengths: the records equally spaced in time, and `time` where that spacing puts it.
    const double span = r0.time - r1.time;
    const double slack = 1e-6 * std::abs(span);
    const double expected = r0.time + span * double(substep - r0.substep) / double(k);
    return span > 0 && std::abs((r1.time - r2.time) - span) <= slack && std::abs(time - expected) <= slack;
}

bool btHydrostaticsHistory::canPredict(std::uint64_t substep, double time, int interval) const {
    return interval >= 2 && spaced(substep, time, interval, std::uint64_t(interval) - 1);
}

bool btHydrostaticsHistory::canCheck(std::uint64_t substep, double time, int interval) const {
    return interval >= 2 && spaced(substep, time, interval, std::uint64_t(interval)) &&
           substep - m_records[0].substep == std::uint64_t(interval);
}

btHydrostaticsSnapshot btHydrostaticsHistory::extrapolate(std::uint64_t substep, int interval) const {
    // Newton's backward-difference formula on three equally spaced samples (see the header).
    const double a = double(substep - m_records[0].substep) / double(interval);
    const double c1 = a, c2 = 0.5 * a * (a + 1.0);
    std::array<double, kValues> y;
    for (std::size_t i = 0; i < y.size(); ++i) {
        const double x0 = m_records[0].x[i], x1 = m_records[1].x[i], x2 = m_records[2].x[i];
        y[i] = x0 + c1 * (x0 - x1) + c2 * (x0 - 2.0 * x1 + x2);
    }
    return unpack(y);
}

double btHydrostaticsHistory::poseDeviation(const Eigen::Vector3d& com, const Eigen::Matrix3d& rotation,
                                            const btHydrostaticsSnapshot& predicted, double radius) {
    return (com - predicted.com).norm() + radius * (rotation - predicted.rotation).norm() / std::sqrt(2.0);
}

double btHydrostaticsHistory::velocityDeviation(const Eigen::Vector3d& linearVelocity,
                                                const Eigen::Vector3d& angularVelocity,
                                                const btHydrostaticsSnapshot& predicted, double radius) {
    return (linearVelocity - predicted.linearVelocity).norm() +
           radius * (angularVelocity - predicted.angularVelocity).norm();
}
