#include <BulletBuoyancy/graph/WaterGraph.h>

#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace buoyancy {

namespace {

[[noreturn]] void fail(const std::string& field, const std::string& what) {
    throw std::invalid_argument(field + ": " + what);
}

std::string num(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
}

}  // namespace

int WaterGraph::findNode(const std::string& name) const {
    for (std::size_t i = 0; i < nodes.size(); ++i)
        if (nodes[i].name == name) return int(i);
    return -1;
}

double WaterGraph::totalCapacity() const {
    double c = 0;
    for (const WaterNode& n : nodes) c += n.capacity;
    return c;
}

void WaterGraph::validate() const {
    if (nodes.empty()) fail("nodes", "a water graph needs at least one node");
    std::set<std::string> names;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const WaterNode& n = nodes[i];
        const std::string key = "nodes[" + std::to_string(i) + "]";
        if (n.name.empty()) fail(key + ".name", "must not be empty");
        if (!names.insert(n.name).second) fail(key + ".name", "duplicate node name \"" + n.name + "\"");
        if (!n.position.allFinite()) fail(key + ".position", "must be finite");
        if (!std::isfinite(n.capacity) || !(n.capacity > 0))
            fail(key + ".capacity", "must be a finite number > 0 (got " + num(n.capacity) + ")");
        if (!std::isfinite(n.water) || n.water < 0 || n.water > n.capacity)
            fail(key + ".water", "must be in [0, capacity = " + num(n.capacity) + "] (got " + num(n.water) + ")");
        if (n.shape == WaterNodeShape::Box) {
            if (!n.size.allFinite() || !(n.size.minCoeff() > 0)) fail(key + ".size", "must be 3 finite numbers > 0");
        } else if (n.shape != WaterNodeShape::Sphere) {
            fail(key + ".shape", "not a WaterNodeShape value");
        }
    }
    std::set<std::pair<int, int>> pairs;
    for (std::size_t i = 0; i < edges.size(); ++i) {
        const WaterEdge& e = edges[i];
        const std::string key = "edges[" + std::to_string(i) + "]";
        const int n = int(nodes.size());
        if (e.from < 0 || e.from >= n) fail(key + ".from", "no such node (index " + std::to_string(e.from) + ")");
        if (e.to < 0 || e.to >= n) fail(key + ".to", "no such node (index " + std::to_string(e.to) + ")");
        if (e.from == e.to) fail(key, "connects node \"" + nodes[e.from].name + "\" to itself");
        if (!pairs.insert({std::min(e.from, e.to), std::max(e.from, e.to)}).second)
            fail(key, "a second edge between \"" + nodes[e.from].name + "\" and \"" + nodes[e.to].name + "\"");
        if (!std::isfinite(e.radius) || !(e.radius > 0)) fail(key + ".radius", "must be a finite number > 0");
        if (!std::isfinite(e.length) || !(e.length > 0)) fail(key + ".length", "must be a finite number > 0");
        if (!std::isfinite(e.permeability) || e.permeability < 0 || e.permeability > 1)
            fail(key + ".permeability", "must be in [0, 1] (got " + num(e.permeability) + ")");
    }
    if (ingress != WaterIngressModel::Orifice && ingress != WaterIngressModel::Paper)
        fail("ingress", "not a WaterIngressModel value");
    if (flow != WaterFlowModel::Poiseuille && flow != WaterFlowModel::Diffusion)
        fail("flow", "not a WaterFlowModel value");
    if (!std::isfinite(dischargeCoefficient) || !(dischargeCoefficient > 0) || dischargeCoefficient > 1)
        fail("discharge_coefficient", "must be in (0, 1] (got " + num(dischargeCoefficient) + ")");
    if (!std::isfinite(viscosity) || !(viscosity > 0)) fail("viscosity", "must be a finite number > 0");
    if (!std::isfinite(diffusivity) || !(diffusivity > 0)) fail("diffusivity", "must be a finite number > 0");
}

}  // namespace buoyancy
