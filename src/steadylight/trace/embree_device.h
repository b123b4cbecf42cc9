// The process-wide Embree device, created on first use, with an error callback that turns
// Embree errors into exceptions (Embree tutorial "minimal": set it right after rtcNewDevice).
#pragma once

#include <embree3/rtcore.h>

namespace steadylight {

/// The shared device. Thread-safe; lives until the program exits.
RTCDevice embree_device();

}  // namespace steadylight
