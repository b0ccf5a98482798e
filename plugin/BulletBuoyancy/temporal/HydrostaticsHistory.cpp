#include <BulletBuoyancy/temporal/HydrostaticsHistory.h>

#include <BulletBuoyancy/state/StateBlob.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace buoyancy {
namespace {
void put(std::array<double, HydrostaticsHistory::kValues>& x, int at, const Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i) x[std::size_t(at + i)] = v[i];
}
Eigen::Vector3d get(const std::array<double, HydrostaticsHistory::kValues>& x, int at) {
    return Eigen::Vector3d(x[std::size_t(at)], x[std::size_t(at + 1)], x[std::size_t(at + 2)]);
}
}  // namespace

std::array<double, HydrostaticsHistory::kValues> HydrostaticsHistory::pack(const HydrostaticsSnapshot& s) {
    std::array<double, kValues> x{};
    const HydrostaticsResult& h = s.hydrostatics;
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
    const WaterplaneMoments& w = h.waterplane;
    x[36] = w.x;
    x[37] = w.z;
    x[38] = w.xx;
    x[39] = w.xz;
    x[40] = w.zz;
    return x;
}

HydrostaticsSnapshot HydrostaticsHistory::unpack(const std::array<double, kValues>& x) {
    HydrostaticsSnapshot s;
    HydrostaticsResult& h = s.hydrostatics;
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
    WaterplaneMoments& w = h.waterplane;
    w.x = x[36];
    w.z = x[37];
    w.xx = std::max(x[38], 0.0);
    w.xz = x[39];
    w.zz = std::max(x[40], 0.0);
    return s;
}

void HydrostaticsHistory::push(std::uint64_t substep, double time, const HydrostaticsSnapshot& snapshot) {
    for (int i = kStored - 1; i > 0; --i) m_records[std::size_t(i)] = m_records[std::size_t(i - 1)];
    m_records[0].substep = substep;
    m_records[0].time = time;
    m_records[0].x = pack(snapshot);
    m_records[0].waterplane = snapshot.hydrostatics.waterplane.valid;
    if (m_count < kStored) ++m_count;
}

bool HydrostaticsHistory::find(int interval, int index[kRecords]) const {
    if (m_count < kRecords || interval < 2) return false;
    const std::uint64_t k = std::uint64_t(interval);
    index[0] = 0;
    int at = 0;
    for (int j = 1; j < kRecords; ++j) {  // records newest first, substeps decreasing: search on from the last hit
        const std::uint64_t want = m_records[0].substep - std::uint64_t(j) * k;
        while (at + 1 < m_count && m_records[std::size_t(at + 1)].substep > want) ++at;
        if (at + 1 >= m_count || m_records[std::size_t(at + 1)].substep != want) return false;
        index[j] = ++at;
    }
    // Equal substep lengths: the records equally spaced in time.
    const double span = m_records[0].time - m_records[std::size_t(index[1])].time;
    if (!(span > 0)) return false;
    for (int j = 1; j + 1 < kRecords; ++j) {
        const double d = m_records[std::size_t(index[j])].time - m_records[std::size_t(index[j + 1])].time;
        if (std::abs(d - span) > 1e-6 * span) return false;
    }
    return true;
}

bool HydrostaticsHistory::spaced(std::uint64_t substep, double time, int interval, std::uint64_t maxAhead) const {
    int index[kRecords];
    if (!find(interval, index)) return false;
    const Record& newest = m_records[0];
    if (substep <= newest.substep || substep - newest.substep > maxAhead) return false;
    // `time` where the records' spacing puts it (a changed substep length makes the extrapolation meaningless).
    const double span = newest.time - m_records[std::size_t(index[1])].time;
    const double expected = newest.time + span * double(substep - newest.substep) / double(interval);
    return std::abs(time - expected) <= 1e-6 * span;
}

