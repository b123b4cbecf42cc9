// A stored photon (Jensen 2001, ch. 5): where it landed, the surface side it landed on, where it
// came from, and the power it carries.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "steadylight/base/color.h"
#include "steadylight/base/vec.h"

namespace steadylight {

struct Photon {
    Vec3 p;
    Vec3 n;               // unit surface normal on the side the photon arrived from
    Vec3 wi;              // unit direction back towards where it came from
    Rgb power;            // W per channel; negative for the negative photons of the dynamic map
    uint16_t bounce = 0;  // surface interactions before this one: 0 = a direct hit from the light
};

/// The same photon bit for bit (negative zeros and NaNs included; padding aside).
inline bool same_bits(const Photon& a, const Photon& b) {
    return std::memcmp(&a, &b, offsetof(Photon, bounce)) == 0 && a.bounce == b.bounce;
}

/// The normal filter's threshold: the cosine between two normals above which they are one side.
constexpr float same_side_cosine = 0.5f;

/// Whether a density estimate at a point of normal n counts light arriving along `normal`'s side:
/// photons arriving on the other side of a thin wall, or on a differently oriented surface nearby,
/// do not (Jensen 2001 §7.2: "the normal ... filter").
inline bool same_side(Vec3 normal, Vec3 n) { return dot(normal, n) > same_side_cosine; }
inline bool same_side(const Photon& photon, Vec3 n) { return same_side(photon.n, n); }

}  // namespace steadylight
