#pragma once
/// @file WaterGraph.h
/// The water graph (paper section 4, design.md 4): nodes are the empty spaces inside a body that can
/// hold water (body-frame position, capacity, initial water), edges are the pipes between them (radius,
/// length, permeability). This file holds the plain data and its validation; the simulation is
/// WaterGraphState, the Bullet coupling btFloodingAction.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace buoyancy {

/// How a node's water level is modelled (the shape models the water level, not the hull's geometry).
enum class WaterNodeShape {
    Sphere, ///< a sphere of the node's capacity centred at its position (default)
    Box,    ///< a box of extents `size` (body axes) centred at its position
};

/// One compartment of the water graph.
struct WaterNode {
    std::string name;                                   ///< unique, non-empty
    Eigen::Vector3d position = Eigen::Vector3d::Zero(); ///< centre, body (mesh) frame, m
    double capacity = 0;                                ///< volume it can hold, m³, > 0
    double water = 0;                                   ///< initial water, m³, in [0, capacity]
    WaterNodeShape shape = WaterNodeShape::Sphere;      ///< level model
    Eigen::Vector3d size = Eigen::Vector3d::Zero();     ///< box extents, m (Box only, each > 0)
};

/// One pipe between two nodes.
struct WaterEdge {
    int from = -1;             ///< node index
    int to = -1;               ///< node index (≠ from)
    double radius = 0.05;      ///< pipe radius r, m, > 0
    double length = 1.0;       ///< pipe length L, m, > 0
    double permeability = 1.0; ///< open fraction in [0, 1] scaling the flow (0: closed)
};

/// How water enters through permeable samples.
enum class WaterIngressModel {
    Orifice, ///< Q = C_d a sqrt(2 g |Δh|) signed (design.md 4; default): drains out when the inside is higher
    Paper,   ///< the paper's section 4.2: permeability × the water column over the sample, per step (step-size dependent)
};

/// How water moves between nodes.
enum class WaterFlowModel {
    Poiseuille, ///< paper eq. 14 along the findDischargeNode path, capped by the orifice rate (default)
    Diffusion,  ///< Fick's law between neighbours on the fill fraction (soaking materials, plush toy)
};

/// How the water of each node contributes to the inertia (paper eq. 17 vs its shape).
enum class WaterInertiaModel {
    Shape,      ///< the rigid inertia of each node's water shape (sphere cap / clipped box) about its centroid,
                ///< plus the parallel-axis terms (default; NodeLevel nodeWaterInertia)
    PointMass,  ///< paper eq. 17: each node's water as a point mass at its centroid
};

/// A whole water graph with its simulation parameters.
struct WaterGraph {
    std::vector<WaterNode> nodes;  ///< at least one
    std::vector<WaterEdge> edges;  ///< undirected; at most one edge per node pair
    std::uint64_t seed = 1;        ///< seeds the random search order of findDischargeNode (reproducible runs)
    WaterIngressModel ingress = WaterIngressModel::Orifice; ///< see WaterIngressModel
    WaterFlowModel flow = WaterFlowModel::Poiseuille;       ///< see WaterFlowModel
    double dischargeCoefficient = 0.61; ///< C_d of orifices (sharp-edged hole ≈ 0.61), in (0, 1]
    double viscosity = 1.0e-3;          ///< dynamic viscosity μ, Pa·s (water at 20 °C: 1.0e-3), > 0
    double diffusivity = 1.0e-3;        ///< Diffusion mode: D, m²/s; flux D π r² Δc / L, > 0
    WaterInertiaModel inertia = WaterInertiaModel::Shape; ///< see WaterInertiaModel

    /// Index of the node called `name`, or -1.
    int findNode(const std::string& name) const;
    /// Total capacity, m³.
    double totalCapacity() const;
    /// @throws std::invalid_argument naming the bad field, e.g. "nodes[2].capacity: must be > 0"
    void validate() const;
};

}  // namespace buoyancy
