// Pixel reuse for a still camera (docs/localized.md, "Pixels reused"). A
// segment whose camera and lights do not move keeps a static frame: every pixel shaded with the
// dynamic objects removed, its per-term sums and what its shading went through (StaticFrame). Each frame then asks, per
// pixel and conservatively, which terms the frame's changes can reach, and does only that work:
//   camera  a camera ray may meet a dynamic object (the object's screen box), or a chain of
//           mirror and glass bounces may (the sphere about the pixel's points)
//   direct  a shadow ray may: a dynamic object's sphere meets the hull of the pixel's points and
//           a light
//   indirect  a corrected static record whose reach covers the pixel's screen position changed,
//           the influence blends in L_y, or the pixel gathered anew or read photons (a coat)
//   caustic a caustic photon that changed lies within an estimate's reach of the pixel on the
//           screen (or the caustic map changed whole) and the pixel shaded a diffuse point
// No bit: the pixel is the static frame's, bit for bit what shading it would give. Only the
// indirect bit, from changed records alone: where none of the records its look-ups interpolated
// in the static frame changed, no bit after all; else its indirect light is interpolated again
// where its camera rays looked it up, over those records, no ray traced. Only the indirect or caustic
// bits: it is shaded again without its shadow rays (its direct light is the static frame's).
// Else it is shaded again whole. Points seen through mirrors and glass are not
// on the screen where their pixel is, so a pixel with chains counts as changed whenever a record
// or a caustic photon changed anywhere.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

#include "steadylight/base/bounding_sphere.h"
#include "steadylight/base/unfilled_allocator.h"
#include "steadylight/irradiance/irradiance_cache.h"
#include "steadylight/passes/kept_direct_light.h"
#include "steadylight/passes/shading_pass.h"

namespace steadylight {

/// What a pixel's shading went through (PixelRecorder's flags and points), kept in the static
/// frame so that a later frame can tell whether the pixel can change.
struct PixelTrace {
    Vec3 lo{infinity, infinity, infinity}, hi{-infinity, -infinity, -infinity};  // box of every surface point hit
    uint8_t flags = 0;                                                           // PixelRecorder::Flag bits
    uint8_t surface_rays = 0;  // camera rays whose first hit is diffuse (they fill the method's layers)
    // The box of the unit directions of the shadow rays towards lights from far away that reached
    // them (nothing static in the way), in 127ths rounded outwards: only a dynamic object in one
    // of those directions from the points can change the pixel's light from far away.
    std::array<int8_t, 3> to_distant_lo{127, 127, 127}, to_distant_hi{-127, -127, -127};

    void add_point(Vec3 p) { lo = min(lo, p), hi = max(hi, p); }
    void add_distant_direction(Vec3 w);
    bool reached_distant_light() const { return to_distant_lo[0] <= to_distant_hi[0]; }
};

/// The distinct sets of records the look-ups of one shading tile interpolated, packed: the
/// records any of them holds, ascending, and each set as bits over those (neighbouring pixels
/// mostly interpolate the same few dozen records).
struct TileRecordSets {
    std::vector<uint32_t> ids;
    std::vector<uint64_t> bits;  // `words` words a set
    int words = 0, sets = 0;

    /// The ids of set `set`, ascending.
    void get(int set, std::vector<uint32_t>& out) const;
    /// Per set, 1 where it holds a record that `records` marks (non-zero at a record's id).
    std::vector<uint8_t> sets_meeting(const std::vector<uint8_t>& records) const;
    /// Packs `sets`: each set's size, then its ids, ascending.
    static TileRecordSets of(const std::vector<uint32_t>& sets);
    size_t bytes() const { return ids.capacity() * sizeof(uint32_t) + bits.capacity() * sizeof(uint64_t); }
};

/// Where a kept pixel's camera rays looked up their indirect light: the pixel memo's look-ups
/// (points, normals and the records each interpolated) and, per camera ray, which one and the
/// albedo that multiplied it. A view into the static frame's bytes.
class KeptLookUps {
public:
    static constexpr int none = -1;

