#include "cli/SceneGraph.h"
#include "cli/SceneJsonReader.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace buoyancy::cli {

namespace {

using json = nlohmann::json;

using R = SceneJsonReader;

constexpr double kBig = 1e6;

void readGraph(const R& r, const json& g, const std::string& key, SceneFlooding& out) {
    r.requireObject(g, key);
    r.allowKeys(g, key, {"nodes", "edges", "seed", "auto", "ingress", "discharge_coefficient", "viscosity", "flow",
                    "diffusivity"});
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
    if (g.contains("discharge_coefficient"))
        graph.dischargeCoefficient = r.number(g["discharge_coefficient"], key + ".discharge_coefficient", 0, 1, true);
    if (g.contains("viscosity")) graph.viscosity = r.number(g["viscosity"], key + ".viscosity", 0, 1e6, true);
    if (g.contains("diffusivity")) graph.diffusivity = r.number(g["diffusivity"], key + ".diffusivity", 0, 1e6, true);

    if (g.contains("auto")) {
        if (g.contains("nodes") || g.contains("edges")) r.fail(key + ".auto", "give either \"auto\" or \"nodes\"/\"edges\", not both");
        const json& a = g["auto"];
        const std::string ak = key + ".auto";
        r.requireObject(a, ak);
        r.allowKeys(a, ak, {"nodes", "resolution", "fill"});
        out.automatic = true;
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

}  // namespace

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
            std::ifstream in(p);
            if (!in) fail(gk, "cannot read " + p.string());
            json file;
            try {
                in >> file;
            } catch (const json::exception& e) {
                fail(gk, p.string() + ": invalid JSON: " + e.what());
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
        r.allowKeys(p, pk, {"regions", "texture"});
        if (p.contains("texture"))
            fail(pk + ".texture", "permeability textures are not supported in this build (no image loader); use \"regions\"");
        if (!p.contains("regions")) fail(pk + ".regions", "missing (an array of {\"centre\", \"radius\", \"value\"})");
        if (!p["regions"].is_array()) fail(pk + ".regions", "expected an array");
        for (std::size_t i = 0; i < p["regions"].size(); ++i) {
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
    return out;
}

WaterGraph buildSceneWaterGraph(const SceneFlooding& flooding, const TriangleMesh& mesh) {
    if (!flooding.automatic) return flooding.graph;
    WaterGraph g = autoWaterGraph(mesh, flooding.autoSettings);
    g.ingress = flooding.graph.ingress;
    g.flow = flooding.graph.flow;
    g.dischargeCoefficient = flooding.graph.dischargeCoefficient;
    g.viscosity = flooding.graph.viscosity;
    g.diffusivity = flooding.graph.diffusivity;
    return g;
}

PermeableSamples buildScenePermeability(const SceneFlooding& flooding, const WaterGraph& graph,
                                        const SurfaceSamples& samples) {
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

}  // namespace buoyancy::cli
