// The shading pass of photon mapping: every pixel's camera rays, L_r = L_d + L_i + L_c + L_s.
// Direct light by stratified shadow rays, caustics from the caustic map, specular and glossy by
// recursive ray tracing; the indirect irradiance L_i comes from the method (the irradiance cache
// of --method photon, or the localized method's blend of L_y and L_t), which may also fill
// layers of its own.
#pragma once

#include <array>
#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "steadylight/base/image.h"
#include "steadylight/passes/photon_gather.h"
#include "steadylight/photons/photon_map.h"
#include "steadylight/shading/frame_context.h"
#include "steadylight/shading/surface_point.h"

namespace steadylight {

class DirectLightLog;

struct ShadingSettings {
    int samples_per_pixel = 16;   // camera rays per pixel, stratified
    int direct_samples = 2;       // shadow rays per diffuse hit and camera ray, stratified over the pixel
    int max_specular_depth = 64;  // mirror, glass and glossy bounces followed from the camera
    DensitySettings caustic_estimate{.k = 50, .max_radius = 0.2f};
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(ShadingSettings, samples_per_pixel, direct_samples, max_specular_depth,
                                                caustic_estimate)
void validate(const ShadingSettings& settings, const std::string& where);

/// The side of the square tiles shade_frame() shades, each on one thread at a time, row by row
/// from the top-left one.
constexpr int shading_tile_size = 16;

/// Up to five layers of the method's own (influence, L_y, L_t, ...), one value per camera ray.
constexpr int max_extra_layers = 5;
using ExtraLayers = std::array<Rgb, max_extra_layers>;

/// Whether a frame computes its method's analysis layers (its records, influence, estimates:
/// the pictures of how it worked, `--layers all`), or may leave them empty because the files
/// will not hold them.
enum class AnalysisLayers { made, left_out };

/// Indirect irradiance found for a pixel's earlier camera rays, so that its later rays landing
/// on the same surface close by can reuse it: the cache's indirect light varies over several
/// pixels (records reach at least CacheSettings::min_spacing_px), so one look-up serves the
/// pixel, and 16 camera rays cost about one look-up instead of 16 (the same holds for caustic
/// estimates, whose radius spans many pixels). Rays hitting another object, or a surface turned
/// by more than about 8 degrees (an edge, a crease), look up their own.
class PixelMemo {
public:
    using Values = std::array<Rgb, 3>;  // what the method needs to remember (e.g. L_y and L_t)

    static constexpr int capacity = 4;

    /// Values stored for a point of the same object within `reach` of sp.p, with a normal close to n.
    const Values* find(const SurfacePoint& sp, Vec3 n, float reach) const;
    /// Remembers values at (sp, n); when full, the values are simply not kept.
    void add(const SurfacePoint& sp, Vec3 n, const Values& values);
    void clear() { m_count = 0; }
    /// The entry the last find() found or add() kept; -1 when it found none or kept nothing.
    int last_used() const { return m_last; }
    /// Where entry `i`'s values were computed: the point and the normal.
    std::pair<Vec3, Vec3> point_of(int i) const { return {m_entries[size_t(i)].p, m_entries[size_t(i)].n}; }

private:
    struct Entry {
        int object;
        Vec3 p, n;
        Values values;
    };
    std::array<Entry, capacity> m_entries;
    int m_count = 0;
    mutable int m_last = -1;
};

/// A pixel's terms summed over its camera rays (in ray order), before dividing by their count.
struct PixelSums {
    Rgb direct, indirect, caustic, specular;
    ExtraLayers extra{};
    float covered = 0;  // camera rays that met a surface (the alpha of a transparent background)

    Rgb sum() const { return direct + indirect + caustic + specular; }
};

/// Told what the shading of each pixel goes through, ray by ray: pixel reuse keeps it with its
/// static frame to tell later which pixels a frame's changes can reach (pixel_reuse.h).
class PixelRecorder {
public:
    enum Flag : uint8_t {
        chain = 1,           // some ray went on from a mirror, glass or glossy surface
        open_chain = 2,      // ...and left the scene
        coat = 4,            // a coat reflected photon-mapped light (read from the global photons)
        reads_caustics = 8,  // a diffuse point was shaded: it reads the caustic map (an empty one too)
        gather = 16,         // the method gathered anew (no cache record reached a point)
        unkept = 32,         // some camera ray's indirect light is not in the kept look-ups
    };

    virtual ~PixelRecorder() = default;
    /// A surface point the pixel's rays hit (or, in a mirror, the image of a light they sampled).
    virtual void add_point(size_t pixel, Vec3 p) = 0;
    virtual void add_flags(size_t pixel, uint8_t flags) = 0;
    /// A shadow ray towards a light from far away, along unit `w`, that nothing static stopped.
    virtual void add_distant_direction(size_t pixel, Vec3 w) = 0;
    /// A camera ray whose first hit is diffuse (it fills the method's layers).
    virtual void add_surface_ray(size_t pixel) = 0;
    /// Camera ray `sample`'s indirect light is the look-up at (p, n), entry `entry` of its
    /// pixel's memo, times `albedo_over_pi`.
    virtual void add_look_up(size_t pixel, int sample, int entry, Vec3 p, Vec3 n, Rgb albedo_over_pi) = 0;
    /// The ids of the records the look-up of memo entry `entry` interpolated, when the method
    /// has them at hand (IrradianceCache::usable_ids at the first reach that found any).
    virtual void add_look_up_records(size_t /*pixel*/, int /*entry*/, const std::vector<uint32_t>& /*ids*/) {}
};

/// Where shade_frame() takes a pixel's values from when it does not shade every pixel anew
/// (pixel reuse, pixel_reuse.h): asked before each pixel, told its sums after. Without one, every
/// pixel is shaded whole. Called from several threads at once, for different pixels.
class PixelSource {
public:
    enum class Shading : uint8_t {
        none,            // the source gave every term
        direct_only,     // shade only the direct light (emission and shadow rays); the source gave the rest
        all_but_direct,  // shade it, but the direct light (no shadow rays, no emission) is the source's
        all,
    };