    KeptLookUps() = default;  // none kept
    /// `rays`: a byte per camera ray, or one for all of them (`same_rays`).
    KeptLookUps(int count, const std::byte* look_ups, const std::byte* albedos, const uint8_t* rays, bool same_rays,
                const TileRecordSets* record_sets)
        : m_count(count),
          m_look_ups(look_ups),
          m_albedos(albedos),
          m_rays(rays),
          m_same_rays(same_rays),
          m_record_sets(record_sets) {}
    /// How many look-ups were kept.
    int count() const { return m_count; }
    /// Whether every camera ray took the same look-up and albedo (or none).
    bool same_rays() const { return m_same_rays; }
    /// The look-up camera ray `ray`'s indirect light came from, or none.
    int look_up(int ray) const { return m_rays && ray_byte(ray) != no_ray ? ray_byte(ray) & 3 : none; }
    Vec3 point(int look_up) const;
    Vec3 normal(int look_up) const;
    /// The ids of the corrected records the look-up interpolated, ascending (usable_ids: at the
    /// first reach that found any); empty where none did.
    void records(int look_up, std::vector<uint32_t>& out) const;
    /// Which of the tile's record sets the look-up interpolated.
    int record_set(int look_up) const;
    /// The albedo / pi that multiplied camera ray `ray`'s indirect light (one with a look-up).
    Rgb albedo(int ray) const;

    /// A camera ray's byte: its look-up in the low 2 bits, the index of its albedo above them.
    static constexpr uint8_t no_ray = 255;
    static constexpr int max_albedos = 32;

private:
    uint8_t ray_byte(int ray) const { return m_rays[m_same_rays ? 0 : ray]; }

    int m_count = 0;
    const std::byte* m_look_ups = nullptr;
    const std::byte* m_albedos = nullptr;
    const uint8_t* m_rays = nullptr;  // null: no camera ray's look-up was kept
    bool m_same_rays = false;
    const TileRecordSets* m_record_sets = nullptr;  // the pixel's tile's
};

/// The static frame: every pixel's sums and trace, shaded with the dynamic objects removed, and
/// where its camera rays looked up indirect light. Kept packed, since it is held for a whole
/// segment at production sizes: per pixel a KeptPixel (its trace, and how its values are kept),
/// then its values in the bytes of its shading tile (each tile is shaded by one thread at a
/// time, so a tile's bytes grow from one thread): of its sums only those that are not zero and
/// not equal to its indirect sum (the L_t layer mostly is), its look-ups, the distinct albedos
/// its camera rays multiplied them by, and a byte per camera ray; per tile, the distinct sets of
/// records its look-ups interpolated (neighbouring pixels mostly share them). A diffuse room's
/// pixel keeps about 120 bytes at 16 camera rays (docs/notes/reuse-memory.md).
class StaticFrame {
public:
    FrameState made_at;                      // the view and lights it was shaded with
    int width = 0, height = 0, samples = 0;  // samples: camera rays per pixel

    const PixelTrace& trace(size_t pixel) const { return m_pixels[pixel].trace; }
    PixelSums sums(size_t pixel) const;
    /// sums(pixel).direct, without unpacking the others.
    Rgb direct(size_t pixel) const;
    KeptLookUps look_ups(size_t pixel) const;
    /// Per shading tile, per record set of its look-ups, whether the set holds a record that
    /// `records` marks (non-zero at a record's id): for interpolates_marked(). Once a tile and set,
    /// not once a pixel: neighbouring pixels mostly share their sets.
    std::vector<std::vector<uint8_t>> marked_sets(const std::vector<uint8_t>& records) const;
    /// Whether a look-up of the pixel interpolated a record that marked_sets() was given marked.
    bool interpolates_marked(size_t pixel, const std::vector<std::vector<uint8_t>>& marked_sets) const;
    size_t pixel_count() const { return m_pixels.size(); }
    /// The memory it holds.
    size_t bytes() const;
    /// The memory every pixel takes whatever it keeps (its KeptPixel).
    static size_t fixed_bytes_per_pixel() { return sizeof(KeptPixel); }

private:
    friend class StaticFrameMaker;

