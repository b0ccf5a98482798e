// Property test (for the reliability soak): random valid water graphs with random
// ingress, random poses and random outside water never make a node negative or over its capacity, and
// conserve water (Σ nodes − initial = entered − drained). The invariants are the issue's own words; the
// graphs come from a seeded generator written here, so a failure names its case and replays.
#include <catch2/catch.hpp>

#include <BulletBuoyancy/graph/WaterGraph.h>
#include <BulletBuoyancy/graph/WaterGraphState.h>
#include <BulletBuoyancy/graph/WaterIngress.h>
#include <BulletBuoyancy/graph/WaterMassProperties.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <set>

using namespace buoyancy;

namespace {

/// A random valid graph: 1–8 nodes (spheres and boxes, capacities over 3 decades, random initial water),
/// a random spanning tree plus extra edges (pipes over 2 decades of radius), random parameters.
WaterGraph randomGraph(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    auto logU = [&](double lo, double hi) { return lo * std::pow(hi / lo, u(rng)); };
    WaterGraph g;
    const int n = 1 + int(rng() % 8);
    for (int i = 0; i < n; ++i) {
        WaterNode node;
        node.name = "n" + std::to_string(i);
        node.position = Eigen::Vector3d(u(rng) * 4 - 2, u(rng) * 2 - 1, u(rng) * 2 - 1);
        if (rng() % 3 == 0) {
            node.shape = WaterNodeShape::Box;
            node.size = Eigen::Vector3d(logU(0.05, 1.5), logU(0.05, 1.5), logU(0.05, 1.5));
            node.capacity = node.size.prod() * (rng() % 2 ? 1.0 : logU(0.2, 1.0));
        } else {
            node.capacity = logU(1e-3, 1.0);
        }
        const int fill = int(rng() % 4);  // empty, full, or partly
        node.water = fill == 0 ? 0.0 : fill == 1 ? node.capacity : u(rng) * node.capacity;
        g.nodes.push_back(node);
    }
    std::set<std::pair<int, int>> pairs;
    auto addEdge = [&](int a, int b) {
        if (a == b || !pairs.insert({std::min(a, b), std::max(a, b)}).second) return;
        WaterEdge e;
        e.from = a;
        e.to = b;
        e.radius = logU(0.002, 0.2);
        e.length = logU(0.05, 3.0);
        e.permeability = rng() % 5 == 0 ? 0.0 : u(rng);
        g.edges.push_back(e);
    };
    for (int i = 1; i < n; ++i) addEdge(i, int(rng() % std::uint64_t(i)));
    for (int k = int(rng() % 4); k > 0 && n > 1; --k) addEdge(int(rng() % n), int(rng() % n));
    g.seed = rng();
    g.ingress = rng() % 3 == 0 ? WaterIngressModel::Paper : WaterIngressModel::Orifice;
    g.flow = rng() % 3 == 0 ? WaterFlowModel::Diffusion : WaterFlowModel::Poiseuille;
    g.inertia = rng() % 2 ? WaterInertiaModel::Shape : WaterInertiaModel::PointMass;
    g.dischargeCoefficient = 0.3 + 0.7 * u(rng);
    g.viscosity = logU(1e-4, 1e-1);
    g.diffusivity = logU(1e-5, 1e-1);
    return g;
}

}  // namespace

TEST_CASE("random graphs with random ingress: no node negative or over capacity, water conserved", "[graph]") {
    std::mt19937_64 rng(20261122);
    std::uniform_real_distribution<double> u(0, 1);
    int violations = 0, nonFinite = 0;
    double worstConservation = 0, totalEntered = 0, totalDrained = 0;
    for (int c = 0; c < 200; ++c) {
        const WaterGraph g = randomGraph(rng);
        REQUIRE_NOTHROW(g.validate());
        WaterGraphState s(g);
        // Random holes: 0–12 points on a 2 m sphere around the body, each feeding a random node.
        PermeableSamples holes;
        const int nh = int(rng() % 13);
        for (int i = 0; i < nh; ++i) {
            const Eigen::Vector3d p = Eigen::Vector3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized() * 2.0;
            holes.px.push_back(p.x());
            holes.py.push_back(p.y());
            holes.pz.push_back(p.z());
            holes.openArea.push_back(std::pow(10.0, -4 + 3 * u(rng)));
            holes.node.push_back(int(rng() % g.nodes.size()));
        }
        IngressScratch scratch;
        std::vector<double> wy(holes.size()), f(holes.size());
        const double dt = std::pow(10.0, -3.5 + 2 * u(rng));  // 0.3 ms … 30 ms
        const Eigen::Vector3d axis = Eigen::Vector3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
        const double spin = 3 * u(rng), heave = 2 * u(rng), sea = 2 * u(rng) - 1;
        const double initial = s.totalWater();
        for (int step = 0; step < 150; ++step) {
            const double t = step * dt * 10;
            const Eigen::Isometry3d pose(Eigen::Translation3d(0, heave * std::sin(1.7 * t), 0) *
                                         Eigen::AngleAxisd(spin * t, axis));
            s.setPose(pose);
            for (std::size_t i = 0; i < holes.size(); ++i) {
                wy[i] = (pose * Eigen::Vector3d(holes.px[i], holes.py[i], holes.pz[i])).y();
                f[i] = sea + 0.5 * std::sin(2.3 * t + double(i));
            }
            applyIngress(s, holes, wy.data(), f.data(), dt, 9.81, scratch);
            s.flow(dt, 1000, 9.81);
            for (std::size_t k = 0; k < s.size(); ++k) {
                const double w = s.water(int(k));
                if (!std::isfinite(w)) ++nonFinite;
                else if (w < 0 || w > g.nodes[k].capacity) ++violations;
            }
            if (step % 50 == 49) {
                const MassProperties mp = waterMassProperties(s, 1000);
                if (!std::isfinite(mp.mass) || !mp.centre.allFinite() || !mp.inertia.allFinite()) ++nonFinite;
            }
        }
        const double expected = initial + s.enteredVolume() - s.drainedVolume();
        const double scale = std::max({g.totalCapacity(), s.enteredVolume(), s.drainedVolume()});
        worstConservation = std::max(worstConservation, std::abs(s.totalWater() - expected) / scale);
        totalEntered += s.enteredVolume();
        totalDrained += s.drainedVolume();
    }
    INFO("entered " << totalEntered << " m3, drained " << totalDrained << " m3 over all cases");
    CHECK(violations == 0);
    CHECK(nonFinite == 0);
    CHECK(worstConservation <= 1e-12);
    CHECK(totalEntered > 1.0);  // the cases really moved water both ways
    CHECK(totalDrained > 0.1);
}
