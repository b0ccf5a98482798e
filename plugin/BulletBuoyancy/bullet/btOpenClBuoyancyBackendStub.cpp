/// @file btOpenClBuoyancyBackendStub.cpp
/// btOpenClBuoyancyBackend in a library built without OpenCL (CMake compiles this file instead of the backend's):
/// create() explains, nothing else is reachable.

#include <BulletBuoyancy/bullet/btOpenClBuoyancyBackend.h>

#include <string>

bool btOpenClBuoyancyBackend::compiledIn() { return false; }

struct btOpenClBuoyancyBackend::Impl {
    Stats stats;
    std::string none;
};
std::unique_ptr<btOpenClBuoyancyBackend> btOpenClBuoyancyBackend::create(btBuoyancyWorld&, const btOpenClOptions&,
                                                                         std::string* message) {
    if (message)
        *message = "OpenCL: this BulletBuoyancy was built without OpenCL (BULLET_BUOYANCY_OPENCL=OFF, or the OpenCL "
                   "headers/library were not found at configure time); using the CPU path";
    return nullptr;
}
btOpenClBuoyancyBackend::btOpenClBuoyancyBackend(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
btOpenClBuoyancyBackend::~btOpenClBuoyancyBackend() = default;
void btOpenClBuoyancyBackend::beginSubstep(double) {}
bool btOpenClBuoyancyBackend::hydrostatics(const btBuoyancyDeviceBody&, const Eigen::Isometry3d&, const Eigen::Vector3d&,
                                           buoyancy::HydrostaticsResult&) {
    return false;
}
bool btOpenClBuoyancyBackend::drag(const btBuoyancyDeviceBody&, const Eigen::Vector3d&, const Eigen::Vector3d&,
                                   const Eigen::Vector3d&, Eigen::Vector3d&, Eigen::Vector3d&, Eigen::Vector3d&,
                                   double&) {
    return false;
}
std::string btOpenClBuoyancyBackend::describe() const { return "OpenCL: not built"; }
bool btOpenClBuoyancyBackend::usesDouble() const { return false; }
void btOpenClBuoyancyBackend::setEnabled(bool) {}
bool btOpenClBuoyancyBackend::isEnabled() const { return false; }
std::string btOpenClBuoyancyBackend::deviceName() const { return ""; }
const std::string& btOpenClBuoyancyBackend::lastFallbackReason() const { return m_impl->none; }
const btOpenClBuoyancyBackend::Stats& btOpenClBuoyancyBackend::stats() const { return m_impl->stats; }
void btOpenClBuoyancyBackend::rebakeOnDevice(const buoyancy::RebakeMap&, const std::vector<Eigen::Vector3d>&,
                                             buoyancy::SurfaceSamples&) {
    throw std::runtime_error("OpenCL: not built");
}