    /// How a sum is kept, 2 bits each in KeptPixel::kept; the coverage takes every_ray for 1.
    enum Kept : uint32_t { zero = 0, same_as_indirect = 1, every_ray = 1, stored = 2 };
    static constexpr int kept_sums = 4 + max_extra_layers;  // direct, indirect, caustic, specular, extras

    struct KeptPixel {
        PixelTrace trace;
        uint32_t at = 0;    // where its values start in its tile's bytes
        uint32_t kept = 0;  // Kept codes: sum i at bits 2i, covered after them
        uint8_t look_ups = 0, albedos = 0;
        bool same_rays = false;  // every camera ray's byte the same: kept once
    };

    size_t tile_of(size_t pixel) const;
    const std::byte* values_of(size_t pixel) const { return m_tiles[tile_of(pixel)].data() + m_pixels[pixel].at; }

    std::vector<KeptPixel, UnfilledAllocator<KeptPixel>> m_pixels;  // each made by StaticFrameMaker::begin
    std::vector<std::vector<std::byte>> m_tiles;                    // per shading tile, row by row
    std::vector<TileRecordSets> m_tile_record_sets;                 // per shading tile
    int m_tiles_x = 0;
    double m_inverse_width = 0;  // 1 / width, for tile_of
};

/// A static frame is kept only where it takes at most this share of the memory available (else
/// every frame shades every pixel).
constexpr double static_frame_memory_share = 0.25;

/// The pixel source that makes a static frame: every pixel shaded whole, its sums and what its
/// shading went through kept. When the frame's bytes grow past `max_bytes` (counted a shading
/// tile at a time, as tiles are done) it stops keeping values, and fits() says so (the frame must
/// then not be used). Its tiles' bytes may reserve up to as much again while it is made, until
/// finish_frame().
class StaticFrameMaker : public PixelSource, public PixelRecorder {
public:
    /// Fills `out`, made for `frame`'s camera at `samples` camera rays a pixel, whose look-ups
    /// interpolate `records` (kept: which of them each look-up used).
    StaticFrameMaker(StaticFrame& out, const FrameState& frame, int samples, const IrradianceCache& records,
                     double max_bytes);
    bool fits() const { return !m_too_big; }
    /// Gives back what the tiles' bytes reserved beyond their size; call once every pixel is shaded.
    void finish_frame();

    Shading begin(int, int, size_t pixel, PixelSums&) override;
    void finish(size_t pixel, PixelSums& sums) override;
    PixelRecorder* recorder() override { return this; }

    void add_point(size_t pixel, Vec3 p) override { m_out.m_pixels[pixel].trace.add_point(p); }
    void add_distant_direction(size_t pixel, Vec3 w) override { m_out.m_pixels[pixel].trace.add_distant_direction(w); }
    void add_flags(size_t pixel, uint8_t flags) override { m_out.m_pixels[pixel].trace.flags |= flags; }
    void add_surface_ray(size_t pixel) override { ++m_out.m_pixels[pixel].trace.surface_rays; }
    void add_look_up(size_t pixel, int sample, int entry, Vec3 p, Vec3 n, Rgb albedo_over_pi) override;
    void add_look_up_records(size_t pixel, int entry, const std::vector<uint32_t>& ids) override;

private:
    /// The look-ups of the pixel a tile is shading, until finish() packs them.
    struct Pending {
        std::array<Vec3, PixelMemo::capacity> p, n;
        int look_ups = 0;
        std::vector<Rgb> albedos;
        std::vector<uint8_t> rays;
        // Per look-up, the records it interpolated: as shading told them (has_ids), else found in finish().
        std::array<std::vector<uint32_t>, PixelMemo::capacity> ids;
        std::array<bool, PixelMemo::capacity> has_ids{};
    };
    /// The distinct sets of records a tile's look-ups interpolated, until its last pixel is
    /// finished and they are packed (so that only the tiles being shaded hold them unpacked), and
    /// the bytes of the tile's values, counted into the frame's once the tile is done.
    struct PendingSets {
        std::vector<uint32_t> sets;                         // in the order first met: size, then ids
        std::vector<uint32_t> at;                           // per set: where it starts in `sets`
        std::unordered_multimap<uint64_t, uint16_t> index;  // a set's checksum: the sets with it
        int pixels_done = 0;
        size_t value_bytes = 0;
    };
    /// The tile's set holding `ids`, added if it is new.
    uint16_t record_set(size_t tile, const std::vector<uint32_t>& ids);
    /// Packs the tile's record sets into the static frame.
    void pack_record_sets(size_t tile);

