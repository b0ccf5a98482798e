#pragma once
/// @file btBuoyancyState.h
/// Save and restore (docs/integration.md "Save and restore"): the bytes that btBuoyancyWorld::saveState,
/// btBuoyancyAction::saveState, btFloodingAction::saveState, btTimeVaryingMassAction::saveState,
/// btBuoyantBody::saveState, btInteractiveWaterCoupler::saveState, btBuoyancyImmediate::saveState and
/// btBuoyancyMultiBodyAction::saveState write, and their restoreState functions read back,
/// so that a replay or a rollback goes on bit-identically.
///
/// The format (every number little-endian; a header with the magic "BBST", the format version, the precision byte,
/// the kind and the payload size; the payload; its checksum) is the core's (state/StateBlob.h): btBuoyancyStateWriter
/// and btBuoyancyStateReader are buoyancy::StateWriter and buoyancy::StateReader with this layer's kinds
/// (btBuoyancyStateKind) and precision byte, sizeof(btScalar) (4 float, 8 double). A blob is read whole and checked
/// (magic, version, precision, kind, sizes, checksum, and the object's own sizes: sample, drag cluster and water-graph
/// node counts) before anything is changed: a bad blob throws std::invalid_argument with a message naming the problem,
/// and leaves the object as it was. A newer format version is refused (no migration yet); a blob made by a build of
/// the other precision is refused (its btScalar numbers, stored as doubles, are not this build's: a float build's run
/// would not continue a double build's bit for bit).

#include <BulletBuoyancy/state/StateBlob.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

/// The format version written by this library, and the only one it reads (buoyancy::kStateFormatVersion).
constexpr std::uint16_t btBuoyancyStateFormatVersion = buoyancy::kStateFormatVersion;

/// What a state blob belongs to (the header's kind byte).
enum class btBuoyancyStateKind : std::uint8_t {
    World = 1,           ///< btBuoyancyWorld::saveState
    Action = 2,          ///< btBuoyancyAction::saveState
    Flooding = 3,        ///< btFloodingAction::saveState
    TimeVaryingMass = 4, ///< btTimeVaryingMassAction::saveState
    BuoyantBody = 5,     ///< btBuoyantBody::saveState
    InteractiveWater = 6, ///< btInteractiveWaterCoupler::saveState (the grid and the footprints)
    Immediate = 7,       ///< btBuoyancyImmediate::saveState (its context's and its evaluation's blobs inside)
    MultiBodyAction = 8, ///< btBuoyancyMultiBodyAction::saveState (each part's btBuoyancyImmediate blob inside)
};

/// Name of a kind for messages, e.g. "btBuoyancyAction"; "unknown" for other values.
const char* btBuoyancyStateKindName(btBuoyancyStateKind kind);

/// Writes one state blob of this layer (used by the classes' saveState): a buoyancy::StateWriter whose header holds
/// `kind` and this build's precision, sizeof(btScalar). Values are appended to the payload; bytes() adds the header
/// and the checksum.
class btBuoyancyStateWriter : public buoyancy::StateWriter {
public:
    /// @param kind  what the blob is
    explicit btBuoyancyStateWriter(btBuoyancyStateKind kind);
};

/// Reads one state blob of this layer (used by the classes' restoreState): a buoyancy::StateReader that expects
/// `kind` and this build's precision, sizeof(btScalar), and names kinds by btBuoyancyStateKindName. Every failure
/// throws std::invalid_argument whose message begins with `what` (e.g. "btBuoyancyAction::restoreState").
class btBuoyancyStateReader : public buoyancy::StateReader {
public:
    /// @param data, size  the blob
    /// @param kind        the kind expected
    /// @param what        the function reading, for messages
    /// @throws std::invalid_argument for a null or truncated blob, a wrong magic, format version, precision or kind,
    ///         a payload size that does not match the blob's, or a wrong checksum
    btBuoyancyStateReader(const unsigned char* data, std::size_t size, btBuoyancyStateKind kind, std::string what);
};
