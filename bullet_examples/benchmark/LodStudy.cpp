#include "benchmark/LodStudy.h"

#include "benchmark/BodyTiming.h"
#include "benchmark/Scaling.h"

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyShape.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace buoyancy::bench {

namespace {

constexpr double kRho = 1000.0, kG = 9.81;
using Clock = std::chrono::steady_clock;

template <class F>
double nsPerCall(F&& f, int minCalls) {
    double best = 1e300;
    for (int b = 0; b < 3; ++b) {
        const auto t0 = Clock::now();
        for (int i = 0; i < minCalls; ++i) f();
        best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count() / minCalls);
    }
    return 1e9 * best;
}

std::FILE* openCsv(const std::string& path, const char* header) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + path);
    std::fputs(header, f);
    return f;
}

}  // namespace

std::string runLodStudy(const std::vector<BenchShape>& shapes, const std::vector<std::string>& waveShapes,
                        const std::string& outDir, bool quick, std::ostream& log) {
    std::ostringstream md;
    // ---- Waves: water patch against exact per-vertex queries (same clipping, same wave field) --------------
    {
        std::FILE* f = openCsv(outDir + "/waves_lod.csv",
                               "shape,triangles,nodes,pose,time,volume_error_pct,cob_error_pct,torque_error_pct,"
                               "ns_hydrostatics\n");
        const btGerstnerWaterSurface sea(p3Sea());
        const std::vector<int> nodes = quick ? std::vector<int>{8} : std::vector<int>{5, 6, 8, 12, 16};
        const std::vector<double> times = quick ? std::vector<double>{0.0} : std::vector<double>{0.0, 3.7, 8.1};
        for (const BenchShape& s : shapes) {
            if (std::find(waveShapes.begin(), waveShapes.end(), s.name) == waveShapes.end()) continue;
            btBuoyancySettings st;
            st.method = btBuoyancyMethod::ExactMesh;
            const auto shape = btBuoyancyShape::create(s.mesh, st);
            const double V = shape->getVolume(), diag = boundingBoxDiagonal(s.mesh);
            const std::vector<BenchPose> poses = benchPoses(s.mesh, quick ? std::vector<double>{0.5} : std::vector<double>{0.3, 0.5, 0.7},
                                                            quick ? std::vector<double>{0} : std::vector<double>{0, 20});
            std::map<int, double> worstV, worstC, sumNs;
            double exactNs = 0;
            int count = 0;
            for (const BenchPose& p : poses)
                for (double t : times) {
                    // Place the body where the sea is: at a point of the sea, with its pose's draft about the local level.
                    Eigen::Isometry3d pose = p.pose;
                    const double x = 7.3 * (count + 1), z = -4.1 * (count + 1);
                    pose.pretranslate(Eigen::Vector3d(x, sea.height(x, z, t), z));
                    const Eigen::Vector3d ref = pose * shape->getUnitSolid().centre;
                    const HydrostaticsResult exact = clippedHydrostatics(shape->getMesh(), pose, sea, t, kRho, kG, ref);
                    exactNs += nsPerCall([&] { clippedHydrostatics(shape->getMesh(), pose, sea, t, kRho, kG, ref); }, quick ? 3 : 10);
                    const Eigen::Vector3d bc = pose * shape->getBoundsCentre();
                    for (int m : nodes) {
                        WaterPatch patch;
                        btWaterQueryCache cache;
                        HydrostaticsResult h;
                        const double ns = nsPerCall([&] {
                            patch.build(sea, bc.x(), bc.z(), shape->getBoundsRadius(), t, m, cache);
                            h = clippedHydrostatics(shape->getMesh(), pose, sea, t, kRho, kG, ref, &patch);
                        }, quick ? 3 : 10);
                        const double eV = 100.0 * std::abs(h.submerged_volume - exact.submerged_volume) / V;
                        const double eC = 100.0 * (h.centre_of_buoyancy - exact.centre_of_buoyancy).norm() / diag;
                        const double eT = 100.0 * (h.torque - exact.torque).norm() / (kRho * kG * V * diag);
                        std::fprintf(f, "%s,%zu,%d,%s,%.1f,%.6g,%.6g,%.6g,%.0f\n", s.name.c_str(), s.mesh.triangleCount(), m,
                                     p.id.c_str(), t, eV, eC, eT, ns);
                        worstV[m] = std::max(worstV[m], eV);
                        worstC[m] = std::max(worstC[m], eC);
                        sumNs[m] += ns;
                    }
                    ++count;
                }
            std::fprintf(f, "%s,%zu,0,exact-queries,,0,0,0,%.0f\n", s.name.c_str(), s.mesh.triangleCount(), exactNs / count);
            md << "- Waves, `" << s.name << "` (" << s.mesh.triangleCount() << " triangles, exact-mesh, scaling sea, " << count
               << " poses × times): one exact query per vertex costs " << std::lround(exactNs / count / 1000.0)
               << " µs per hydrostatic evaluation;";
            for (int m : nodes) {
                char b[200];
                std::snprintf(b, sizeof b, " %d×%d patch: %.0f µs, worst volume error %.2g %%, CoB %.2g %%;", m, m,
                              sumNs[m] / count / 1000.0, worstV[m], worstC[m]);
                md << b;
            }
            md << " (errors against the exact-query clip at the same wave field, `waves_lod.csv`).\n";
            log << "  waves LOD " << s.name << " done\n";
        }
        std::fclose(f);
    }
    // ---- Waves: the exact-mesh water model against the same solid subdivided 64× --------------------------------
    // On waves the exact-mesh methods take the water over each triangle as the plane through its corners' heights
    // (ClippedHydrostatics.cpp): an error of O(curvature × triangle size²) that the comparisons against "exact
    // queries" above do not see. Reference: the 850-triangle boat subdivided three times (1:4 at edge midpoints, the
    // same solid, 54,400 triangles), clipped with one exact wave query per vertex. Rows: the boat at 1×, 4×, 16× with
    // exact queries, and the library's default evaluation (tree / per-vertex shares with the wave patch sized as the
    // action sizes it).
    if (!quick) {
        std::FILE* f = openCsv(outDir + "/waves_mesh.csv",
                               "shape,subdivisions,triangles,water,pose,volume_error_pct,cob_error_pct\n");
        const btGerstnerWaterSurface sea(p3Sea());
        TriangleMesh meshes[4];
        meshes[0] = loadBoatHull();
        for (int k = 1; k < 4; ++k) meshes[k] = subdivideMesh(meshes[k - 1]);
        std::shared_ptr<const btBuoyancyShape> shapes4[4];
        btBuoyancySettings st;
        st.method = btBuoyancyMethod::ExactMesh;
        for (int k = 0; k < 4; ++k) shapes4[k] = btBuoyancyShape::create(meshes[k], st);
        const double V = shapes4[0]->getVolume(), diag = boundingBoxDiagonal(meshes[0]);
        const int nodes = btBuoyancyWaterPatchNodes(btBuoyancySettings(), shapes4[0]->getBoundsRadius(), sea.shortestWavelength());
        double worst[3][2] = {{0, 0}, {0, 0}, {0, 0}}, worstDefault[3][2] = {{0, 0}, {0, 0}, {0, 0}};  // [1×,4×,16×][V, CoB]
        for (int p = 0; p < 24; ++p) {
            // Headings, heels, drafts and places in the sea; the boat's centre at the local water level ± 0.2 m.
            const double t = 1.7 * p, x = 13.1 * p, z = -7.7 * p;
            Eigen::Isometry3d pose = Eigen::Translation3d(x, sea.height(x, z, t) + 0.2 * std::sin(2.3 * p), z) *
                                     Eigen::AngleAxisd(0.7 * p, Eigen::Vector3d::UnitY()) *
                                     Eigen::AngleAxisd(0.25 * std::sin(1.3 * p), Eigen::Vector3d::UnitX());
            pose.translation() -= pose.linear() * shapes4[0]->getBoundsCentre();
            const Eigen::Vector3d ref = pose * shapes4[0]->getUnitSolid().centre;
            const HydrostaticsResult truth = clippedHydrostatics(meshes[3], pose, sea, t, kRho, kG, ref);
            if (!(truth.submerged_volume > 0.01 * V)) continue;
            char id[32];
            std::snprintf(id, sizeof id, "p%02d", p);
            for (int k = 0; k < 3; ++k) {
                const HydrostaticsResult exact = clippedHydrostatics(meshes[k], pose, sea, t, kRho, kG, ref);
                const Eigen::Vector3d bc = pose * shapes4[k]->getBoundsCentre();
                WaterPatch patch;
                btWaterQueryCache cache;
                patch.build(sea, bc.x(), bc.z(), shapes4[k]->getBoundsRadius(), t, nodes, cache);
                const HydrostaticsResult lib =
                    treeHydrostatics(shapes4[k]->getMomentTree(), meshes[k], pose, sea, t, kRho, kG, ref, &patch);
                const HydrostaticsResult* rs[2] = {&exact, &lib};
                for (int w = 0; w < 2; ++w) {
                    const double eV = 100.0 * std::abs(rs[w]->submerged_volume - truth.submerged_volume) / V;
                    const double eC = 100.0 * (rs[w]->centre_of_buoyancy - truth.centre_of_buoyancy).norm() / diag;
                    std::fprintf(f, "boat,%d,%zu,%s,%s,%.3g,%.3g\n", k, meshes[k].triangleCount(),
                                 w ? "default-patch" : "exact-queries", id, eV, eC);
                    double (&target)[3][2] = w ? worstDefault : worst;
                    target[k][0] = std::max(target[k][0], eV);
                    target[k][1] = std::max(target[k][1], eC);
                }
            }
        }
        std::fclose(f);
        char b[700];
        std::snprintf(b, sizeof b,
                      "- Waves, the exact-mesh water model (`waves_mesh.csv`; the boat against itself subdivided 64×, 54,400 "
                      "triangles, exact queries; scaling sea, 24 poses, worst volume / CoB error): exact queries per vertex — "
                      "850 triangles %.2g %% / %.2g %%, 3,400 %.2g %% / %.2g %%, 13,600 %.2g %% / %.2g %%; the default "
                      "evaluation (%d×%d patch) — %.2g %% / %.2g %%, %.2g %% / %.2g %%, %.2g %% / %.2g %%.\n",
                      worst[0][0], worst[0][1], worst[1][0], worst[1][1], worst[2][0], worst[2][1], nodes, nodes,
                      worstDefault[0][0], worstDefault[0][1], worstDefault[1][0], worstDefault[1][1], worstDefault[2][0],
                      worstDefault[2][1]);
        md << b;
        log << "  waves mesh model done\n";
    }
    // ---- Exact-mesh: the moment tree against clipping every triangle (design.md 2.5) ----------------------
    {
        std::FILE* f = openCsv(outDir + "/mesh_tree.csv",
                               "shape,triangles,water,pose,ns_clip_all,ns_tree,volume_difference_pct,cob_difference_pct,ns_vertex_shares,"
                               "vertex_difference_pct\n");
        const btGerstnerWaterSurface sea(p3Sea());
        const btFlatWaterSurface flat(0.0);
        md << "- Exact-mesh through the moment tree (`mesh_tree.csv`; one hydrostatic evaluation, the same poses as "
              "speed_vs_error in flat water and at 3 sea states of the scaling sea with the default 8×8 patch; mean time of "
              "clipping every triangle / the tree / the per-vertex shares, and the worst volume difference from clipping every "
              "triangle):";
        for (const BenchShape& s : shapes) {
            btBuoyancySettings st;
            st.method = btBuoyancyMethod::ExactMesh;
            const auto shape = btBuoyancyShape::create(s.mesh, st);
            const double V = shape->getVolume(), diag = boundingBoxDiagonal(s.mesh);
            const std::vector<BenchPose> poses = benchPoses(s.mesh, quick ? std::vector<double>{0.5} : std::vector<double>{0.1, 0.3, 0.5, 0.7, 0.9},
                                                            quick ? std::vector<double>{0} : std::vector<double>{0, 20, 45});
            double sum[2][3] = {{0, 0, 0}, {0, 0, 0}}, worst[2] = {0, 0}, worstVertex[2] = {0, 0};  // [flat, waves][clip, tree, vertex]
            int count[2] = {0, 0};
            int k = 0;
            for (const BenchPose& p : poses)
                for (int waves = 0; waves < 2; ++waves) {
                    Eigen::Isometry3d pose = p.pose;
                    const double t = 2.9 * (k % 3);
                    const double x = waves ? 5.3 * (k + 1) : 0.0, z = waves ? -3.7 * (k + 1) : 0.0;
                    if (waves) pose.pretranslate(Eigen::Vector3d(x, sea.height(x, z, t), z));
                    ++k;
                    const btWaterSurface& water = waves ? static_cast<const btWaterSurface&>(sea) : flat;
                    const Eigen::Vector3d ref = pose * shape->getUnitSolid().centre;
                    const Eigen::Vector3d bc = pose * shape->getBoundsCentre();
                    WaterPatch patch;
                    btWaterQueryCache cache;
                    if (waves) patch.build(sea, bc.x(), bc.z(), shape->getBoundsRadius(), t, 8, cache);
                    const WaterPatch* pp = waves ? &patch : nullptr;
                    HydrostaticsResult a, b, c;
                    const double nsClip = nsPerCall([&] { a = clippedHydrostatics(shape->getMesh(), pose, water, t, kRho, kG, ref, pp); }, quick ? 3 : 10);
                    const double nsTree = nsPerCall([&] {
                        b = treeHydrostatics(shape->getMomentTree(), shape->getMesh(), pose, water, t, kRho, kG, ref, pp);
                    }, quick ? 3 : 10);
                    const double nsVertex = nsPerCall([&] {
                        c = vertexHydrostatics(shape->getMomentTree().shares, pose, water, t, kRho, kG, ref, pp);
                    }, quick ? 3 : 10);
                    const double dV = 100.0 * std::abs(a.submerged_volume - b.submerged_volume) / V;
                    const double dVertex = 100.0 * std::abs(a.submerged_volume - c.submerged_volume) / V;
                    const double dC = a.submerged_volume > 1e-3 * V ? 100.0 * (a.centre_of_buoyancy - b.centre_of_buoyancy).norm() / diag : 0.0;
                    std::fprintf(f, "%s,%zu,%s,%s,%.0f,%.0f,%.3g,%.3g,%.0f,%.3g\n", s.name.c_str(), s.mesh.triangleCount(),
                                 waves ? "p3-sea-patch8" : "flat", p.id.c_str(), nsClip, nsTree, dV, dC, nsVertex, dVertex);
                    sum[waves][0] += nsClip;
                    sum[waves][1] += nsTree;
                    sum[waves][2] += nsVertex;
                    worst[waves] = std::max(worst[waves], dV);
                    worstVertex[waves] = std::max(worstVertex[waves], dVertex);
                    ++count[waves];
                }
            char b[400];
            std::snprintf(b, sizeof b, " `%s` (%zu triangles): flat %.1f / %.1f / %.1f µs (tree ≤ %.1g %%, shares ≤ %.1g %%), "
                          "waves %.1f / %.1f / %.1f µs (tree ≤ %.2g %%, shares ≤ %.1g %%);", s.name.c_str(), s.mesh.triangleCount(),
                          sum[0][0] / count[0] / 1000.0, sum[0][1] / count[0] / 1000.0, sum[0][2] / count[0] / 1000.0, worst[0],
                          worstVertex[0], sum[1][0] / count[1] / 1000.0, sum[1][1] / count[1] / 1000.0,
                          sum[1][2] / count[1] / 1000.0, worst[1], worstVertex[1]);
            md << b;
            log << "  mesh tree " << s.name << " done\n";
        }
        md << "\n";
        std::fclose(f);
    }
    // ---- Drag: clusters against every fine sample ------------------------------------------------------------
    {
        std::FILE* f = openCsv(outDir + "/drag_lod.csv",
                               "shape,triangles,clusters_max,clusters,fine_samples,pose,drag_force_error_pct,"
                               "drag_torque_error_pct,ns_per_body_substep\n");
        const std::vector<int> ks = quick ? std::vector<int>{0, 64} : std::vector<int>{0, 16, 32, 64, 128, 256};
        TimingOptions timing;
        if (quick) {
            timing.minBatchSeconds = 2e-4;
            timing.batches = 2;
        }
        md << "- Drag level of detail (flat water, v = (0.5, −0.3, 0.2) m/s, ω = (0.2, 0.1, −0.3) rad/s; error of the drag "
              "force against every fine drag sample, % of its magnitude, worst over 3 poses; `drag_lod.csv`):";
        for (const BenchShape& s : shapes) {
            const auto shape = btBuoyancyShape::create(s.mesh);
            const std::vector<BenchPose> poses = benchPoses(s.mesh, {0.3, 0.6, 0.9}, {0});
            std::map<int, std::pair<double, double>> fine;  // pose index → (|F|, |τ|) of K = 0
            std::vector<Eigen::Vector3d> fineF, fineT;
            md << " `" << s.name << "`:";
            for (int k : ks) {
                btBuoyancySettings st;
                st.dragClusters = k;
                st.hydrostaticsInterval = 1;  // every timed call computes the drag (no temporal prediction)
                SingleBodyRig rig(shape);
                btBuoyancyAction action(rig.body(), &rig.buoyancyWorld(), st);
                double worstF = 0, worstT = 0, ns = 0;
                for (std::size_t i = 0; i < poses.size(); ++i) {
                    const double t = rig.nsPerSubstep(action, poses[i].pose, timing);
                    ns += t;
                    const btBuoyancyResult& r = action.getLastResult();
                    const Eigen::Vector3d F(r.dragForce.x(), r.dragForce.y(), r.dragForce.z());
                    const Eigen::Vector3d T(r.dragTorque.x(), r.dragTorque.y(), r.dragTorque.z());
                    if (k == 0) {
                        fineF.push_back(F);
                        fineT.push_back(T);
                    }
                    const double eF = fineF[i].norm() > 0 ? 100.0 * (F - fineF[i]).norm() / fineF[i].norm() : 0.0;
                    const double eT = fineT[i].norm() > 0 ? 100.0 * (T - fineT[i]).norm() / fineT[i].norm() : 0.0;
                    worstF = std::max(worstF, eF);
                    worstT = std::max(worstT, eT);
                    std::fprintf(f, "%s,%zu,%d,%zu,%zu,%s,%.4g,%.4g,%.0f\n", s.name.c_str(), s.mesh.triangleCount(), k,
                                 action.getDragClusters().size(), shape->getDragSamples().size(), poses[i].id.c_str(), eF,
                                 eT, t);
                }
                char b[160];
                std::snprintf(b, sizeof b, " K=%d → %zu clusters %.1f µs, force %.2g %%, torque %.2g %%;", k,
                              action.getDragClusters().size(), ns / poses.size() / 1000.0, worstF, worstT);
                md << b;
            }
        }
        md << "\n";
        std::fclose(f);
    }
    return md.str();
}

}  // namespace buoyancy::bench