    StaticFrame& m_out;
    const IrradianceCache& m_records;
    std::vector<PendingSets> m_pending_sets;  // per tile
    std::vector<Pending> m_pending;           // per tile
    double m_max_bytes;
    std::atomic<size_t> m_bytes = 0;
    std::atomic<bool> m_too_big = false;
};

/// What a frame does with a pixel when it has a static frame.
enum class PixelWork : uint8_t {
    reuse,            // every term as the static frame has it
    look_up_again,    // only the indirect light changes: look it up again where the camera rays did, none traced
    direct_again,     // the direct light changes, maybe the indirect as look_up_again has it: only the
                      // direct light shaded again (camera and shadow rays), the rest reused or looked up
    redo_but_direct,  // shade again, but the direct light (no shadow rays) is the static frame's
    redo,             // shade again
};

/// The bits of the `changed` layer: which terms of a pixel a frame redid.
enum ChangedTerm : uint8_t { camera_term = 1, direct_term = 2, indirect_term = 4, caustic_term = 8 };

/// The work of every pixel of a frame, the terms that made it, and how many of each.
struct PixelPlan {
    std::vector<PixelWork> work;
    std::vector<uint8_t> changed;  // ChangedTerm bits
    long reused = 0, looked_up_again = 0, direct_again = 0, redone_but_direct = 0, redone = 0;
    long changed_pixels[4] = {};  // per ChangedTerm bit, in bit order
};

/// The pixel source of a frame that reuses a static frame: each pixel's work (plan_pixels), the
/// static frame's sums where a pixel is reused, and the method's values that change although the
/// pixel's terms do not.
class PixelReuse : public PixelSource {
public:
    PixelReuse(const StaticFrame& base, const PixelPlan& plan) : m_base(base), m_plan(plan) {}

    /// Gives a reused pixel's sums the method's layers that change between frames although its
    /// terms do not (the localized method's influence).
    std::function<void(int x, int y, const PixelTrace& trace, PixelSums& sums)> reused_layers;
    /// Gives a PixelWork::look_up_again pixel's sums (the static frame's) its indirect light and
    /// the method's layers, looked up again at the static frame's look-ups of pixel `index`
    /// (and a PixelWork::direct_again pixel's whose indirect term changed).
    std::function<void(int x, int y, size_t index, PixelSums& sums)> look_up_again;

    /// Keeps the direct light of PixelWork::direct_again pixels in `kept` as the frame shades it,
    /// and sums it from there where an earlier frame kept it, asking `tracer` (placed at the
    /// frame) about the dynamic objects alone.
    void keep_direct_light(KeptDirectLight& kept, const RayTracer& tracer) { m_kept = &kept, m_tracer = &tracer; }
    /// PixelWork::direct_again pixels whose direct light came from `kept`, so far.
    long direct_from_kept() const { return m_direct_from_kept; }

