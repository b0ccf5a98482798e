#pragma once
/// @file DischargeSearch.h
/// findDischargeNode (the paper's Algorithm 1): a depth-first search from a source node for a node it can
/// send water to, through the water graph's edges in a seeded random order (reproducible runs,
/// design.md 4).
///
/// Rules (world heights, the body's current pose):
/// - energy barrier: a node whose bottom lies above the source's water level stops the search on that
///   path. For point-sized nodes this is the paper's "a node higher than the source"; with nodes of finite
///   size it lets a nearly full low node feed a higher neighbour whose bottom is under its level
///   (communicating vessels).
/// - discharge node: the first node ≠ source that is not full and whose level is below the source's
///   level (the paper: "not full"; the level condition avoids selecting a node the water cannot flow to
///   and keeps searching past it).
/// - the path keeps the smallest radius, the summed length and the smallest permeability of its edges
///   (Poiseuille's r, L and the paper's perm_min).

#include <BulletBuoyancy/graph/WaterGraph.h>

#include <cstdint>
#include <vector>

namespace buoyancy {

/// splitmix64 (Steele, Lea, Flood 2014): a tiny, portable, seeded generator; the same seed gives the
/// same sequence on every platform (std distributions do not).
class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed = 1) : m_state(seed) {}
    /// Next 64 random bits.
    std::uint64_t next() {
        std::uint64_t z = (m_state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform integer in [0, n), n > 0 (Lemire's multiply-shift; bias below 2⁻³² for small n).
    std::uint32_t below(std::uint32_t n) {
        return std::uint32_t((std::uint64_t(std::uint32_t(next() >> 32)) * n) >> 32);
    }
    /// Shuffle [first, first + n) (Fisher–Yates).
    template <class T>
    void shuffle(T* first, std::size_t n) {
        for (std::size_t i = n; i > 1; --i) {
            const std::size_t j = below(std::uint32_t(i));
            T tmp = first[i - 1];
            first[i - 1] = first[j];
            first[j] = tmp;
        }
    }

    /// The generator's state (save and restore: SplitMix64(state()) continues the same sequence).
    std::uint64_t state() const { return m_state; }

private:
    std::uint64_t m_state;
};

/// Result of one search.
struct DischargePath {
    int node = -1;             ///< discharge node, or -1 when the source cannot send water anywhere now
    double radius = 0;         ///< smallest edge radius on the path, m
    double length = 0;         ///< summed edge length, m
    double permeability = 0;   ///< smallest edge permeability on the path
};

/// Reusable search over one graph's topology (no allocation per search).
class DischargeSearch {
public:
    DischargeSearch() = default;
    /// Build the adjacency of `graph` (validated by the caller).
    explicit DischargeSearch(const WaterGraph& graph);

    /// Algorithm 1 from `source`.
    /// @param bottom  #nodes world height of each node's lowest point, m
    /// @param level   #nodes world height of each node's water level (its bottom when empty), m
    /// @param full    #nodes non-zero when the node is full
    /// @param rng     advanced to shuffle each visited node's edges
    DischargePath find(int source, const double* bottom, const double* level, const unsigned char* full,
                       SplitMix64& rng);
    /// The same search with the source's level given: the outside water pushing through a hole into
    /// full node `source` (its surface `sourceLevel` is the head; barriers and targets are judged against it).
    DischargePath find(int source, double sourceLevel, const double* bottom, const double* level,
                       const unsigned char* full, SplitMix64& rng);

private:
    bool visit(int current, const double* bottom, const double* level, const unsigned char* full, SplitMix64& rng,
               double radius, double length, double perm, DischargePath& out);

    std::vector<int> m_offset;      // CSR: edges of node i are m_adj[m_offset[i] .. m_offset[i+1])
    std::vector<int> m_adj;         // edge indices
    std::vector<int> m_other;       // neighbour node per CSR slot
    std::vector<int> m_order;       // scratch: shuffled CSR slots per node
    std::vector<unsigned char> m_visited;
    std::vector<WaterEdge> m_edges;
    int m_source = -1;
    double m_sourceLevel = 0;
};

}  // namespace buoyancy