void HydrostaticsHistory::halveSpacing(int interval) {
    int index[kRecords];
    if (interval < 4 || interval % 2 != 0 || !find(interval, index)) {
        clear();
        return;
    }
    // Cubic interpolation through the four records (Newton's backward form at a = −½ and −3/2, inside their span):
    // the records K/2 before the newest and the second newest, so that the last four are K/2 apart.
    Record r[kRecords];
    for (int j = 0; j < kRecords; ++j) r[j] = m_records[std::size_t(index[j])];
    Record mid[2];
    for (int m = 0; m < 2; ++m) {
        const double a = -0.5 - double(m);
        const double c1 = a, c2 = 0.5 * a * (a + 1.0), c3 = c2 * (a + 2.0) / 3.0;
        mid[m].substep = r[m].substep - std::uint64_t(interval / 2);
        mid[m].time = 0.5 * (r[m].time + r[m + 1].time);
        for (std::size_t i = 0; i < mid[m].x.size(); ++i) {
            const double x0 = r[0].x[i], x1 = r[1].x[i], x2 = r[2].x[i], x3 = r[3].x[i];
            mid[m].x[i] = x0 + c1 * (x0 - x1) + c2 * (x0 - 2.0 * x1 + x2) + c3 * (x0 - 3.0 * (x1 - x2) - x3);
        }
        mid[m].waterplane = r[0].waterplane && r[1].waterplane && r[2].waterplane && r[3].waterplane;
    }
    m_records[0] = r[0];
    m_records[1] = mid[0];
    m_records[2] = r[1];
    m_records[3] = mid[1];
    m_records[4] = r[2];
    m_records[5] = r[3];
    m_count = 6;
}

bool HydrostaticsHistory::canPredict(std::uint64_t substep, double time, int interval) const {
    return interval >= 2 && spaced(substep, time, interval, std::uint64_t(interval) - 1);
}

bool HydrostaticsHistory::canCheck(std::uint64_t substep, double time, int interval) const {
    return interval >= 2 && spaced(substep, time, interval, std::uint64_t(interval)) &&
           substep - m_records[0].substep == std::uint64_t(interval);
}

HydrostaticsSnapshot HydrostaticsHistory::extrapolate(std::uint64_t substep, int interval) const {
    // Newton's backward-difference formula on four equally spaced samples (see the header).
    int index[kRecords];
    if (!find(interval, index)) return HydrostaticsSnapshot{};
    const double a = double(substep - m_records[0].substep) / double(interval);
    const double c1 = a, c2 = 0.5 * a * (a + 1.0), c3 = c2 * (a + 2.0) / 3.0;
    const Record &r0 = m_records[0], &r1 = m_records[std::size_t(index[1])], &r2 = m_records[std::size_t(index[2])],
                 &r3 = m_records[std::size_t(index[3])];
    std::array<double, kValues> y;
    for (std::size_t i = 0; i < y.size(); ++i) {
        const double x0 = r0.x[i], x1 = r1.x[i], x2 = r2.x[i], x3 = r3.x[i];
        y[i] = x0 + c1 * (x0 - x1) + c2 * (x0 - 2.0 * x1 + x2) + c3 * (x0 - 3.0 * (x1 - x2) - x3);
    }
    HydrostaticsSnapshot s = unpack(y);
    s.hydrostatics.waterplane.valid = r0.waterplane && r1.waterplane && r2.waterplane && r3.waterplane;
    return s;
}

double HydrostaticsHistory::volume(int intervalsBack, int interval) const {
    int index[kRecords];
    if (intervalsBack < 0 || intervalsBack >= kRecords || !find(interval, index)) return 0.0;
    return m_records[std::size_t(index[intervalsBack])].x[9];
}

double HydrostaticsHistory::poseDeviation(const Eigen::Vector3d& com, const Eigen::Matrix3d& rotation,
                                          const HydrostaticsSnapshot& predicted, double radius, double waterSlope) {
    const Eigen::Vector3d d = com - predicted.com;
    return std::abs(d.y()) + waterSlope * std::hypot(d.x(), d.z()) +
           radius * (rotation - predicted.rotation).norm() / std::sqrt(2.0);
}

