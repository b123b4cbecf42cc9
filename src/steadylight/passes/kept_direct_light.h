// The direct light of the pixels a frame shades again only because their shadow rays may meet a
// dynamic object (PixelWork::direct_again, pixel_reuse.h), kept light sample by light sample so
// that later frames of the segment ask the dynamic objects alone. Such a pixel's camera rays meet
// what the static frame's met, so every light sample, BSDF value and shadow ray is the same in
// every frame of the segment, and a shadow ray that a static object stops stays stopped; only
// whether a dynamic object stops the others changes. The first frame that shades the pixel's
// direct light logs, per camera ray, the point its shadow rays leave and, per light sample that
// the static objects do not stop, where its shadow ray aims and what it gives unstopped; a later
// frame sums those whose ray no dynamic object stops (RayTracer::occluded_by_dynamic, the
// frame's own decision), in the shading's order: the same bits as shading the pixel's direct
// light, without sampling the lights or tracing its camera rays
// (docs/localized.md, "Pixels reused").
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "steadylight/base/color.h"
#include "steadylight/base/vec.h"
#include "steadylight/trace/ray_tracer.h"

namespace steadylight {

/// What one pixel's direct light went through while a frame shaded it (direct light only), as
/// the shading pass tells it (PixelSample::direct_log). A camera ray whose direct light is more
/// than its light samples' sum (an emitter or the sky seen, a glossy point, absorbing glass)
/// spoils it: such a pixel is shaded in every frame.
class DirectLightLog {
public:
    /// Light samples a camera ray may take for its pixel to be kept (a byte of bits tells which
    /// of them aim at lights from far away).
    static constexpr int max_samples_per_ray = 8;

    /// Starts pixel `pixel`'s log.
    void start(size_t pixel);
    /// Whether it is pixel `pixel`'s, started and not yet ended.
    bool logs(size_t pixel) const { return m_started && m_pixel == pixel; }
    void end() { m_started = false; }
    /// A camera ray whose shadow rays leave `p` (geometric normal `ng`).
    void add_ray(Vec3 p, Vec3 ng);
    /// A light sample of the last camera ray whose shadow ray the static objects do not stop:
    /// aimed at `to` (shadow_ray()), giving `value` when nothing stops it.
    void add_sample(Vec3 to, bool distant, Rgb value);
    void spoil() { m_spoiled = true; }
    bool spoiled() const { return m_spoiled; }
    int rays() const { return m_rays; }
    const std::vector<std::byte>& bytes() const { return m_bytes; }

private:
    size_t m_pixel = 0;
    bool m_started = false;
    std::vector<std::byte> m_bytes;  // per ray a RayHead, p and ng, then its samples: to and value
    size_t m_head = 0;               // where the last ray's RayHead is
    int m_rays = 0;
    bool m_spoiled = false;
};

/// The kept direct light of a segment's pixels, filled by its frames one frame at a time (the
/// pixels of one shading tile by one thread at a time), up to a number of bytes.
class KeptDirectLight {
public:
    /// Bytes a pixel of the image that it may take on average: beside the static frame's 110 or
    /// so, a still camera keeps at most 150 bytes a pixel (docs/notes/reuse-memory.md).
    static constexpr double max_bytes_per_pixel = 40;

    /// For a `width` x `height` view shaded with `samples` camera rays a pixel and
    /// `direct_samples` light samples a camera ray, keeping up to about `max_bytes`; once
    /// (thread-safe; later calls must agree).
    void make(int width, int height, int samples, int direct_samples, double max_bytes);

    /// The log for pixel (x, y), number `pixel` row by row, when the pixel should be kept: not
    /// kept yet, not refused before, and room left; else null.
    DirectLightLog* log_for(int x, int y, size_t pixel);
    /// Keeps the log of pixel (x, y), number `pixel`, if log_for() started one, when it is whole
    /// (each camera ray logged, none spoiled) and fits. A pixel whose log is not whole is not
    /// logged again; one that did not fit may be, while room is left.
    void keep(int x, int y, size_t pixel);
    /// Pixel (x, y)'s kept light samples, or null.
    const std::byte* find(int x, int y) const;
    /// The pixel's direct light summed over its camera rays as the shading pass sums it, with
    /// `tracer` placed at the frame: each kept light sample counted where no dynamic object stops
    /// its shadow ray.
    Rgb direct_light(const std::byte* kept, const RayTracer& tracer) const;

    /// The memory it holds.
    size_t bytes() const { return m_bytes; }
    long pixels() const { return m_pixels; }

private:
    /// A shading tile's pixels: made when the first of them is logged.
    struct Tile {
        DirectLightLog log;                              // the pixel being shaded
        std::vector<std::unique_ptr<std::byte[]>> kept;  // per pixel of the tile, row by row in it
        std::vector<bool> refused;
    };
    size_t tile_of(int x, int y) const;
    int slot_of(int x, int y) const;

    std::once_flag m_once;
    int m_width = 0, m_height = 0, m_samples = 0, m_direct_samples = 0, m_tiles_x = 0;
    std::vector<Tile> m_tiles;
    double m_max_bytes = 0;
    std::atomic<size_t> m_bytes = 0;
    std::atomic<long> m_pixels = 0;
};

}  // namespace steadylight
