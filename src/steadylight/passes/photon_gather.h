// Final gathering against a photon map, shared by the photon-mapping method and the localized
// method's passes: what a gather ray brings back, which point of each pixel gets cached
// irradiance, building a cache over the camera's image, and the look-up that gathers where no
// record reaches (docs/design.md).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>

#include "steadylight/base/image.h"
#include "steadylight/irradiance/cache_builder.h"
#include "steadylight/photons/photon_map.h"
#include "steadylight/shading/frame_context.h"
#include "steadylight/shading/surface_point.h"

namespace steadylight {

/// The surface point with its normals turned to face the incoming direction `d`.
SurfacePoint face_towards(SurfacePoint sp, Vec3 d);

/// Radiance a final-gather ray brings back: at a diffuse surface rho / pi times the precomputed
/// irradiance there (its whole outgoing radiance, direct included); through mirrors and glass it
/// continues; emitters add nothing (that light is L_d). Sees what `visibility` allows.
GatherHit gather_from_photons(const FrameContext& context, const IrradiancePhotons& photons, float max_radius,
                              Visibility visibility, Ray ray);

/// Mirrors and glass followed from the camera to find a pixel's diffuse point.
constexpr int max_specular_chain = 8;
/// Mirror, glass and glossy bounces a final-gather ray follows, as many as a photon path's
/// (PhotonSettings::max_bounces): light that rough glass turns to grazing angles is held in it
/// by total internal reflection for dozens of bounces, and a limit of 4 lost 1.2% of
/// blender_glass's light behind its frosted pane (docs/notes/truth-rough-glass-light.md).
constexpr int max_gather_chain = 64;

/// The diffuse surface point a pixel's centre sees (seeing what `visibility` allows), where its
/// indirect irradiance is cached: directly, or through mirrors and glass (so that what the camera
/// sees through them is cached too, instead of gathered anew by each camera ray that lands
/// there; rough glass as if it were smooth); std::nullopt for background and other glossy surfaces.
/// `path`, when given, receives how it got there.
struct CentrePath {
    int bounces = 0;           // mirror and glass bounces followed: 0 when the centre's first ray answered alone
    float first_t = infinity;  // where the centre's first ray met a surface; infinity: nowhere
};
std::optional<CachePoint> cache_point_at(const FrameContext& context, Visibility visibility, int x, int y,
                                         CentrePath* path = nullptr);

/// Adds records to `cache` over the camera's image by final gathering against `photons`, at the
/// pixels `wanted` accepts (all when empty); pixels `may_want` refuses (none when empty) are
/// known not to be wanted without their point.
struct PhotonCacheBuild {
    const FrameContext& context;
    const IrradiancePhotons& photons;
    float max_radius;  // of the precomputed-irradiance look-up
    const GatherSettings& gather;
    Visibility visibility;
    std::function<bool(const CachePoint&, int x, int y)> wanted;
    std::function<bool(int x, int y)> may_want;
};
CacheBuildStats build_photon_cache(IrradianceCache& cache, const PhotonCacheBuild& build);

/// How much a camera ray's diffuse point counts in its pixel, which decides how its indirect light
/// is estimated where no record reaches it.
enum class BranchShare : uint8_t {
    whole,   // a full gather
    glossy,  // one of a glossy surface's several bounces: a gather with a sixteenth of the rays
    minor,   // beyond glass's reflection (a few percent): the irradiance at the nearest irradiance
             // photon, read as a gather ray reads it at its end; no ray traced
};

/// The estimates of indirect irradiance at points no record reaches (seeing everything), one per
/// BranchShare.
struct PointFallbacks {
    std::function<GatherResult(const SurfacePoint&, Vec3)> gather, rough_gather, look_up;
    const std::function<GatherResult(const SurfacePoint&, Vec3)>& at(BranchShare share) const {
        return share == BranchShare::minor ? look_up : share == BranchShare::glossy ? rough_gather : gather;
    }
};
PointFallbacks make_point_fallbacks(const FrameContext& context, const IrradiancePhotons& photons, float max_radius,
                                    const GatherSettings& gather);

/// Indirect irradiance interpolated from `cache` as shading interpolates it: over the records
/// Ward's weight lets reach (p, n), else over those reaching twice as far; nothing where none
/// does. `used_ids`, when given, gets the ids of the records interpolated (empty for nothing).
std::optional<Rgb> interpolated_irradiance(const IrradianceCache& cache, Vec3 p, Vec3 n,
                                           std::vector<uint32_t>* used_ids = nullptr);

/// Indirect irradiance from `cache`, or, where no record reaches even twice as far, from a gather
/// at the point (not kept, so the cache never depends on shading order). Counts the fallbacks.
/// `used_ids`, when given, gets the ids of the records interpolated (empty after a gather).
Rgb cached_irradiance(const IrradianceCache& cache, const SurfacePoint& sp, Vec3 n,
                      const std::function<GatherResult(const SurfacePoint&, Vec3)>& gather,
                      std::atomic<long>& fallbacks, std::atomic<long>& gather_rays,
                      std::vector<uint32_t>* used_ids = nullptr);

/// 1 at the pixels where records project, 0 elsewhere (paper Fig. 3).
GreyImage record_picture(const Camera& camera, const std::vector<IrradianceRecord>& records);

}  // namespace steadylight
