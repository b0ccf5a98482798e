#include "scene/SceneGraph.h"
#include "scene/SceneJsonReader.h"

#ifdef BULLET_BUOYANCY_HAS_CGAL
#include <BulletBuoyancy/graph/cgal/SdfWaterGraph.h>
#endif

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <tuple>

namespace buoyancy::cli {

namespace {

using json = nlohmann::json;

using R = SceneJsonReader;

constexpr double kBig = 1e6;

void readGraph(const R& r, const json& g, const std::string& key, SceneFlooding& out) {
    r.requireObject(g, key);
    r.allowKeys(g, key, {"nodes", "edges", "seed", "auto", "ingress", "discharge_coefficient", "viscosity", "flow",
                    "diffusivity", "water_inertia"});
    WaterGraph& graph = out.graph;
    if (g.contains("seed")) graph.seed = std::uint64_t(r.integer(g["seed"], key + ".seed", 0, 2147483647));
    if (g.contains("ingress")) {
        const std::string v = r.string(g["ingress"], key + ".ingress");
        if (v == "orifice") graph.ingress = WaterIngressModel::Orifice;
        else if (v == "paper") graph.ingress = WaterIngressModel::Paper;
        else r.fail(key + ".ingress", "unknown value \"" + v + "\" (orifice or paper)");
    }
    if (g.contains("flow")) {
        const std::string v = r.string(g["flow"], key + ".flow");
        if (v == "poiseuille") graph.flow = WaterFlowModel::Poiseuille;
        else if (v == "diffusion") graph.flow = WaterFlowModel::Diffusion;
        else r.fail(key + ".flow", "unknown value \"" + v + "\" (poiseuille or diffusion)");
    }
    if (g.contains("water_inertia")) {
        const std::string v = r.string(g["water_inertia"], key + ".water_inertia");
        if (v == "shape") graph.inertia = WaterInertiaModel::Shape;
        else if (v == "points") graph.inertia = WaterInertiaModel::PointMass;
        else r.fail(key + ".water_inertia", "unknown value \"" + v + "\" (shape or points)");
    }
    if (g.contains("discharge_coefficient"))
        graph.dischargeCoefficient = r.number(g["discharge_coefficient"], key + ".discharge_coefficient", 0, 1, true);
    if (g.contains("viscosity")) graph.viscosity = r.number(g["viscosity"], key + ".viscosity", 0, 1e6, true);
    if (g.contains("diffusivity")) graph.diffusivity = r.number(g["diffusivity"], key + ".diffusivity", 0, 1e6, true);

    if (g.contains("auto")) {
        if (g.contains("nodes") || g.contains("edges")) r.fail(key + ".auto", "give either \"auto\" or \"nodes\"/\"edges\", not both");
        const json& a = g["auto"];
        const std::string ak = key + ".auto";
        r.requireObject(a, ak);
        r.allowKeys(a, ak, {"nodes", "resolution", "fill", "method"});
        out.automatic = true;
        if (a.contains("method")) {
            const std::string v = r.string(a["method"], ak + ".method");
            if (v == "sdf") {
#ifdef BULLET_BUOYANCY_HAS_CGAL
                out.sdf = true;
                if (a.contains("nodes")) r.integer(a["nodes"], ak + ".nodes", 1, 64);  // SDF clusters: 1..64
#else
                r.fail(ak + ".method", "\"sdf\" needs CGAL: built without CGAL (BULLET_BUOYANCY_CGAL=OFF)");
#endif
            } else if (v != "voxels") {
                r.fail(ak + ".method", "unknown value \"" + v + "\" (voxels or sdf)");
            }
        }
        if (a.contains("nodes")) out.autoSettings.nodes = r.integer(a["nodes"], ak + ".nodes", 1, 256);
        if (a.contains("resolution")) out.autoSettings.resolution = r.integer(a["resolution"], ak + ".resolution", 4, 256);
        if (a.contains("fill")) out.autoSettings.fill = r.number(a["fill"], ak + ".fill", 0, 1, true);
        out.autoSettings.seed = graph.seed;
        return;
    }
    if (!g.contains("nodes")) r.fail(key + ".nodes", "missing (an array of nodes, or give \"auto\")");
    if (!g["nodes"].is_array() || g["nodes"].empty()) r.fail(key + ".nodes", "expected a non-empty array");
    for (std::size_t i = 0; i < g["nodes"].size(); ++i) {
        const json& n = g["nodes"][i];
        const std::string nk = key + ".nodes[" + std::to_string(i) + "]";
        r.requireObject(n, nk);
        r.allowKeys(n, nk, {"name", "position", "capacity", "water", "size"});
        WaterNode node;
        if (!n.contains("name")) r.fail(nk + ".name", "missing");
        node.name = r.string(n["name"], nk + ".name");
        if (node.name.empty()) r.fail(nk + ".name", "must not be empty");
        if (graph.findNode(node.name) >= 0) r.fail(nk + ".name", "duplicate node name \"" + node.name + "\"");
        if (n.contains("position")) node.position = r.vec3(n["position"], nk + ".position", -kBig, kBig);
        if (n.contains("size")) {
            node.shape = WaterNodeShape::Box;
            node.size = r.vec3(n["size"], nk + ".size", 0, kBig, true);
        }
        if (n.contains("capacity")) node.capacity = r.number(n["capacity"], nk + ".capacity", 0, 1e12, true);
        else if (node.shape == WaterNodeShape::Box) node.capacity = node.size.prod();
        else r.fail(nk + ".capacity", "missing (m^3; optional only with \"size\")");
        if (n.contains("water")) node.water = r.number(n["water"], nk + ".water", 0, node.capacity);
        graph.nodes.push_back(node);
    }
    if (g.contains("edges")) {
        if (!g["edges"].is_array()) r.fail(key + ".edges", "expected an array");
        std::set<std::pair<int, int>> pairs;
        for (std::size_t i = 0; i < g["edges"].size(); ++i) {
            const json& e = g["edges"][i];
            const std::string ek = key + ".edges[" + std::to_string(i) + "]";
            r.requireObject(e, ek);
            r.allowKeys(e, ek, {"from", "to", "radius", "length", "permeability"});
            WaterEdge edge;
            for (const char* end : {"from", "to"}) {
                if (!e.contains(end)) r.fail(ek + "." + end, "missing (a node name)");
                const std::string name = r.string(e[end], ek + "." + end);
                const int idx = graph.findNode(name);
                if (idx < 0) r.fail(ek + "." + end, "no node named \"" + name + "\"");
                (std::string(end) == "from" ? edge.from : edge.to) = idx;
            }
            if (edge.from == edge.to) r.fail(ek, "connects a node to itself");
            if (!pairs.insert({std::min(edge.from, edge.to), std::max(edge.from, edge.to)}).second)
                r.fail(ek, "a second edge between the same two nodes");
            if (e.contains("radius")) edge.radius = r.number(e["radius"], ek + ".radius", 0, kBig, true);
            if (e.contains("length")) edge.length = r.number(e["length"], ek + ".length", 0, kBig, true);
            else edge.length = std::max(1e-3, (graph.nodes[std::size_t(edge.from)].position -
                                               graph.nodes[std::size_t(edge.to)].position).norm());
            if (e.contains("permeability")) edge.permeability = r.number(e["permeability"], ek + ".permeability", 0, 1);
            graph.edges.push_back(edge);
        }
    }
    try {
        graph.validate();
    } catch (const std::invalid_argument& ex) {
        r.fail(key, ex.what());
    }
}

SceneDensityMap readDensityMap(const R& r, const json& j, const std::string& key) {
    r.requireObject(j, key);
    r.allowKeys(j, key, {"base", "spots", "rotation", "update_interval"});
    SceneDensityMap m;
    m.enabled = true;
    if (j.contains("base")) m.base = r.number(j["base"], key + ".base", 0, kBig);
    if (j.contains("spots")) {
        if (!j["spots"].is_array()) r.fail(key + ".spots", "expected an array of {\"direction\", \"angle\", \"value\"}");
        for (std::size_t i = 0; i < j["spots"].size(); ++i) {
            const json& sj = j["spots"][i];
            const std::string sk = key + ".spots[" + std::to_string(i) + "]";
            r.requireObject(sj, sk);
            r.allowKeys(sj, sk, {"direction", "angle", "value"});
            SceneDensitySpot spot;
            if (!sj.contains("direction")) r.fail(sk + ".direction", "missing");
            spot.direction = r.vec3(sj["direction"], sk + ".direction", -kBig, kBig);
            if (!(spot.direction.norm() > 1e-12)) r.fail(sk + ".direction", "zero direction");
            spot.direction.normalize();
            if (sj.contains("angle")) spot.angleDegrees = r.number(sj["angle"], sk + ".angle", 0, 180, true);
            if (!sj.contains("value")) r.fail(sk + ".value", "missing (relative areal density, >= 0)");
            spot.value = r.number(sj["value"], sk + ".value", 0, kBig);
            m.spots.push_back(spot);
        }
    }
    if (j.contains("rotation")) {
        const json& rj = j["rotation"];
        const std::string rk = key + ".rotation";
        r.requireObject(rj, rk);
        r.allowKeys(rj, rk, {"axis", "degrees_per_second"});
        if (rj.contains("axis")) m.rotationAxis = r.vec3(rj["axis"], rk + ".axis", -kBig, kBig);
        if (!(m.rotationAxis.norm() > 1e-12)) r.fail(rk + ".axis", "zero axis");
        m.rotationAxis.normalize();
        if (rj.contains("degrees_per_second"))
            m.degreesPerSecond = r.number(rj["degrees_per_second"], rk + ".degrees_per_second", -1e6, 1e6);
    }
    if (j.contains("update_interval"))
        m.updateInterval = r.number(j["update_interval"], key + ".update_interval", 0, 1e6, true);
    bool positive = m.base > 0;
    for (const SceneDensitySpot& s : m.spots) positive = positive || s.value > 0;
    if (!positive) r.fail(key, "the map is zero everywhere (give \"base\" > 0 or a spot with \"value\" > 0)");
    return m;
}

}  // namespace

std::int64_t SceneDensityMap::version(double t) const {
    if (degreesPerSecond == 0) return 0;
    const double k = std::floor(t / updateInterval + 1e-9);
    return std::isfinite(k) ? std::int64_t(std::clamp(k, -9e15, 9e15)) : 0;
}

double SceneDensityMap::density(double t, const Eigen::Vector3d& p, const Eigen::Vector3d& centre) const {
    const Eigen::Vector3d d = p - centre;
    const double n = d.norm();
    if (!(n > 0) || spots.empty()) return base;
    // The map of step k = version(t) is the one at time k·interval (piecewise constant in time).
    const double angle = double(version(t)) * updateInterval * degreesPerSecond * 3.14159265358979323846 / 180.0;
    const Eigen::AngleAxisd rot(angle, rotationAxis);
    double sigma = base;
    bool inSpot = false;
    for (const SceneDensitySpot& s : spots) {
        const double c = std::clamp(d.dot(rot * s.direction) / n, -1.0, 1.0);
        if (std::acos(c) <= s.angleDegrees * 3.14159265358979323846 / 180.0) {
            sigma = inSpot ? std::max(sigma, s.value) : s.value;
            inSpot = true;
        }
    }
    return sigma;
}

SceneFlooding readSceneFlooding(const json& body, const std::string& key, const std::string& directory,
                                const SceneFailFn& fail) {
    const R r{fail};
    SceneFlooding out;
    if (body.contains("water_graph")) {
        const std::string gk = key + ".water_graph";
        const json& g = body["water_graph"];
        out.enabled = true;
        if (g.is_string()) {
            std::filesystem::path p(g.get<std::string>());
            if (p.is_relative()) p = std::filesystem::path(directory) / p;
            // A directory opens as a stream but throws std::ios_base::failure on the first read (found by fuzzing).
            std::error_code ec;
            if (!std::filesystem::is_regular_file(p, ec)) fail(gk, "cannot read " + p.string() + " (not a file)");
            std::ifstream in(p);
            if (!in) fail(gk, "cannot read " + p.string());
            json file;
            try {
                in >> file;
            } catch (const json::exception& e) {
                fail(gk, p.string() + ": invalid JSON: " + e.what());
            } catch (const std::ios_base::failure& e) {
                fail(gk, "cannot read " + p.string() + ": " + e.what());
            }
            readGraph(r, file, gk + " (" + p.filename().string() + ")", out);
        } else {
            readGraph(r, g, gk, out);
        }
    }
    if (body.contains("permeability")) {
        const std::string pk = key + ".permeability";
        if (!out.enabled) fail(pk, "needs a \"water_graph\" (where would the water go?)");
        const json& p = body["permeability"];
        r.requireObject(p, pk);
        r.allowKeys(p, pk, {"regions", "texture", "filter"});
        if (p.contains("texture")) {
            const std::string tk = pk + ".texture";
            const std::string name = r.string(p["texture"], tk);
            if (name.empty()) fail(tk, "must not be empty (an image file, relative to the scene file)");
            std::filesystem::path path(name);
            if (path.is_relative()) path = std::filesystem::path(directory) / path;
            out.texturePath = path.string();
            try {
                out.texture = loadPermeabilityImage(out.texturePath);
            } catch (const std::invalid_argument& e) {
                fail(tk, e.what());
            }
            out.hasTexture = true;
        }
        if (p.contains("filter")) {
            const std::string v = r.string(p["filter"], pk + ".filter");
            if (v == "bilinear") out.textureFilter = TextureFilter::Bilinear;
            else if (v == "nearest") out.textureFilter = TextureFilter::Nearest;
            else fail(pk + ".filter", "unknown value \"" + v + "\" (bilinear or nearest)");
            if (!out.hasTexture) fail(pk + ".filter", "only with \"texture\"");
        }
        if (!p.contains("regions") && !out.hasTexture)
            fail(pk + ".regions", "missing (an array of {\"centre\", \"radius\", \"value\"}, or give \"texture\")");
        if (p.contains("regions") && !p["regions"].is_array()) fail(pk + ".regions", "expected an array");
        for (std::size_t i = 0; p.contains("regions") && i < p["regions"].size(); ++i) {
            const json& g = p["regions"][i];
            const std::string rk = pk + ".regions[" + std::to_string(i) + "]";
            r.requireObject(g, rk);
            r.allowKeys(g, rk, {"centre", "radius", "value", "node"});
            PermeabilityRegion region;
            if (!g.contains("centre")) fail(rk + ".centre", "missing");
            if (!g.contains("radius")) fail(rk + ".radius", "missing");
            region.centre = r.vec3(g["centre"], rk + ".centre", -kBig, kBig);
            region.radius = r.number(g["radius"], rk + ".radius", 0, kBig, true);
            region.value = g.contains("value") ? r.number(g["value"], rk + ".value", 0, 1) : 1.0;
            std::string node;
            if (g.contains("node")) {
                node = r.string(g["node"], rk + ".node");
                if (!out.automatic && out.graph.findNode(node) < 0) fail(rk + ".node", "no node named \"" + node + "\"");
            }
            out.regions.push_back(region);
            out.regionNodes.push_back(node);
        }
    }
    if (body.contains("density_map")) out.densityMap = readDensityMap(r, body["density_map"], key + ".density_map");
    return out;
}

WaterGraph buildSceneWaterGraph(const SceneFlooding& flooding, const TriangleMesh& mesh) {
    if (!flooding.automatic) return flooding.graph;
#ifdef BULLET_BUOYANCY_HAS_CGAL
    WaterGraph g;
    if (flooding.sdf) {
        SdfWaterGraphSettings sdf;  // the paper's method: k SDF clusters, voxels for the capacities
        sdf.nodes = flooding.autoSettings.nodes;
        sdf.resolution = flooding.autoSettings.resolution;
        sdf.fill = flooding.autoSettings.fill;
        sdf.seed = flooding.autoSettings.seed;
        g = sdfWaterGraph(mesh, sdf);
    } else {
        g = autoWaterGraph(mesh, flooding.autoSettings);
    }
#else
    WaterGraph g = autoWaterGraph(mesh, flooding.autoSettings);
#endif
    g.ingress = flooding.graph.ingress;
    g.flow = flooding.graph.flow;
    g.dischargeCoefficient = flooding.graph.dischargeCoefficient;
    g.viscosity = flooding.graph.viscosity;
    g.diffusivity = flooding.graph.diffusivity;
    return g;
}

PermeableSamples buildScenePermeability(const SceneFlooding& flooding, const WaterGraph& graph,
                                        const SurfaceSamples& samples, const TriangleMesh& mesh) {
    if (!flooding.hasTexture) return buildScenePermeability(flooding, graph, samples);
    // Texture (in the model's UVs, or the generated atlas at the image's larger side), then the regions on
    // top (overlaps take the largest value).
    PermeabilityMap map(samples, graph);
    const int atlasSize = std::max(flooding.texture.width, flooding.texture.height);
    PermeabilityUvs uvs;
    try {
        uvs = permeabilityUvs(mesh, atlasSize);
    } catch (const std::exception& e) {
        throw std::invalid_argument("permeability.texture: the model has no UVs and no atlas fits at " +
                                    std::to_string(atlasSize) + " texels (" + e.what() + ")");
    }
    map.paintImage(flooding.texture, surfaceSampleUvs(samples, mesh, uvs.corner_uvs), PermeabilityPaint::Set,
                   flooding.textureFilter);
    for (std::size_t i = 0; i < flooding.regions.size(); ++i) {
        const std::string& name = i < flooding.regionNodes.size() ? flooding.regionNodes[i] : std::string();
        int node = -1;
        if (!name.empty()) {
            node = graph.findNode(name);
            if (node < 0)
                throw std::invalid_argument("permeability.regions[" + std::to_string(i) + "].node: no node named \"" + name + "\"");
        }
        const PermeabilityRegion& g = flooding.regions[i];
        map.paintSphere(g.centre, g.radius, g.value, PermeabilityPaint::Max, node);
    }
    return map.permeableSamples();
}

PermeableSamples buildScenePermeability(const SceneFlooding& flooding, const WaterGraph& graph,
                                        const SurfaceSamples& samples) {
    if (flooding.hasTexture)
        throw std::invalid_argument("permeability.texture: needs the mesh (use the overload taking the mesh)");
    std::vector<PermeabilityRegion> regions = flooding.regions;
    for (std::size_t i = 0; i < regions.size(); ++i) {
        const std::string& name = i < flooding.regionNodes.size() ? flooding.regionNodes[i] : std::string();
        if (name.empty()) continue;
        regions[i].node = graph.findNode(name);
        if (regions[i].node < 0)
            throw std::invalid_argument("permeability.regions[" + std::to_string(i) + "].node: no node named \"" + name + "\"");
    }
    return permeableSamplesFromRegions(samples, regions, graph);
}

void addOpenTriangles(PermeableSamples& holes, const SurfaceSamples& samples, const WaterGraph& graph,
                      const std::vector<std::size_t>& triangles) {
    const std::set<std::size_t> open(triangles.begin(), triangles.end());
    std::set<std::tuple<double, double, double>> present;
    for (std::size_t k = 0; k < holes.size(); ++k) present.insert({holes.px[k], holes.py[k], holes.pz[k]});
    for (std::size_t i = 0; i < samples.size(); ++i) {
        if (!open.count(std::size_t(samples.triangle[i]))) continue;
        if (present.count({samples.px[i], samples.py[i], samples.pz[i]})) continue;
        holes.px.push_back(samples.px[i]);
        holes.py.push_back(samples.py[i]);
        holes.pz.push_back(samples.pz[i]);
        holes.openArea.push_back(samples.area[i]);
        holes.node.push_back(nearestWaterNode(graph, Eigen::Vector3d(samples.px[i], samples.py[i], samples.pz[i])));
    }
}

}  // namespace buoyancy::cli
