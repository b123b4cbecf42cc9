// The photon walk that photon_tracer.cpp and photon_paths.cpp share (internal to photons/): a
// photon path's random numbers, its state in flight, and the tracer that emits and follows it.
// Every bounce draws exactly four numbers (lobe, survival, direction), after the five of the
// emission, so bounce k of photon i always starts at dimension 5 + 4k of point i: a path can be
// resumed at any bounce with the numbers full tracing would give it there.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "steadylight/base/halton.h"
#include "steadylight/base/rng.h"
#include "steadylight/photons/caustic_targets.h"
#include "steadylight/photons/photon_paths.h"

namespace steadylight {

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

    /// Emits photon `index` from the lights and follows it and any negative photon it spawns.
    void trace(uint64_t index, float scale, PhotonOutput out) const;
    /// Follows photon `index` on from `segment`, the ray of its bounce `bounce`, as trace() would.
    void resume(uint64_t index, const PathSegment& segment, int bounce, PhotonOutput out) const;

private:
    std::optional<EmissionSample> emit(float u_select, Vec2 u_position, Vec2 u_direction) const;
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

}  // namespace steadylight
