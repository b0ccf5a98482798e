/// @file btBuoyancyCompute.cpp
/// btBuoyancyWorld::setCompute (declared in bullet/btBuoyancyWorld.h): kept beside the OpenCL backend it creates.

#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btOpenClBuoyancyBackend.h>

bool btBuoyancyWorld::setCompute(btBuoyancyCompute compute, std::string* message) {
    if (compute == btBuoyancyCompute::Cpu) {
        setDeviceBackend(nullptr);
        if (message) *message = "CPU";
        return true;
    }
    std::unique_ptr<btOpenClBuoyancyBackend> backend = btOpenClBuoyancyBackend::create(*this, btOpenClOptions(), message);
    if (!backend) return false;  // the previous backend (CPU or another device) stays
    setDeviceBackend(std::move(backend));
    return true;
}