    const StaticFrame& base() const { return m_base; }
    Shading begin(int x, int y, size_t pixel, PixelSums& sums) override;
    void finish(size_t pixel, PixelSums& sums) override;
    DirectLightLog* direct_light_log(int x, int y, size_t pixel) override;

private:
    const StaticFrame& m_base;
    const PixelPlan& m_plan;
    KeptDirectLight* m_kept = nullptr;
    const RayTracer* m_tracer = nullptr;
    std::atomic<long> m_direct_from_kept = 0;
};

/// What changed in a frame against its static frame.
struct FrameChanges {
    std::vector<BoundingSphere> dynamic;  // the dynamic objects at this frame
    std::vector<uint8_t> near_dynamic;    // per pixel, row by row: pixels_near_dynamic(camera, dynamic)
    std::vector<BoundingSphere> lights;
    enum IndirectChange : uint8_t { records = 1, blend = 2 };
    std::vector<uint8_t> indirect;  // per pixel, row by row: IndirectChange bits, why its indirect light may change
    bool records_changed = false;   // some corrected record differs from the static one
    bool caustics_changed = false;  // the caustic map differs from the static one somewhere
    std::vector<uint8_t> caustic;   // per pixel: a diffuse point there may read changed caustic photons
    // Per corrected record: 1 where it differs from the static one. A pixel whose look-ups
    // interpolated none of them keeps its indirect light (empty: any may have).
    std::vector<uint8_t> changed_records;
};

/// What each pixel of a frame does against its static frame `base`, given what changed (the top
/// of this file says how it is told).
PixelPlan plan_pixels(const Camera& camera, const StaticFrame& base, const FrameChanges& changes);

/// The surface points a pixel's camera rays met, as the tests of its shadow rays see them.
BoundingSphere pixel_points(const PixelTrace& trace);
/// How much wider than its `points` a pixel's shadow rays are tested: a pixel's shadow rays to
/// a light may meet a dynamic object where may_meet_segments(object, points, light, slack).
float shadow_ray_slack(const BoundingSphere& points);

/// Whether sphere `s` may meet a ray from a point of sphere `from` along a unit direction in the
/// box [lo, hi] of directions in 127ths (PixelTrace::to_distant_lo, hi): conservative, never a
/// "no" for a ray that does.
bool may_meet_rays(const BoundingSphere& s, const BoundingSphere& from, std::array<int8_t, 3> lo,
                   std::array<int8_t, 3> hi);

/// How closely mark_sphere_on_screen() follows a sphere: its screen box (cheap: for many small
/// spheres), or within the box the pixels whose centre's ray comes within the sphere's angular
/// radius plus half a pixel's diagonal of its centre (a ray per pixel: for a few large ones).
enum class Outline { box, round };

/// Sets `mask` at every pixel whose camera rays may pass through `sphere` (the whole screen when
/// it reaches behind the camera).
void mark_sphere_on_screen(const Camera& camera, const BoundingSphere& sphere, std::vector<uint8_t>& mask,
                           Outline outline = Outline::box);

/// Per pixel, row by row, 1 where its camera rays may pass through one of the `dynamic` objects'
/// bounds (their round outlines), else 0: most of the screen, where a frame's camera rays meet
/// what the static frame's met.
std::vector<uint8_t> pixels_near_dynamic(const Camera& camera, const std::vector<BoundingSphere>& dynamic);

/// The pixels [x0, x1] x [y0, y1] (none when x1 < x0 or y1 < y0).
struct PixelBox {
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
};

/// mark_sphere_on_screen(camera, s, mask) for every sphere s of `spheres`, in parallel: a frame
/// marks the reach of thousands of records at production sizes.
void mark_spheres_on_screen(const Camera& camera, const std::vector<BoundingSphere>& spheres,
                            std::vector<uint8_t>& mask);

/// Whether a frame of `scene` at `frame` may reuse pixels of a static frame made at `static_frame`
/// of the same segment: the same camera, lights and emissions, and no dynamic object emits.
bool same_view_and_lights(const Scene& scene, const FrameState& frame, const FrameState& static_frame);

}  // namespace steadylight
