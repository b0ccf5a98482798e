#include <BulletBuoyancy/bullet/btBuoyancyState.h>

#include <LinearMath/btScalar.h>

#include <utility>

namespace {

/// The header's precision byte of this build: the size of btScalar in bytes (4 float, 8 double).
constexpr std::uint8_t kPrecisionBytes = static_cast<std::uint8_t>(sizeof(btScalar));

const char* kindName(std::uint8_t kind) { return btBuoyancyStateKindName(static_cast<btBuoyancyStateKind>(kind)); }

buoyancy::StateNames layerNames() {
    buoyancy::StateNames names;
    names.kind = &kindName;
    names.scalar = "btScalar";
    return names;
}

}  // namespace

const char* btBuoyancyStateKindName(btBuoyancyStateKind kind) {
    switch (kind) {
    case btBuoyancyStateKind::World: return "btBuoyancyWorld";
    case btBuoyancyStateKind::Action: return "btBuoyancyAction";
    case btBuoyancyStateKind::Flooding: return "btFloodingAction";
    case btBuoyancyStateKind::TimeVaryingMass: return "btTimeVaryingMassAction";
    case btBuoyancyStateKind::BuoyantBody: return "btBuoyantBody";
    case btBuoyancyStateKind::InteractiveWater: return "btInteractiveWaterCoupler";
    case btBuoyancyStateKind::Immediate: return "btBuoyancyImmediate";
    case btBuoyancyStateKind::MultiBodyAction: return "btBuoyancyMultiBodyAction";
    }
    return "unknown";
}

btBuoyancyStateWriter::btBuoyancyStateWriter(btBuoyancyStateKind kind)
    : buoyancy::StateWriter(static_cast<std::uint8_t>(kind), kPrecisionBytes) {}

btBuoyancyStateReader::btBuoyancyStateReader(const unsigned char* data, std::size_t size, btBuoyancyStateKind kind,
                                             std::string what)
    : buoyancy::StateReader(data, size, static_cast<std::uint8_t>(kind), kPrecisionBytes, std::move(what),
                            layerNames()) {}
