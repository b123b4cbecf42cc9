// Photon tracing, the first pass of photon mapping (Jensen 2001, ch. 5): photons leave the lights
// in proportion to their power and bounce through the scene by the BSDFs, with Russian roulette
// by reflectance so that the power of surviving photons stays constant. Caustic photons are aimed
// at the specular and glossy objects (caustic_targets.h). Every random decision of
// photon i comes from point i of the scrambled Halton sequence (base/halton.h), so the photons
// of a frame depend only on the scene at that frame (paper §4).
//
// In a scene with dynamic objects the same pass also fills the dynamic photon map (paper §3.1,
// docs/design.md): from a path's first dynamic hit on, its diffuse hits are stored there (except
// direct hits), and a negative photon re-traces the static path the photon would have taken
// without the dynamic objects, with the same random numbers, carrying negated power.
// photon_paths.h composes a frame's maps from the static paths instead, with the same result.
//
// The photon walk, which photon_paths.cpp shares: a photon path's random numbers, its state in
// flight, and the tracer that emits and follows it.
// Every bounce draws exactly four numbers (lobe, survival, direction), after the five of the
// emission, so bounce k of photon i always starts at dimension 5 + 4k of point i: a path can be
// resumed at any bounce with the numbers full tracing would give it there.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "steadylight/base/halton.h"
#include "steadylight/base/rng.h"
#include "steadylight/photons/caustic_targets.h"
#include "steadylight/photons/photon_map.h"
#include "steadylight/shading/frame_context.h"

namespace steadylight {

struct PathSegment;  // photon_paths.h

struct PhotonSettings {
    long global_photons = 200'000;   // photon paths emitted for the global map
    long caustic_photons = 200'000;  // photon paths emitted for the caustic map
    // Bounces before a path is cut, as the path tracer's max_depth: survival by the scattered
    // power ends nearly every path long before (16 cut a room of albedo 0.75 about 1% dark).
    int max_bounces = 64;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(PhotonSettings, global_photons, caustic_photons, max_bounces)
/// Throws InputError naming `where` + "/<field>" for a value out of range.
void validate(const PhotonSettings& settings, const std::string& where);

struct TracedPhotons {
    PhotonMap global;   // every diffuse hit, direct ones included (for final gathering)
    PhotonMap caustic;  // diffuse hits after one or more specular bounces (L S+ D)
    PhotonMap dynamic;  // the change the dynamic objects make: positive and negative photons
};

/// Traces both kinds of photons in the scene as `context.frame` places it, seeing the objects
/// that `visibility` allows; with Visibility::everything in a scene with dynamic objects it also
/// fills the dynamic map (from the global photons' paths). Deterministic: the maps are the same
/// for any thread count.
TracedPhotons trace_photons(const FrameContext& context, const PhotonSettings& settings,
                            Visibility visibility = Visibility::everything);

enum class MapKind { global, caustic };

/// The random numbers of one photon path: Halton dimensions while they last, then a stream
/// hashed from the photon index (deep bounces matter little and are rare). Copyable, so that a
/// negative photon can go on with exactly the numbers the static photon would have used.
class PhotonSampler {
public:
    static constexpr int emission_numbers = 5;
    static constexpr int bounce_numbers = 4;

    explicit PhotonSampler(uint64_t index) : m_index(index), m_rng(hash_ids(index, 0x9407)) {}
    /// The sampler of photon `index` as it stands at the start of bounce `bounce`.
    static PhotonSampler at_bounce(uint64_t index, int bounce) {
        PhotonSampler sampler(index);
        for (int i = emission_numbers + bounce_numbers * bounce; i > 0; --i) sampler.skip();
        return sampler;
    }

    float next() { return m_dimension < halton_dimensions ? halton(m_dimension++, m_index) : m_rng.next_float(); }
    Vec2 next_vec2() {
        const float x = next();
        return {x, next()};
    }

private:
    void skip() { m_dimension < halton_dimensions ? void(++m_dimension) : void(m_rng.next_u32()); }

    uint64_t m_index;
    int m_dimension = 0;
    Pcg32 m_rng;
};

/// Where the photons of one path go.
struct PhotonOutput {
    std::vector<Photon>& main;     // the global or the caustic map
    std::vector<Photon>* dynamic;  // the dynamic map, or nullptr when it is not wanted
    bool negatives = true;         // spawn the negative photon (resumed paths take it from the static path)
    std::vector<PathSegment>* segments = nullptr;  // where the static pass keeps the path's rays
};

/// One photon path in flight: its ray, power and history.
struct PhotonPath {
    Ray ray;
    Rgb power;
    PhotonSampler sampler;
    int bounce = 0;
    bool specular_path = false;  // every bounce so far was specular or glossy
    bool dynamic = false;        // it has hit a dynamic object
    bool negative = false;       // it re-traces a static path with negated power
};

class PhotonTracer {
public:
    /// `targets`: where caustic photons are aimed (nullptr: emitted as the lights emit).
    PhotonTracer(const FrameContext& context, const PhotonSettings& settings, MapKind kind, Visibility visibility,
                 const CausticTargets* targets)
        : m_context(context), m_settings(settings), m_kind(kind), m_visibility(visibility), m_targets(targets) {}

    /// Emits photon `index` from the lights of `group` and follows it and any negative photon it
    /// spawns; `scale` spreads the group's power over its photons (1 / their number).
    void trace(uint64_t index, PhotonGroup group, float scale, PhotonOutput out) const;
    /// Follows photon `index` on from `segment`, the ray of its bounce `bounce`, as trace() would.
    void resume(uint64_t index, const PathSegment& segment, int bounce, PhotonOutput out) const;

private:
    std::optional<EmissionSample> emit(PhotonGroup group, float u_select, Vec2 u_position, Vec2 u_direction) const;
    void follow(PhotonPath path, PhotonOutput out) const;
    void store(const PhotonPath& path, const Photon& photon, PhotonOutput out) const;

    const FrameContext& m_context;
    const PhotonSettings& m_settings;
    MapKind m_kind;
    Visibility m_visibility;
    const CausticTargets* m_targets;
};

/// The first photon index of a map kind: the caustic map uses other points of the sequence.
inline uint64_t first_photon_index(MapKind kind) { return kind == MapKind::global ? 0 : uint64_t(1) << 32; }

/// The parts that chunks of a parallel loop filled, joined in chunk order.
template <class T>
std::vector<T> join(const std::vector<std::vector<T>>& parts) {
    size_t size = 0;
    for (const auto& part : parts) size += part.size();
    std::vector<T> all;
    all.reserve(size);
    for (const auto& part : parts) all.insert(all.end(), part.begin(), part.end());
    return all;
}

/// Caustic paths need a specular or glossy surface; without one the caustic map stays empty.
bool has_non_diffuse_surface(const FrameContext& context);

/// A frame has a dynamic map where something moves: a dynamic object, or a light whose photons
/// are traced every frame (PhotonGroup::moving).
bool has_dynamic_map(const FrameContext& context);

/// The photons of paths [begin, end) of a map of `kind` split as `split` says, each path
/// emitted from its group's lights and weighted by its group's count, in path order; and the
/// dynamic map's when `dynamic` is set.
struct TracedPaths {
    std::vector<Photon> main, dynamic;
};
TracedPaths trace_paths(const PhotonTracer& tracer, MapKind kind, PhotonSplit split, long begin, long end,
                        bool dynamic);

}  // namespace steadylight