double HydrostaticsHistory::correctedPoseDeviation(const Eigen::Vector3d& com, const Eigen::Matrix3d& rotation,
                                                   const HydrostaticsSnapshot& predicted, double radius,
                                                   double waterSlope) {
    const Eigen::Vector3d d = com - predicted.com;
    const double turn = radius * (rotation - predicted.rotation).norm() / std::sqrt(2.0);  // radius × angle
    const double rise = std::abs(d.y()) + turn;
    return waterSlope * (std::hypot(d.x(), d.z()) + turn) + (radius > 0 ? 8.0 * rise * rise / radius : rise);
}

double HydrostaticsHistory::velocityDeviation(const Eigen::Vector3d& linearVelocity,
                                              const Eigen::Vector3d& angularVelocity,
                                              const HydrostaticsSnapshot& predicted, double radius) {
    return (linearVelocity - predicted.linearVelocity).norm() +
           radius * (angularVelocity - predicted.angularVelocity).norm();
}

void hydrostaticStiffnessCorrection(HydrostaticsSnapshot& predicted, const Eigen::Vector3d& com,
                                    const Eigen::Matrix3d& rotation, double rhoG) {
    // See the header. The linear part restores the pose; what the waves drive is left to the extrapolation
    // (F = −C δ + G(t) predicted as −C δ + E[G]): extrapolating all of F leads a bobbing body's motion and pumps
    // energy into it (measured: temporal_lod.csv, energy column).
    HydrostaticsResult& h = predicted.hydrostatics;
    const double dy = com.y() - predicted.com.y();
    double dVolume = -h.waterline_area * dy;  // m³
    if (h.waterplane.valid) {
        const Eigen::Matrix3d M = rotation * predicted.rotation.transpose();  // ≈ I + [φ]×
        const Eigen::Vector3d phi(0.5 * (M(2, 1) - M(1, 2)), 0.5 * (M(0, 2) - M(2, 0)), 0.5 * (M(1, 0) - M(0, 1)));
        const WaterplaneMoments& w = h.waterplane;
        dVolume -= phi.z() * w.x - phi.x() * w.z;
        Eigen::Vector3d dTorque(rhoG * (w.z * dy + phi.z() * w.xz - phi.x() * w.zz), 0.0,
                                -rhoG * (w.x * dy + phi.z() * w.xx - phi.x() * w.xz));
        if (h.submerged_volume > 0) dTorque += phi.cross(h.centre_of_buoyancy - predicted.com).cross(h.force);
        h.torque += dTorque;
    }
    h.force.y() += rhoG * dVolume;
    h.submerged_volume = std::max(h.submerged_volume + dVolume, 0.0);
}

void HydrostaticsHistory::writeState(StateWriter& out) const {
    out.u32(std::uint32_t(kStored));
    out.u32(std::uint32_t(kValues));
    out.i32(m_count);
    for (const Record& r : m_records) {
        out.u64(r.substep);
        out.f64(r.time);
        out.f64s(r.x.data(), r.x.size());
        out.boolean(r.waterplane);
    }
}

void HydrostaticsHistory::readState(StateReader& in) {
    in.expectCount(in.u32("history records stored"), std::uint32_t(kStored), "the history's stored record count");
    in.expectCount(in.u32("history values per record"), std::uint32_t(kValues), "the history's values per record");
    HydrostaticsHistory h;
    h.m_count = in.i32("history record count");
    if (h.m_count < 0 || h.m_count > kStored)
        in.fail("the history holds " + std::to_string(h.m_count) + " records, at most " + std::to_string(kStored));
    for (Record& r : h.m_records) {
        r.substep = in.u64("history record substep");
        r.time = in.f64("history record time");
        in.f64s(r.x.data(), r.x.size(), "history record values");
        r.waterplane = in.boolean("history record waterplane");
    }
    *this = h;
}

}  // namespace buoyancy
