#include <BulletBuoyancy/state/StateBlob.h>

#include <cstring>
#include <stdexcept>

namespace buoyancy {
namespace {

constexpr unsigned char kMagic[4] = {'B', 'B', 'S', 'T'};
/// magic (4) + version (2) + precision (1) + kind (1) + payload size (8)
constexpr std::size_t kHeader = 16;
constexpr std::size_t kChecksum = 8;

/// FNV-1a, 64 bits (Fowler, Noll, Vo): detects a flipped or swapped byte of the payload.
std::uint64_t fnv1a(const unsigned char* p, std::size_t n) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (std::size_t i = 0; i < n; ++i) {
        h ^= p[i];
        h *= 0x100000001b3ull;
    }
    return h;
}

void putLe(std::vector<unsigned char>& out, std::uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}

std::uint64_t getLe(const unsigned char* p, int bytes) {
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= std::uint64_t(p[i]) << (8 * i);
    return v;
}

const char* precisionName(unsigned size) { return size == 8 ? "double" : size == 4 ? "float" : "unknown"; }

/// "a btBuoyancyAction state (kind 2)" with a name for the kind, else "a kind 2 state".
std::string kindPhrase(const StateNames& names, std::uint8_t kind, bool withNumber) {
    if (!names.kind) return "a kind " + std::to_string(kind) + " state";
    return std::string("a ") + names.kind(kind) + " state" +
           (withNumber ? " (kind " + std::to_string(kind) + ")" : std::string());
}

}  // namespace

// ---- writer ----
void StateWriter::u32(std::uint32_t v) { putLe(m_payload, v, 4); }
void StateWriter::u64(std::uint64_t v) { putLe(m_payload, v, 8); }
void StateWriter::f64(double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    u64(bits);
}
void StateWriter::f32(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    u32(bits);
}
void StateWriter::f64Vector(const std::vector<double>& v) {
    u64(v.size());
    f64s(v.data(), v.size());
}

void StateWriter::blob(const std::vector<unsigned char>& bytes) {
    u64(bytes.size());
    m_payload.insert(m_payload.end(), bytes.begin(), bytes.end());
}

std::vector<unsigned char> StateWriter::bytes() const {
    std::vector<unsigned char> out;
    out.reserve(kHeader + m_payload.size() + kChecksum);
    for (const unsigned char c : kMagic) out.push_back(c);
    putLe(out, kStateFormatVersion, 2);
    out.push_back(m_precisionBytes);
    out.push_back(m_kind);
    putLe(out, m_payload.size(), 8);
    out.insert(out.end(), m_payload.begin(), m_payload.end());
    putLe(out, fnv1a(m_payload.data(), m_payload.size()), 8);
    return out;
}

// ---- reader ----
StateReader::StateReader(const unsigned char* data, std::size_t size, std::uint8_t kind, std::uint8_t precisionBytes,
                         std::string what, const StateNames& names)
    : m_data(data), m_what(std::move(what)) {
    if (!data && size > 0) fail("the data pointer is null");
    if (size < 4 || std::memcmp(data, kMagic, 4) != 0) {
        if (size < 4 && (size == 0 || std::memcmp(data, kMagic, size) == 0))
            fail("truncated: " + std::to_string(size) + " bytes, a state blob has at least " +
                 std::to_string(kHeader + kChecksum));
        fail("not a buoyancy state blob (wrong magic: it does not begin with \"BBST\")");
    }
    if (size < kHeader)
        fail("truncated: " + std::to_string(size) + " bytes, a state blob has at least " +
             std::to_string(kHeader + kChecksum));
    const unsigned version = unsigned(getLe(data + 4, 2));
    if (version != kStateFormatVersion)
        fail("format version " + std::to_string(version) + ", this library reads version " +
             std::to_string(kStateFormatVersion) + " only");
    const unsigned scalar = data[6];
    if (scalar != precisionBytes)
        fail(std::string("saved by a ") + precisionName(scalar) + "-precision build (" + names.scalar + " of " +
             std::to_string(scalar) + " bytes), this build is " + precisionName(precisionBytes) + "-precision");
    const std::uint8_t saved = data[7];
    if (saved != kind)
        fail("the blob is " + kindPhrase(names, saved, true) + ", expected " + kindPhrase(names, kind, false));
    const std::uint64_t payload = getLe(data + 8, 8);
    if (payload > size - kHeader || size - kHeader - payload < kChecksum)
        fail("truncated: " + std::to_string(size) + " bytes, the header announces " +
             (payload > std::uint64_t(-1) - kHeader - kChecksum ? std::string("more")
                                                                : std::to_string(kHeader + payload + kChecksum)));
    if (size - kHeader - payload != kChecksum)
        fail(std::to_string(size) + " bytes, the header announces " + std::to_string(kHeader + payload + kChecksum) +
             " (trailing bytes)");
    m_pos = kHeader;
    m_end = kHeader + std::size_t(payload);
    if (getLe(data + m_end, 8) != fnv1a(data + kHeader, std::size_t(payload)))
        fail("checksum mismatch: the blob is corrupted");
}

void StateReader::fail(const std::string& message) const { throw std::invalid_argument(m_what + ": " + message); }

void StateReader::need(std::size_t n, const char* field) const {
    if (m_end - m_pos < n) fail(std::string("the payload ends inside '") + field + "'");
}

std::uint8_t StateReader::u8(const char* field) {
    need(1, field);
    return m_data[m_pos++];
}

bool StateReader::boolean(const char* field) {
    const std::uint8_t v = u8(field);
    if (v > 1) fail(std::string("'") + field + "' is " + std::to_string(v) + ", not a boolean");
    return v != 0;
}

std::uint32_t StateReader::u32(const char* field) {
    need(4, field);
    const std::uint32_t v = std::uint32_t(getLe(m_data + m_pos, 4));
    m_pos += 4;
    return v;
}

std::uint64_t StateReader::u64(const char* field) {
    need(8, field);
    const std::uint64_t v = getLe(m_data + m_pos, 8);
    m_pos += 8;
    return v;
}

double StateReader::f64(const char* field) {
    const std::uint64_t bits = u64(field);
    double v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}

float StateReader::f32(const char* field) {
    const std::uint32_t bits = u32(field);
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}

std::vector<double> StateReader::f64Vector(const char* field) {
    const std::uint64_t n = u64(field);
    if (n > remaining() / 8)
        fail(std::string("'") + field + "' announces " + std::to_string(n) + " numbers, the payload holds fewer");
    std::vector<double> v(static_cast<std::size_t>(n));
    f64s(v.data(), v.size(), field);
    return v;
}

std::vector<unsigned char> StateReader::blob(const char* field) {
    const std::uint64_t n = u64(field);
    if (n > remaining())
        fail(std::string("'") + field + "' announces " + std::to_string(n) + " bytes, the payload holds fewer");
    std::vector<unsigned char> v(m_data + m_pos, m_data + m_pos + static_cast<std::size_t>(n));
    m_pos += static_cast<std::size_t>(n);
    return v;
}

void StateReader::expectCount(std::uint64_t saved, std::uint64_t expected, const char* field) const {
    if (saved != expected)
        fail(std::string(field) + " is " + std::to_string(saved) + " in the blob, " + std::to_string(expected) +
             " here (a state of another body or scene)");
}

void StateReader::finish() const {
    if (m_pos != m_end) fail(std::to_string(m_end - m_pos) + " bytes of the payload left unread");
}

}  // namespace buoyancy
