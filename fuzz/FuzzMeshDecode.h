#pragma once
/// @file FuzzMeshDecode.h
/// Turns fuzzer bytes into a triangle soup. Layout (all optional, missing bytes read as 0):
///   byte 0  header h: bits 0–5 vertex count − 1 (1..64); bit 6: per-corner UVs follow each triangle;
///           bit 7: coordinates are raw 8-byte doubles (NaN, Inf, huge, tiny) instead of the int8 grid
///   then    #V vertices: 3 × int8 (× 0.125 m: a coarse grid, so closed meshes and coincident vertices
///           are common) or 3 × double
///   then    triangles until the data ends: 3 × u8 vertex index (mod #V), then with bit 6 six u8 UV
///           coordinates (/255, so exactly 0 and 1 occur)
/// Vertex indices out of range cannot be produced (our loaders never make them either); everything else
/// (degenerate, open, non-manifold, inside-out, duplicated, NaN) can.
#include "FuzzContract.h"

#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace buoyancy::fuzz {

/// Sequential reader over the fuzzer's bytes.
class ByteReader {
public:
    ByteReader(const std::uint8_t* data, std::size_t size) : m_data(data), m_size(size) {}
    /// Next byte (0 past the end).
    std::uint8_t u8() { return m_pos < m_size ? m_data[m_pos++] : 0; }
    /// Next 8 bytes as a double (raw bit pattern).
    double f64() {
        std::uint64_t bits = 0;
        for (int k = 0; k < 8; ++k) bits |= std::uint64_t(u8()) << (8 * k);
        double d;
        std::memcpy(&d, &bits, sizeof d);
        return d;
    }
    /// Bytes not read yet.
    std::size_t remaining() const { return m_size - m_pos; }

private:
    const std::uint8_t* m_data;
    std::size_t m_size;
    std::size_t m_pos = 0;
};

/// Decode a soup as described in the file comment; at most maxTriangles triangles.
inline TriangleMesh decodeSoup(ByteReader& in, std::size_t maxTriangles = 4096) {
    TriangleMesh mesh;
    const std::uint8_t h = in.u8();
    const int nv = 1 + (h & 0x3f);
    const bool uvs = (h & 0x40) != 0;
    const bool raw = (h & 0x80) != 0;
    for (int i = 0; i < nv; ++i) {
        Eigen::Vector3d p;
        for (int k = 0; k < 3; ++k) p[k] = raw ? in.f64() : 0.125 * double(std::int8_t(in.u8()));
        mesh.vertices.push_back(p);
    }
    const std::size_t record = uvs ? 9 : 3;
    while (in.remaining() >= record && mesh.triangles.size() < maxTriangles) {
        Eigen::Vector3i t;
        for (int k = 0; k < 3; ++k) t[k] = in.u8() % nv;
        mesh.triangles.push_back(t);
        if (uvs)
            for (int k = 0; k < 3; ++k) {
                const double u = in.u8() / 255.0;
                const double v = in.u8() / 255.0;
                mesh.corner_uvs.emplace_back(u, v);
            }
    }
    return mesh;
}

/// The preamble of the mesh targets: decode a soup (at most maxTriangles) and run prepareMesh on it.
/// @return false when prepareMesh rejected it with a MeshError (the expected end of bad input); true with
/// `mesh` repaired and checked otherwise
inline bool decodePreparedSoup(ByteReader& in, std::size_t maxTriangles, TriangleMesh& mesh) {
    mesh = decodeSoup(in, maxTriangles);
    try {
        prepareMesh(mesh, "fuzz.obj");
    } catch (const MeshError&) {
        return false;
    }
    return true;
}

}  // namespace buoyancy::fuzz
