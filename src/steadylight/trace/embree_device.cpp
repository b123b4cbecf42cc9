#include "steadylight/trace/embree_device.h"

#include <stdexcept>
#include <string>

namespace steadylight {
namespace {

void on_embree_error(void*, RTCError code, const char* message) {
    throw std::runtime_error("Embree error " + std::to_string(int(code)) + ": " + (message ? message : "(no message)"));
}

struct Device {
    RTCDevice handle;

    Device() : handle(rtcNewDevice(nullptr)) {
        if (!handle) throw std::runtime_error("cannot create the Embree device");
        rtcSetDeviceErrorFunction(handle, on_embree_error, nullptr);
    }
    ~Device() { rtcReleaseDevice(handle); }
};

}  // namespace

RTCDevice embree_device() {
    static Device device;
    return device.handle;
}

}  // namespace steadylight
