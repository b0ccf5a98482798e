#include "benchmark/SpeedVsError.h"

#include "benchmark/ComparisonMethods.h"
#include "benchmark/PlaneClipMethods.h"
#include "benchmark/SubTexel.h"
#include "oracles/PolyhedralOracle.h"
#include "oracles/WaveOracle.h"

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iomanip>
#include <ostream>
#include <stdexcept>

namespace buoyancy::bench {

namespace {

constexpr double kRho = 1000.0;
constexpr double kG = 9.81;

/// Exact reference of one shape at one pose (design.md 5: plane clipping of the same mesh).
struct PoseReference {
    BenchPose pose;
    double volume = 0;
    Eigen::Vector3d cob = Eigen::Vector3d::Zero();
    Eigen::Vector3d ref = Eigen::Vector3d::Zero();     ///< the body's exact centre of volume, world
    Eigen::Vector3d torque = Eigen::Vector3d::Zero();  ///< Archimedes: (C_B − ref) × (0, ρ g V_sub, 0)
    /// Wave rows: pose.pose as the body holds it (btScalar rounding), the pose every method is evaluated at.
    Eigen::Isometry3d held = Eigen::Isometry3d::Identity();
};

struct ShapeReference {
    double volume = 0, diagonal = 0;
    std::vector<PoseReference> poses;
};

ShapeReference reference(const BenchShape& s, const SpeedErrorOptions& o) {
    ShapeReference r;
    const auto dry = buoyancy_test::oracleDryMoments(s.mesh.vertices, s.mesh.triangles);
    r.volume = dry.volume;
    r.diagonal = boundingBoxDiagonal(s.mesh);
    for (const BenchPose& p : benchPoses(s.mesh, o.drafts, o.heels)) {
        PoseReference pr;
        pr.pose = p;
        const auto sub = buoyancy_test::oracleSubmergedMoments(buoyancy_test::oraclePose(s.mesh.vertices, p.pose),
                                                               s.mesh.triangles, 0.0);
        pr.volume = sub.volume;
        pr.cob = sub.centroid;
        pr.ref = p.pose * dry.centroid;
        pr.torque = (pr.cob - pr.ref).cross(Eigen::Vector3d(0, kRho * kG * pr.volume, 0));
        r.poses.push_back(pr);
    }
    return r;
}

/// Errors of one evaluation against the reference, in the table's units.
void fillErrors(SpeedErrorRow& row, const ShapeReference& sr, const PoseReference& pr, double volume,
                const Eigen::Vector3d& cob, const Eigen::Vector3d& torque) {
    row.volume_error_pct = 100.0 * std::abs(volume - pr.volume) / sr.volume;
    row.cob_error_pct = volume > 0 ? 100.0 * (cob - pr.cob).norm() / sr.diagonal : 100.0;
    row.torque_error_pct = 100.0 * (torque - pr.torque).norm() / (kRho * kG * sr.volume * sr.diagonal);
    row.submerged_fraction = pr.volume / sr.volume;
}

void logConfig(std::ostream& log, const std::vector<SpeedErrorRow>& rows, std::size_t first, double setupSeconds) {
    if (rows.size() <= first) return;
    double v = 0, c = 0, ns = 0, nsH = 0;
    for (std::size_t i = first; i < rows.size(); ++i) {
        v = std::max(v, rows[i].volume_error_pct);
        c = std::max(c, rows[i].cob_error_pct);
        ns += rows[i].ns_per_body_substep;
        nsH += rows[i].ns_hydrostatics;
    }
    ns /= double(rows.size() - first);
    nsH /= double(rows.size() - first);
    const SpeedErrorRow& r = rows[first];
    log << "  " << std::left << std::setw(11) << r.shape;
    if (r.water != "flat") log << std::setw(6) << r.water;
    log << std::setw(15) << r.method << std::setw(5) << r.texture << ' '
        << std::setw(18) << r.variant << std::right << std::setw(8) << r.samples << " samples  worst V "
        << std::setprecision(3) << std::scientific << v << " %  CoB " << c << " %  " << std::fixed
        << std::setprecision(0) << std::setw(9) << ns << " ns/substep";
    if (std::isfinite(nsH)) log << std::setw(9) << nsH << " ns hydrostatics";
    log << "  (setup " << std::setprecision(2) << setupSeconds << " s)" << std::defaultfloat << std::setprecision(6) << '\n';
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::vector<SpeedErrorRow> runSpeedVsError(const std::vector<BenchShape>& shapes, const SpeedErrorOptions& o,
                                           std::ostream& log) {
    std::vector<SpeedErrorRow> rows;
    const btFlatWaterSurface water(0.0);
    for (const BenchShape& s : shapes) {
        const ShapeReference sr = reference(s, o);
        log << s.name << " (" << s.mesh.triangleCount() << " triangles, V = " << sr.volume << " m3)\n";
        auto base = [&](const std::string& method, int texture, const std::string& variant, std::size_t samples) {
            SpeedErrorRow r;
            r.shape = s.name;
            r.triangles = s.mesh.triangleCount();
            r.method = method;
            r.texture = texture;
            r.variant = variant;
            r.samples = samples;
            return r;
        };

        // Library configurations: the shape as btBuoyancyShape builds it, errors from the same integrals the
        // action calls, time from the action itself.
        auto library = [&](const std::string& label, btBuoyancySettings settings) {
            const auto t0 = std::chrono::steady_clock::now();
            std::shared_ptr<const btBuoyancyShape> shape;
            try {
                shape = btBuoyancyShape::create(s.mesh, settings);
            } catch (const std::exception& e) {
                log << "  " << s.name << ' ' << label << ' ' << settings.textureSize << ": skipped (" << e.what() << ")\n";
                return;
            }
            const double setup = secondsSince(t0);
            SingleBodyRig rig(shape);
            // One exact evaluation per timed call: the methods are compared per evaluation (the paper's have no
            // temporal level of detail; hydrostaticsInterval is measured on its own in temporal_lod.csv and the
            // scaling rows). Timed at a fixed pose, half the default's calls would be trivially predicted.
            btBuoyancySettings timed = settings;
            timed.hydrostaticsInterval = 1;
            btBuoyancyAction action(rig.body(), &rig.buoyancyWorld(), timed);
            const bool mesh = shape->getMethod() == btBuoyancyMethod::ExactMesh;
            const int texture = mesh ? 0 : shape->getTextureSize();
            const std::size_t samples = mesh ? s.mesh.triangleCount() : shape->getSamples().size();
            std::string variant;
            const std::string resolved = std::string(btBuoyancyMethodName(shape->getMethod())) + (mesh ? "" : "-" + std::to_string(texture));
            if (label == "default") variant = resolved;
            if (label == "lod") {  // automatic level of detail: the budget and what it picked
                char b[32];
                std::snprintf(b, sizeof b, "budget-%g%%:", settings.errorBudget);
                variant = b + resolved;
            }
            SampleWorkspace ws;
            const std::size_t first = rows.size();
            for (const PoseReference& pr : sr.poses) {
                // Through the shape's method entry, as the action evaluates it (design.md 8.2).
                const HydrostaticsResult h = shape->getIntegrationMethod().evaluate(
                    shape->getGeometry(shape->getSamples()), pr.pose.pose, {water, 0.0, kRho, kG, pr.ref, nullptr, &ws});
                SpeedErrorRow row = base(label, texture, variant, samples);
                row.pose = pr.pose.id;
                fillErrors(row, sr, pr, h.submerged_volume, h.centre_of_buoyancy, h.torque);
                row.ns_per_body_substep = rig.nsPerSubstep(action, pr.pose.pose, o.timing);
                rows.push_back(row);
            }
            logConfig(log, rows, first, setup);
        };
        library("default", btBuoyancySettings());
        for (const char* m : {"texel-centre", "exact-coverage"})
            for (int n : o.textures) {
                btBuoyancySettings st;
                st.method = btBuoyancyMethodFromName(m);
                st.textureSize = n;
                library(m, st);
            }
        {
            btBuoyancySettings st;
            st.method = btBuoyancyMethod::ExactMesh;
            library("exact-mesh", st);
        }
        // Automatic level of detail (btBuoyancySettings::errorBudget): what each budget picks, measured.
        for (double budget : o.budgets) {
            btBuoyancySettings st;
            st.errorBudget = budget;
            library("lod", st);
        }
        // Sub-texel waterline (design.md 2.4; SubTexel.h): exact-coverage samples, wet part of straddling samples.
        for (int n : o.textures) {
            btBuoyancySettings st;
            st.method = btBuoyancyMethod::ExactCoverage;
            st.textureSize = n;
            const auto t0 = std::chrono::steady_clock::now();
            std::shared_ptr<const btBuoyancyShape> shape;
            try {
                shape = btBuoyancyShape::create(s.mesh, st);
            } catch (const std::exception& e) {
                log << "  " << s.name << " sub-texel " << n << ": skipped (" << e.what() << ")\n";
                continue;
            }
            const double setup = secondsSince(t0);
            SingleBodyRig rig(shape);
            btBuoyancySettings dragOnly = st;
            dragOnly.buoyancyEnabled = false;
            btBuoyancyAction drag(rig.body(), &rig.buoyancyWorld(), dragOnly);
            SubTexelAction action(rig.body().getRigidBody(), &shape->getSamples(), &rig.water(), rig.meshInCom(), &drag,
                                  kRho, kG);
            SampleWorkspace ws;
            const std::size_t first = rows.size();
            for (const PoseReference& pr : sr.poses) {
                const HydrostaticsResult h = subTexelHydrostatics(shape->getSamples(), pr.pose.pose, water, 0.0, kRho, kG, pr.ref, ws);
                SpeedErrorRow row = base("sub-texel", shape->getTextureSize(), "", shape->getSamples().size());
                row.pose = pr.pose.id;
                fillErrors(row, sr, pr, h.submerged_volume, h.centre_of_buoyancy, h.torque);
                row.ns_per_body_substep = rig.nsPerSubstep(action, pr.pose.pose, o.timing);
                rows.push_back(row);
            }
            logConfig(log, rows, first, setup);
        }

        // Comparison methods (not in the library), timed on the body of an exact-mesh shape (no bake).
        btBuoyancySettings meshSettings;
        meshSettings.method = btBuoyancyMethod::ExactMesh;
        SingleBodyRig rig(btBuoyancyShape::create(s.mesh, meshSettings));
        const Eigen::Isometry3d meshInCom = rig.meshInCom();
        auto comparison = [&](const std::string& method, const ProbeSet* probes, const FaceSet* faces, double setup) {
            ComparisonAction action(rig.body().getRigidBody(), probes, faces, &rig.water(), meshInCom, kRho, kG);
            ComparisonWorkspace ws;
            const std::size_t first = rows.size();
            for (const PoseReference& pr : sr.poses) {
                const ComparisonResult c =
                    probes ? probeHydrostatics(*probes, pr.pose.pose, water, 0.0, kRho, kG, pr.ref, ws)
                           : downwardFaceHydrostatics(*faces, pr.pose.pose, water, 0.0, kRho, kG, pr.ref, ws);
                SpeedErrorRow row = base(method, 0, probes ? probes->variant : "", probes ? probes->size() : faces->size());
                row.pose = pr.pose.id;
                fillErrors(row, sr, pr, c.volume, c.centre, c.torque);
                row.ns_per_body_substep = rig.nsPerSubstep(action, pr.pose.pose, o.timing);
                rows.push_back(row);
            }
            logConfig(log, rows, first, setup);
        };
        for (int n : o.hullProbes) {
            const auto t0 = std::chrono::steady_clock::now();
            const ProbeSet p = makeHullProbes(s.mesh, n, sr.volume);
            comparison("probes", &p, nullptr, secondsSince(t0));
        }
        for (int n : o.gridProbes) {
            const auto t0 = std::chrono::steady_clock::now();
            const ProbeSet p = makeGridProbes(s.mesh, n, sr.volume);
            comparison("probes", &p, nullptr, secondsSince(t0));
        }
        const FaceSet faces = makeFaceSet(s.mesh);
        comparison("downward-faces", nullptr, &faces, 0.0);
    }
    return rows;
}

namespace {

Eigen::Vector3d toEigen(const btVector3& v) { return {double(v.x()), double(v.y()), double(v.z())}; }

/// The wave reference of one shape at every pose (tests/oracles/WaveOracle): the pose as the body holds it, the
/// body's centre of mass there (the torque reference of every method), and the oracle's integrals.
ShapeReference waveReference(const BenchShape& s, const std::vector<BenchPose>& poses, const btWaterSurface& water,
                             double shortestWavelength, SingleBodyRig& rig, const SpeedErrorOptions& o) {
    ShapeReference r;
    r.volume = buoyancy_test::oracleDryMoments(s.mesh.vertices, s.mesh.triangles).volume;
    r.diagonal = boundingBoxDiagonal(s.mesh);
    buoyancy_test::WaveOracleOptions oo;
    // Fine against the shortest wave, bounded below by 1 % of the body's size (keeps the reference fast).
    oo.maxEdge = std::max(shortestWavelength / 40.0, 0.01 * r.diagonal);
    oo.waterlineLevels = o.oracleWaterlineLevels;
    for (const BenchPose& p : poses) {
        PoseReference pr;
        pr.pose = p;
        pr.held = rig.heldMeshPose(p.pose);
        pr.ref = rig.centreOfMass();
        const std::vector<Eigen::Vector3d> verts = buoyancy_test::oraclePose(s.mesh.vertices, pr.held);
        Eigen::Vector3d lo = verts.front(), hi = lo;
        for (const auto& v : verts) {
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
        }
        double wMin = 0, wMax = 0;
        water.heightBounds(lo.x(), lo.z(), hi.x(), hi.z(), p.time, wMin, wMax);
        oo.waterMax = wMax;
        const double t = p.time;
        const auto eta = [&water, t](double x, double z) { return water.height(x, z, t); };
        const buoyancy_test::WaveOracleResult w = buoyancy_test::waveOracle(verts, s.mesh.triangles, eta, pr.ref, oo);
        pr.volume = w.volume;
        pr.cob = w.centreOfBuoyancy();
        pr.torque = kRho * kG * w.torque;
        r.poses.push_back(pr);
    }
    return r;
}

}  // namespace

std::vector<SpeedErrorRow> runSpeedVsErrorWaves(const std::vector<BenchShape>& shapes, const std::vector<BenchSea>& seas,
                                                const SpeedErrorOptions& o, std::ostream& log) {
    std::vector<SpeedErrorRow> rows;
    for (const BenchSea& sea : seas) {
        const btGerstnerWaterSurface water(sea.waves);
        const double lambda = water.shortestWavelength();
        for (const BenchShape& s : shapes) {
            const auto t0 = std::chrono::steady_clock::now();
            const std::vector<BenchPose> poses = waveBenchPoses(s.mesh, water, o.waveTimes, o.waveOffsets, o.waveHeels);
            // The body of the default configuration: its held poses and centre of mass are every method's.
            SingleBodyRig rig(btBuoyancyShape::create(s.mesh, btBuoyancySettings()), &water);
            const ShapeReference sr = waveReference(s, poses, water, lambda, rig, o);
            log << s.name << " in " << sea.name << " (" << s.mesh.triangleCount() << " triangles, V = " << sr.volume
                << " m3; reference " << std::setprecision(3) << secondsSince(t0) << " s for " << poses.size()
                << " poses)" << std::setprecision(6) << '\n';
            auto base = [&](const std::string& method, const std::string& variant, std::size_t samples,
                            const PoseReference& pr) {
                SpeedErrorRow r;
                r.shape = s.name;
                r.triangles = s.mesh.triangleCount();
                r.method = method;
                r.variant = variant;
                r.samples = samples;
                r.pose = pr.pose.id;
                r.water = sea.name;
                return r;
            };

            // The library: errors from what the action computed at the pose and time; timed with drag on, and with
            // drag off (ns_hydrostatics).
            auto library = [&](const std::string& label, const btBuoyancySettings& settings) {
                const auto ts = std::chrono::steady_clock::now();
                const auto shape = btBuoyancyShape::create(s.mesh, settings);
                SingleBodyRig own(shape, &water);
                btBuoyancySettings timed = settings;
                timed.hydrostaticsInterval = 1;  // one exact evaluation per call (as the flat rows)
                btBuoyancySettings dry = timed;
                dry.dragCoefficient = 0;
                dry.skinFriction = 0;
                dry.linearDamping = 0;
                dry.radiationDamping = 0;
                btBuoyancyAction full(own.body(), &own.buoyancyWorld(), timed);
                btBuoyancyAction hydro(own.body(), &own.buoyancyWorld(), dry);
                const bool mesh = shape->getMethod() == btBuoyancyMethod::ExactMesh;
                const std::string resolved = std::string(btBuoyancyMethodName(shape->getMethod())) +
                                             (mesh ? "" : "-" + std::to_string(shape->getTextureSize()));
                const std::size_t samples = mesh ? s.mesh.triangleCount() : shape->getSamples().size();
                const std::size_t first = rows.size();
                for (const PoseReference& pr : sr.poses) {
                    const btBuoyancyResult& h = own.evaluate(full, pr.pose.pose, pr.pose.time);
                    SpeedErrorRow row = base(label, label == "default" ? resolved : "", samples, pr);
                    row.texture = mesh ? 0 : shape->getTextureSize();
                    fillErrors(row, sr, pr, h.submergedVolume, toEigen(h.centreOfBuoyancy), toEigen(h.buoyancyTorque));
                    row.ns_per_body_substep = own.nsPerSubstep(full, pr.pose.pose, o.timing, pr.pose.time);
                    row.ns_hydrostatics = own.nsPerSubstep(hydro, pr.pose.pose, o.timing, pr.pose.time);
                    rows.push_back(row);
                }
                logConfig(log, rows, first, secondsSince(ts));
            };
            library("default", btBuoyancySettings());
            {
                btBuoyancySettings st;
                st.method = btBuoyancyMethod::ExactMesh;
                library("exact-mesh", st);
            }

            // The plane methods: hydrostatics alone, and with the library's drag path (a drag-only btBuoyancyAction).
            btBuoyancySettings dragOnly;
            dragOnly.buoyancyEnabled = false;
            dragOnly.hydrostaticsInterval = 1;
            btBuoyancyAction drag(rig.body(), &rig.buoyancyWorld(), dragOnly);
            Eigen::AlignedBox3d bounds;
            for (const auto& v : s.mesh.vertices) bounds.extend(v);
            for (PlaneMethod m : {PlaneMethod::Tangent, PlaneMethod::Fitted}) {
                PlaneMethodAction full(rig.body().getRigidBody(), m, &s.mesh, &water, &rig.buoyancyWorld(),
                                       rig.meshInCom(), &drag, kRho, kG);
                PlaneMethodAction hydro(rig.body().getRigidBody(), m, &s.mesh, &water, &rig.buoyancyWorld(),
                                        rig.meshInCom(), nullptr, kRho, kG);
                const std::size_t first = rows.size();
                for (const PoseReference& pr : sr.poses) {
                    const HydrostaticsResult h = planeMethodHydrostatics(m, s.mesh, bounds, pr.held, water,
                                                                         pr.pose.time, kRho, kG, pr.ref);
                    SpeedErrorRow row = base(planeMethodName(m), "", s.mesh.triangleCount(), pr);
                    fillErrors(row, sr, pr, h.submerged_volume, h.centre_of_buoyancy, h.torque);
                    row.ns_per_body_substep = rig.nsPerSubstep(full, pr.pose.pose, o.timing, pr.pose.time);
                    row.ns_hydrostatics = rig.nsPerSubstep(hydro, pr.pose.pose, o.timing, pr.pose.time);
                    rows.push_back(row);
                }
                logConfig(log, rows, first, 0.0);
            }

            // The other engines' methods (ComparisonMethods.h), with and without their drag.
            auto comparison = [&](const std::string& method, const ProbeSet* probes, const FaceSet* faces, double setup) {
                ComparisonAction full(rig.body().getRigidBody(), probes, faces, &water, rig.meshInCom(), kRho, kG,
                                      &rig.buoyancyWorld(), true);
                ComparisonAction hydro(rig.body().getRigidBody(), probes, faces, &water, rig.meshInCom(), kRho, kG,
                                       &rig.buoyancyWorld(), false);
                ComparisonWorkspace ws;
                const std::size_t first = rows.size();
                for (const PoseReference& pr : sr.poses) {
                    const ComparisonResult c =
                        probes ? probeHydrostatics(*probes, pr.held, water, pr.pose.time, kRho, kG, pr.ref, ws)
                               : downwardFaceHydrostatics(*faces, pr.held, water, pr.pose.time, kRho, kG, pr.ref, ws);
                    SpeedErrorRow row = base(method, probes ? probes->variant : "", probes ? probes->size() : faces->size(), pr);
                    fillErrors(row, sr, pr, c.volume, c.centre, c.torque);
                    row.ns_per_body_substep = rig.nsPerSubstep(full, pr.pose.pose, o.timing, pr.pose.time);
                    row.ns_hydrostatics = rig.nsPerSubstep(hydro, pr.pose.pose, o.timing, pr.pose.time);
                    rows.push_back(row);
                }
                logConfig(log, rows, first, setup);
            };
            for (int n : o.waveHullProbes) {
                const auto ts = std::chrono::steady_clock::now();
                const ProbeSet p = makeHullProbes(s.mesh, n, sr.volume);
                comparison("probes", &p, nullptr, secondsSince(ts));
            }
            for (int n : o.waveGridProbes) {
                const auto ts = std::chrono::steady_clock::now();
                const ProbeSet p = makeGridProbes(s.mesh, n, sr.volume);
                comparison("probes", &p, nullptr, secondsSince(ts));
            }
            const FaceSet faces = makeFaceSet(s.mesh);
            comparison("downward-faces", nullptr, &faces, 0.0);
            log << "  " << s.name << " in " << sea.name << ": " << std::setprecision(3) << secondsSince(t0) << " s"
                << std::setprecision(6) << '\n';
        }
    }
    return rows;
}

void writeSpeedVsErrorCsv(const std::string& path, const std::vector<SpeedErrorRow>& rows) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + path);
    std::fprintf(f, "shape,triangles,method,texture,variant,samples,pose,volume_error_pct,cob_error_pct,"
                    "torque_error_pct,ns_per_body_substep,water,ns_hydrostatics,submerged_fraction\n");
    for (const SpeedErrorRow& r : rows) {
        char hydro[32] = "";  // empty where not measured
        if (std::isfinite(r.ns_hydrostatics)) std::snprintf(hydro, sizeof hydro, "%.1f", r.ns_hydrostatics);
        std::fprintf(f, "%s,%zu,%s,%d,%s,%zu,%s,%.6g,%.6g,%.6g,%.1f,%s,%s,%.6g\n", r.shape.c_str(), r.triangles,
                     r.method.c_str(), r.texture, r.variant.c_str(), r.samples, r.pose.c_str(), r.volume_error_pct,
                     r.cob_error_pct, r.torque_error_pct, r.ns_per_body_substep, r.water.c_str(), hydro,
                     r.submerged_fraction);
    }
    if (std::fclose(f) != 0) throw std::runtime_error("cannot write " + path);
}

}  // namespace buoyancy::bench
