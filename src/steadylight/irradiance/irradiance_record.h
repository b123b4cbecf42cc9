// One irradiance cache record (Ward, Rubinstein & Clear 1988): the irradiance gathered at a
// surface point, how far it may be reused, and its rotational and translational gradients
// (Ward & Heckbert 1992), which make interpolation first-order accurate.
#pragma once

#include <array>

#include "steadylight/base/color.h"
#include "steadylight/base/vec.h"

namespace steadylight {

struct IrradianceRecord {
    Vec3 p;                                      // position
    Vec3 n;                                      // unit normal on the side the irradiance arrives from
    Rgb E;                                       // irradiance (W m^-2 per channel)
    float radius = 0;                            // validity radius R_i (harmonic mean distance, clamped), world units
    std::array<Vec3, 3> rotational_gradient;     // dE/d(rotation of n), per channel r, g, b
    std::array<Vec3, 3> translational_gradient;  // dE/dx in the tangent plane, per channel
};

}  // namespace steadylight
