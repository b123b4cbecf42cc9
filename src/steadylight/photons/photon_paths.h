// Photon paths kept from the static pass and reused by every frame of the segment
// (docs/localized.md, "Photon paths reused"). In the spirit of selective photon tracing
// (Dmitriev, Brabec, Myszkowski, Seidel 2002), but exact: the static pass keeps every ray of
// every static photon path (the last one too, whether it leaves the scene or ends at Russian
// roulette) with what resuming the path there needs. A frame tests these rays against its
// dynamic objects only (RayTracer::meets_dynamic: the bounds, then the tracer's own instance
// query), retraces in the complete scene only the paths that meet one, from that first hit on,
// with the same quasi-random numbers (photon_tracer.h), and composes its maps: the static
// photons minus the changed paths' tails plus the new ones, in the order full tracing gives.
// The result equals trace_photons() photon for photon, bit for bit; the composed maps search
// the static map's index plus a small one of the new photons (PhotonMap's composed form).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "steadylight/photons/caustic_targets.h"
#include "steadylight/photons/photon_tracer.h"

namespace steadylight {

/// A ray of a photon path as the static pass traced it, and what resuming the path there needs.
struct PathSegment {
    Vec3 o, d;           // the ray (it covers [0, infinity))
    float t_static;      // its nearest hit in the static scene; infinity when it leaves
    Rgb power;           // the power the photon carries along it
    bool specular_path;  // every bounce before it was specular or glossy
};

/// The static paths of one map kind.
struct StoredPaths {
    long count = 0;                       // paths emitted
    std::vector<uint32_t> first_segment;  // path i's rays are segments[first_segment[i], first_segment[i + 1])
    std::vector<uint32_t> first_photon;   // and its photons photons[first_photon[i], first_photon[i + 1])
    std::vector<PathSegment> segments;
    PhotonMap photons;                      // the static map
    std::optional<CausticTargets> targets;  // caustic: where its photons were aimed

    size_t bytes() const;
};

/// The static photon paths of a segment, global and caustic.
struct StaticPhotonPaths {
    PhotonSettings settings;
    StoredPaths global, caustic;
    /// The irradiance at the global photons, probing the static scene, which frames take where
    /// nothing changed (StaticIrradianceReuse); null: frames estimate every value they need.
    std::shared_ptr<const IrradiancePhotons> irradiance;

    size_t bytes() const { return global.bytes() + caustic.bytes(); }
};

/// Traces the static paths (the dynamic objects removed) in `context`'s scene, keeping them.
StaticPhotonPaths trace_static_photon_paths(const FrameContext& context, const PhotonSettings& settings);

/// A frame's maps composed from the static paths, and how many paths it retraced.
struct ComposedPhotons {
    TracedPhotons maps;
    KeptStaticPhotons global_kept;  // which global photons are static ones
    long retraced_paths = 0;
    long caustic_retraced_paths = 0;           // of them caustic ones
    bool caustic_traced = false;               // the caustic map was traced whole: its targets moved
    std::vector<Vec3> changed_caustic_points;  // unless traced whole: where static caustic photons went or new ones are
};

/// The maps trace_photons(context, paths.settings) gives, bit for bit, from `paths` (traced in
/// the same segment) and the frame's dynamic objects. Where a dynamic object is a caustic
/// target, caustic photons leave the lights in other directions than in the static pass, and
/// the caustic map is traced whole.
ComposedPhotons compose_photons(const FrameContext& context, const StaticPhotonPaths& paths);

}  // namespace steadylight
