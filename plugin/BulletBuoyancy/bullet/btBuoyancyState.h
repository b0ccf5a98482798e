#pragma once
/// @file btBuoyancyState.h
/// Save and restore (docs/integration.md "Save and restore"): the bytes that btBuoyancyWorld::saveState,
/// btBuoyancyAction::saveState, btFloodingAction::saveState, btTimeVaryingMassAction::saveState,
/// btBuoyantBody::saveState, btInteractiveWaterCoupler::saveState, btBuoyancyImmediate::saveState and
/// btBuoyancyMultiBodyAction::saveState write, and their restoreState functions read back,
/// so that a replay or a rollback goes on bit-identically.
///
/// Format (every integer little-endian, every floating-point number its IEEE bits, little-endian):
///   magic "BBST" (4 bytes) · format version (u16, btBuoyancyStateFormatVersion) · btScalar size in bytes (u8: 4 float,
///   8 double) · kind (u8, btBuoyancyStateKind) · payload size in bytes (u64) · payload · FNV-1a 64 of the payload (u64).
/// A blob is read whole and checked (magic, version, precision, kind, sizes, checksum, and the object's own sizes: sample,
/// drag cluster and water-graph node counts) before anything is changed: a bad blob throws std::invalid_argument with
/// a message naming the problem, and leaves the object as it was. A newer format version is refused (no migration
/// yet); a blob made by a build of the other precision is refused (its btScalar numbers, stored as doubles, are not
/// this build's: a float build's run would not continue a double build's bit for bit).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

/// The format version written by this library, and the only one it reads.
constexpr std::uint16_t btBuoyancyStateFormatVersion = 1;

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

/// Writes one state blob (used by the classes' saveState). Values are appended to the payload; bytes() adds the
/// header and the checksum.
class btBuoyancyStateWriter {
public:
    /// @param kind  what the blob is
    explicit btBuoyancyStateWriter(btBuoyancyStateKind kind) : m_kind(kind) {}
    /// Append one byte.
    void u8(std::uint8_t v) { m_payload.push_back(v); }
    /// Append a boolean as one byte (0 or 1).
    void boolean(bool v) { u8(v ? 1 : 0); }
    /// Append a 32-bit unsigned integer.
    void u32(std::uint32_t v);
    /// Append a 32-bit signed integer.
    void i32(std::int32_t v) { u32(std::uint32_t(v)); }
    /// Append a 64-bit unsigned integer.
    void u64(std::uint64_t v);
    /// Append a 64-bit signed integer.
    void i64(std::int64_t v) { u64(std::uint64_t(v)); }
    /// Append a double (its bits).
    void f64(double v);
    /// Append a float (its bits).
    void f32(float v);
    /// Append `n` doubles.
    void f64s(const double* v, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) f64(v[i]);
    }
    /// Append a size (u64) then the doubles.
    void f64Vector(const std::vector<double>& v);
    /// Append a size (u64) then the bytes of another blob (a state made of others' states).
    void blob(const std::vector<unsigned char>& bytes);
    /// The complete blob: header, payload, checksum.
    std::vector<unsigned char> bytes() const;

private:
    btBuoyancyStateKind m_kind;
    std::vector<unsigned char> m_payload;
};

/// Reads one state blob (used by the classes' restoreState). The constructor checks the header, the sizes and the
/// checksum; each read checks that the payload holds it. Every failure throws std::invalid_argument whose message
/// begins with `what` (e.g. "btBuoyancyAction::restoreState").
class btBuoyancyStateReader {
public:
    /// @param data, size  the blob
    /// @param kind        the kind expected
    /// @param what        the function reading, for messages
    /// @throws std::invalid_argument for a null or truncated blob, a wrong magic, format version, precision or kind,
    ///         a payload size that does not match the blob's, or a wrong checksum
    btBuoyancyStateReader(const unsigned char* data, std::size_t size, btBuoyancyStateKind kind, std::string what);
    std::uint8_t u8(const char* field);            ///< one byte
    bool boolean(const char* field);               ///< a byte that must be 0 or 1
    std::uint32_t u32(const char* field);          ///< 32-bit unsigned
    std::int32_t i32(const char* field) { return std::int32_t(u32(field)); } ///< 32-bit signed
    std::uint64_t u64(const char* field);          ///< 64-bit unsigned
    std::int64_t i64(const char* field) { return std::int64_t(u64(field)); } ///< 64-bit signed
    double f64(const char* field);                 ///< a double
    float f32(const char* field);                  ///< a float
    /// `n` doubles into `out`.
    void f64s(double* out, std::size_t n, const char* field) {
        for (std::size_t i = 0; i < n; ++i) out[i] = f64(field);
    }
    /// A size (at most what the rest of the payload can hold) then that many doubles.
    std::vector<double> f64Vector(const char* field);
    /// A size (at most what the rest of the payload can hold) then that many bytes: a blob written by
    /// btBuoyancyStateWriter::blob (checked by whoever reads it).
    std::vector<unsigned char> blob(const char* field);
    /// A count read earlier must equal the object's: throws "<what>: <field> is <saved> in the blob, <expected> here".
    void expectCount(std::uint64_t saved, std::uint64_t expected, const char* field) const;
    /// Throw "<what>: <message>".
    [[noreturn]] void fail(const std::string& message) const;
    /// Bytes of the payload not read yet.
    std::size_t remaining() const { return m_end - m_pos; }
    /// Every byte of the payload must have been read. @throws std::invalid_argument otherwise
    void finish() const;

private:
    void need(std::size_t n, const char* field) const;
    const unsigned char* m_data = nullptr;
    std::size_t m_pos = 0, m_end = 0;
    std::string m_what;
};
