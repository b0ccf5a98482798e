#pragma once
/// @file StateBlob.h
/// The byte format of a saved state (docs/integration.md "Save and restore"): what the library's saveState
/// functions write and their restoreState functions read back, so that a replay or a rollback goes on
/// bit-identically. The format knows nothing of Bullet: the layer that writes a blob
/// gives its kind (what the blob belongs to) and its precision byte (the size of the layer's floating-point scalar);
/// the Bullet layer's btBuoyancyStateWriter and btBuoyancyStateReader (bullet/btBuoyancyState.h) pass its
/// btBuoyancyStateKind and sizeof(btScalar).
///
/// Format (every integer little-endian, every floating-point number its IEEE bits, little-endian):
///   magic "BBST" (4 bytes) · format version (u16, kStateFormatVersion) · precision: the writer's scalar size in bytes
///   (u8: 4 float, 8 double) · kind (u8) · payload size in bytes (u64) · payload · FNV-1a 64 of the payload (u64).
/// A blob is read whole and checked (magic, version, precision, kind, sizes, checksum) before anything is changed: a
/// bad blob throws std::invalid_argument with a message naming the problem. A newer format version is refused (no
/// migration yet); a blob of another precision is refused (its scalars, stored as doubles, are not this build's: a
/// float build's run would not continue a double build's bit for bit).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace buoyancy {

/// The format version written by this library, and the only one it reads.
constexpr std::uint16_t kStateFormatVersion = 1;

/// How the layer reading a blob names what blobs hold, for the reader's messages.
struct StateNames {
    /// The name of a kind, e.g. "btBuoyancyAction" (null: a kind is named by its number).
    const char* (*kind)(std::uint8_t kind) = nullptr;
    /// The name of the scalar type whose size is the precision byte, e.g. "btScalar".
    const char* scalar = "scalar";
};

/// Writes one state blob (used by the classes' saveState). Values are appended to the payload; bytes() adds the
/// header and the checksum.
class StateWriter {
public:
    /// @param kind            what the blob is (the writing layer's numbering)
    /// @param precisionBytes  the writing layer's scalar size in bytes (4 float, 8 double): the header's precision
    StateWriter(std::uint8_t kind, std::uint8_t precisionBytes) : m_kind(kind), m_precisionBytes(precisionBytes) {}
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
    std::uint8_t m_kind;
    std::uint8_t m_precisionBytes;
    std::vector<unsigned char> m_payload;
};

/// Reads one state blob (used by the classes' restoreState). The constructor checks the header, the sizes and the
/// checksum; each read checks that the payload holds it. Every failure throws std::invalid_argument whose message
/// begins with `what` (e.g. "btBuoyancyAction::restoreState").
class StateReader {
public:
    /// @param data, size      the blob
    /// @param kind            the kind expected (the writing layer's numbering)
    /// @param precisionBytes  this build's scalar size in bytes (4 float, 8 double): the precision expected
    /// @param what            the function reading, for messages
    /// @param names           how kinds and the scalar are named in messages
    /// @throws std::invalid_argument for a null or truncated blob, a wrong magic, format version, precision or kind,
    ///         a payload size that does not match the blob's, or a wrong checksum
    StateReader(const unsigned char* data, std::size_t size, std::uint8_t kind, std::uint8_t precisionBytes,
                std::string what, const StateNames& names = StateNames());
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
    /// StateWriter::blob (checked by whoever reads it).
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

}  // namespace buoyancy
