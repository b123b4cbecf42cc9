// Final gathering: the irradiance at a surface point, integrated over the hemisphere with
// stratified cosine-weighted rays (theta_j = asin(sqrt((j + u) / M)), phi_k = 2 pi (k + v) / N,
// M x N strata), together with the harmonic mean distance of the rays' hits and Ward & Heckbert's
// rotational and translational gradients computed from the same strata (Ward & Heckbert 1992;
// Jarosz et al., "Irradiance gradients in the presence of participating media and occlusion",
// 2008, eq. for the cosine-weighted hemisphere). The radiance each ray brings back is up to the
// caller (photon-map look-up, path tracing, ...).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "steadylight/base/ray.h"
#include "steadylight/irradiance/irradiance_record.h"

namespace steadylight {

struct GatherSettings {
    int theta_strata = 16;  // M
    int phi_strata = 32;    // N
    /// Use one jitter set for every gather of every frame (paper §4, docs/design.md): the same
    /// local directions everywhere, so unchanged surroundings give bit-identical results.
    bool fixed_directions = true;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(GatherSettings, theta_strata, phi_strata, fixed_directions)
void validate(const GatherSettings& settings, const std::string& where);

/// What a gather ray found: the radiance arriving along it and the distance to what it hit.
struct GatherHit {
    Rgb L;
    float distance = infinity;  // infinity when the ray left the scene
};

/// Radiance arriving at the ray's origin from along the ray.
using GatherRadiance = std::function<GatherHit(const Ray& ray)>;

/// The local (normal = +z) directions of the strata, theta-major: index j * N + k. With
/// `fixed_directions` the jitter comes from a fixed seed; otherwise from `seed`.
std::vector<Vec3> gather_directions(const GatherSettings& settings, uint64_t seed);

struct GatherResult {
    IrradianceRecord record;        // p, n, E and both gradients filled in; radius = harmonic mean distance
    float min_distance = infinity;  // the nearest hit, for diagnostics
    int rays = 0;
};

/// Gathers at `p` with unit shading normal `n` and geometric normal `ng` (same side): each ray
/// leaves by spawn_ray(p, ng, d) (base/ray.h) along a direction of `directions` (from
/// gather_directions()) turned into the frame of `n`.
GatherResult final_gather(Vec3 p, Vec3 n, Vec3 ng, const std::vector<Vec3>& directions, const GatherSettings& settings,
                          const GatherRadiance& radiance);

}  // namespace steadylight