    virtual ~PixelSource() = default;
    /// How much of pixel (x, y), number `pixel` row by row, to shade; with Shading::none it has
    /// filled `sums`, with Shading::direct_only every sum but the direct light's.
    virtual Shading begin(int x, int y, size_t pixel, PixelSums& sums) = 0;
    /// The pixel's sums once shaded (not called for Shading::none); with all_but_direct it fills
    /// their direct light.
    virtual void finish(size_t pixel, PixelSums& sums) = 0;
    /// Told what the shading goes through, or null.
    virtual PixelRecorder* recorder() { return nullptr; }
    /// Where a Shading::direct_only pixel's light samples are logged as it is shaded
    /// (kept_direct_light.h), or null; asked after begin(), on the same thread.
    virtual DirectLightLog* direct_light_log(int /*x*/, int /*y*/, size_t /*pixel*/) { return nullptr; }
};

/// Which camera ray of which pixel is being shaded.
struct PixelSample {
    int x = 0, y = 0;
    int sample = 0;  // 0 .. samples_per_pixel - 1
    int samples = 1;
    /// For points the camera sees directly: the method's memo for the pixel (the shading pass
    /// keeps one of its own for caustics) and how far from its point a value may be reused (about
    /// a pixel's world size there). Null for points seen through mirrors and glass.
    PixelMemo* memo = nullptr;
    PixelMemo* caustic_memo = nullptr;
    float reach = 0;
    /// How much the point counts in its pixel: less beyond glass's reflection (the less likely of
    /// two lobes both followed) or one of several glossy bounces, where no record reaches a
    /// cheaper estimate then does (photon_gather.h).
    BranchShare share = BranchShare::whole;
    /// Told what the pixel's shading goes through, or null.
    PixelRecorder* recorder = nullptr;
    size_t pixel_index = 0;  // row by row
    /// The direct light is the pixel source's: no emission, no shadow rays.
    bool skip_direct = false;
    /// Only the direct light: no indirect light, caustics, coat or bounces (the source's).
    bool direct_only = false;
    /// With direct_only, where its light samples are logged (PixelSource::direct_light_log), or null.
    DirectLightLog* direct_log = nullptr;
};

/// The values `compute()` returns at (sp, n), or those an earlier camera ray of the same pixel
/// found within `reach` of sp.p on the same surface (see PixelMemo). No memo: always compute().
template <class Compute>
PixelMemo::Values remembered(PixelMemo* memo, float reach, const SurfacePoint& sp, Vec3 n, Compute&& compute) {
    if (!memo) return compute();
    if (const PixelMemo::Values* values = memo->find(sp, n, reach)) return *values;
    const PixelMemo::Values values = compute();
    memo->add(sp, n, values);
    return values;
}

/// Indirect irradiance at diffuse point `sp` with normal `n` (facing the viewer), for a camera
/// ray of `pixel`. `extra` is non-null for the points the camera sees directly when the frame
/// pictures the method's layers (shade_frame's `extra_layers`): the method adds its layers there
/// (each ray's values are averaged over the pixel's rays).
using IndirectIrradiance =
    std::function<Rgb(const SurfacePoint& sp, Vec3 n, const PixelSample& pixel, ExtraLayers* extra)>;

/// Radiance arriving along a ray that a coat over a diffuse base reflects, read from the
/// photons (photon_gather.h gather_from_photons): the coat's reflection of indirect light
/// (docs/materials.md, "The photon method").
using ReflectedRadiance = std::function<Rgb(const Ray& ray)>;

struct ShadedFrame {
    Image beauty, direct, indirect, caustic, specular;
    /// With a transparent background (Camera::transparent_background): the share of each
    /// pixel's camera rays that met a surface, grey. The colours are then premultiplied by it.
    std::optional<Image> alpha;
    /// The first `extra_layers` of shade_frame(), each in `extra` or, where it is grey, in
    /// `grey_extra`; the rest empty.
    std::array<Image, max_extra_layers> extra;
    std::array<GreyImage, max_extra_layers> grey_extra;
    double caustic_cpu_s = 0;  // time in caustic estimates, summed over threads
};

/// Shades every pixel of the frame, seeing what `visibility` allows (static_only: pixel reuse's
/// static frame), or, with a `source`, the part of each pixel it asks for. The method's own
/// layers are pictured for its first `extra_layers` slots (ExtraLayers) only; slot e is grey
/// (its three channels equal, pictured from the red one) where bit e of `grey_extras` is set.
ShadedFrame shade_frame(const FrameContext& context, const ShadingSettings& settings, const PhotonMap& caustic,
                        const IndirectIrradiance& indirect, const ReflectedRadiance& reflected,
                        Visibility visibility = Visibility::everything, PixelSource* source = nullptr,
                        int extra_layers = 0, unsigned grey_extras = 0);

/// Moves the shading pass's common layers into a frame that has members of the same names.
template <class FrameImages>
void take_common_layers(ShadedFrame& shaded, FrameImages& out) {
    out.beauty = std::move(shaded.beauty);
    out.direct = std::move(shaded.direct);
    out.indirect = std::move(shaded.indirect);
    out.caustic = std::move(shaded.caustic);
    out.specular = std::move(shaded.specular);
    out.alpha = std::move(shaded.alpha);
}

}  // namespace steadylight
