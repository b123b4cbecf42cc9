// The shading pass of photon mapping: every pixel's camera rays, L_r = L_d + L_i + L_c + L_s.
// Direct light by stratified shadow rays, caustics from the caustic map, specular and glossy by
// recursive ray tracing; the indirect irradiance L_i comes from the method (the irradiance cache
// of --method photon, or the localized method's blend of L_y and L_t), which may also fill
// layers of its own.
#pragma once

#include <array>
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "steadylight/base/image.h"
#include "steadylight/passes/photon_gather.h"
#include "steadylight/photons/photon_map.h"
#include "steadylight/shading/frame_context.h"
#include "steadylight/shading/surface_point.h"

namespace steadylight {

struct ShadingSettings {
    int samples_per_pixel = 16;   // camera rays per pixel, stratified
    int direct_samples = 2;       // shadow rays per diffuse hit and camera ray, stratified over the pixel
    int max_specular_depth = 64;  // mirror, glass and glossy bounces followed from the camera
    DensitySettings caustic_estimate{.k = 50, .max_radius = 0.2f};
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(ShadingSettings, samples_per_pixel, direct_samples, max_specular_depth,
                                                caustic_estimate)
void validate(const ShadingSettings& settings, const std::string& where);

/// Up to five layers of the method's own (influence, L_y, L_t, ...), one value per camera ray.
constexpr int max_extra_layers = 5;
using ExtraLayers = std::array<Rgb, max_extra_layers>;

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

/// What a pixel's shading went through, kept in the static frame so that a later frame can tell
/// whether the pixel can change (pixel_reuse.h).
struct PixelTrace {
    enum Flag : uint8_t {
        chain = 1,           // some ray went on from a mirror, glass or glossy surface
        open_chain = 2,      // ...and left the scene
        coat = 4,            // a coat reflected photon-mapped light (read from the global photons)
        reads_caustics = 8,  // a diffuse point was shaded: it reads the caustic map (an empty one too)
        gather = 16,         // the method gathered anew (no cache record reached a point)
        unkept = 32,         // some camera ray's indirect light is not in the kept look-ups (KeptLookUps)
    };
    Vec3 lo{infinity, infinity, infinity}, hi{-infinity, -infinity, -infinity};  // box of every surface point hit
    uint8_t flags = 0;
    uint8_t surface_rays = 0;  // camera rays whose first hit is diffuse (they fill the method's layers)

    void add_point(Vec3 p) { lo = min(lo, p), hi = max(hi, p); }
};

/// A pixel's terms summed over its camera rays (in ray order), before dividing by their count.
struct PixelSums {
    Rgb direct, indirect, caustic, specular;
    ExtraLayers extra{};

    Rgb sum() const { return direct + indirect + caustic + specular; }
};

/// Where a pixel's camera rays looked up their indirect light (PixelMemo's entries), so that a
/// frame can look it up again there without tracing them.
struct PixelLookUps {
    std::array<Vec3, PixelMemo::capacity> p, n;
};

/// The static frame of pixel reuse (pixel_reuse.h): every pixel's sums and trace, shaded with
/// the dynamic objects removed, and where its camera rays looked up indirect light.
struct StaticFrame {
    static constexpr uint8_t no_look_up = 255;

    FrameState made_at;                      // the view and lights it was shaded with
    int width = 0, height = 0, samples = 0;  // samples: camera rays per pixel
    std::vector<PixelSums> sums;
    std::vector<PixelTrace> traces;
    std::vector<PixelLookUps> look_ups;
    std::vector<uint8_t>
        ray_look_up;              // per pixel and camera ray: the look-up its indirect light came from, or no_look_up
    std::vector<Rgb> ray_albedo;  // per pixel and camera ray: the albedo / pi that multiplied it

    static size_t bytes_per_pixel(int samples) {
        return sizeof(PixelSums) + sizeof(PixelTrace) + sizeof(PixelLookUps) + size_t(samples) * (1 + sizeof(Rgb));
    }
};

/// What a frame does with a pixel when it has a static frame.
enum class PixelWork : uint8_t {
    reuse,            // every term as the static frame has it
    look_up_again,    // only the indirect light changes: look it up again where the camera rays did, none traced
    redo_but_direct,  // shade again, but the direct light (no shadow rays) is the static frame's
    redo,             // shade again
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
    /// What the pixel's shading goes through, when the static frame is being made.
    PixelTrace* trace = nullptr;
    StaticFrame* kept = nullptr;  // ...and where it keeps the pixel's look-ups
    size_t pixel_index = 0;
    /// The direct light is taken from the static frame: no emission, no shadow rays.
    bool skip_direct = false;
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
/// ray of `pixel`. `extra` is non-null for the points the camera sees directly: the method adds
/// its layers there (each ray's values are averaged over the pixel's rays).
using IndirectIrradiance =
    std::function<Rgb(const SurfacePoint& sp, Vec3 n, const PixelSample& pixel, ExtraLayers* extra)>;

/// Radiance arriving along a ray that a coat over a diffuse base reflects, read from the
/// photons (photon_gather.h gather_from_photons): the coat's reflection of indirect light
/// (docs/materials.md, "The photon method").
using ReflectedRadiance = std::function<Rgb(const Ray& ray)>;

struct ShadedFrame {
    Image beauty, direct, indirect, caustic, specular;
    std::array<Image, max_extra_layers> extra;
    double caustic_cpu_s = 0;  // time in caustic estimates, summed over threads
};

/// How shade_frame() treats pixels beyond shading them all: making a static frame, or reusing one.
struct PixelReuse {
    Visibility visibility = Visibility::everything;  // static_only: the static frame
    StaticFrame* keep = nullptr;                     // filled with every pixel's sums and trace
    const StaticFrame* base = nullptr;               // with `work`: what pixels take from
    const std::vector<PixelWork>* work = nullptr;    // one per pixel, row by row
    /// Gives a reused pixel's sums the method's layers that change between frames although its
    /// terms do not (the localized method's influence).
    std::function<void(int x, int y, const PixelTrace& trace, PixelSums& sums)> reused_layers;
    /// Gives a PixelWork::look_up_again pixel's sums (the static frame's) its indirect light and
    /// the method's layers, looked up again at the static frame's look-ups of pixel `index`.
    std::function<void(int x, int y, size_t index, PixelSums& sums)> look_up_again;
};

ShadedFrame shade_frame(const FrameContext& context, const ShadingSettings& settings, const PhotonMap& caustic,
                        const IndirectIrradiance& indirect, const ReflectedRadiance& reflected,
                        const PixelReuse& reuse = {});

/// Moves the shading pass's common layers into a frame that has members of the same names.
template <class FrameImages>
void take_common_layers(ShadedFrame& shaded, FrameImages& out) {
    out.beauty = std::move(shaded.beauty);
    out.direct = std::move(shaded.direct);
    out.indirect = std::move(shaded.indirect);
    out.caustic = std::move(shaded.caustic);
    out.specular = std::move(shaded.specular);
}

}  // namespace steadylight
