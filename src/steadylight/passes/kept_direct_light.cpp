// The kept direct light of pixels whose shadow rays alone may change (kept_direct_light.h).
#include "steadylight/passes/kept_direct_light.h"

#include <algorithm>
#include <cstring>

#include "steadylight/base/check.h"
#include "steadylight/passes/shading_pass.h"
#include "steadylight/shading/light.h"

namespace steadylight {
namespace {

/// A logged camera ray's first bytes: how many light samples it kept, and which of them aim at
/// lights from far away (bit k: sample k).
struct RayHead {
    uint8_t samples = 0;
    uint8_t distant = 0;
};

template <class T>
void append(std::vector<std::byte>& bytes, const T& value) {
    const size_t at = bytes.size();
    bytes.resize(at + sizeof(T));
    std::memcpy(bytes.data() + at, &value, sizeof(T));
}

template <class T>
T read(const std::byte*& at) {
    T value;
    std::memcpy(&value, at, sizeof(T));
    at += sizeof(T);
    return value;
}

}  // namespace

void DirectLightLog::start(size_t pixel) {
    m_pixel = pixel;
    m_started = true;
    m_bytes.clear();
    m_rays = 0;
    m_spoiled = false;
}

void DirectLightLog::add_ray(Vec3 p, Vec3 ng) {
    m_head = m_bytes.size();
    append(m_bytes, RayHead{});
    append(m_bytes, p);
    append(m_bytes, ng);
    ++m_rays;
}

void DirectLightLog::add_sample(Vec3 to, bool distant, Rgb value) {
    SL_CHECK(m_rays > 0);
    RayHead head;
    std::memcpy(&head, m_bytes.data() + m_head, sizeof(head));
    if (head.samples == max_samples_per_ray) {
        m_spoiled = true;
        return;
    }
    if (distant) head.distant = uint8_t(head.distant | (1u << head.samples));
    ++head.samples;
    std::memcpy(m_bytes.data() + m_head, &head, sizeof(head));
    append(m_bytes, to);
    append(m_bytes, value);
}

void KeptDirectLight::make(int width, int height, int samples, int direct_samples, double max_bytes) {
    std::call_once(m_once, [&] {
        m_width = width, m_height = height, m_samples = samples, m_direct_samples = direct_samples;
        m_tiles_x = (width + shading_tile_size - 1) / shading_tile_size;
        m_tiles.resize(size_t(m_tiles_x) * size_t((height + shading_tile_size - 1) / shading_tile_size));
        m_max_bytes = max_bytes;
    });
    SL_CHECK(m_width == width && m_height == height && m_samples == samples && m_direct_samples == direct_samples);
}

size_t KeptDirectLight::tile_of(int x, int y) const {
    return size_t(y / shading_tile_size) * size_t(m_tiles_x) + size_t(x / shading_tile_size);
}

int KeptDirectLight::slot_of(int x, int y) const {
    return y % shading_tile_size * shading_tile_size + x % shading_tile_size;
}

DirectLightLog* KeptDirectLight::log_for(int x, int y, size_t pixel) {
    if (m_direct_samples > DirectLightLog::max_samples_per_ray || double(m_bytes) >= m_max_bytes) return nullptr;
    Tile& tile = m_tiles[tile_of(x, y)];
    const int slot = slot_of(x, y);
    if (!tile.refused.empty() && (tile.refused[size_t(slot)] || tile.kept[size_t(slot)])) return nullptr;
    tile.log.start(pixel);
    return &tile.log;
}

void KeptDirectLight::keep(int x, int y, size_t pixel) {
    Tile& tile = m_tiles[tile_of(x, y)];
    if (!tile.log.logs(pixel)) return;
    tile.log.end();
    const DirectLightLog& log = tile.log;
    const bool whole = !log.spoiled() && log.rays() == m_samples;
    constexpr size_t slots = size_t(shading_tile_size) * size_t(shading_tile_size);
    const size_t bookkeeping = tile.kept.empty() ? slots * sizeof(std::unique_ptr<std::byte[]>) + slots / 8 : 0;
    const size_t size = whole ? log.bytes().size() : 0;
    // What does not fit is neither kept nor noted: a later frame may log it again if room is left.
    // The room is taken in one step with the test, so that threads racing for the last of it
    // never take more than the budget between them.
    size_t taken = m_bytes.load();
    do {
        if (double(taken + bookkeeping + size) > m_max_bytes) return;
    } while (!m_bytes.compare_exchange_weak(taken, taken + bookkeeping + size));
    if (bookkeeping) {
        tile.kept.resize(slots);
        tile.refused.assign(slots, false);
    }
    const size_t slot = size_t(slot_of(x, y));
    if (!whole) {
        tile.refused[slot] = true;
        return;
    }
    tile.kept[slot] = std::make_unique_for_overwrite<std::byte[]>(size);
    std::copy(log.bytes().begin(), log.bytes().end(), tile.kept[slot].get());
    ++m_pixels;
}

const std::byte* KeptDirectLight::find(int x, int y) const {
    if (m_tiles.empty()) return nullptr;
    const Tile& tile = m_tiles[tile_of(x, y)];
    if (tile.kept.empty()) return nullptr;
    return tile.kept[size_t(slot_of(x, y))].get();
}

Rgb KeptDirectLight::direct_light(const std::byte* kept, const RayTracer& tracer) const {
    // As shade_frame() sums a pixel's direct light: per camera ray the sum of its light samples
    // over their count (Shader::direct_light), added where finite.
    Rgb direct;
    for (int ray = 0; ray < m_samples; ++ray) {
        const RayHead head = read<RayHead>(kept);
        const Vec3 p = read<Vec3>(kept), ng = read<Vec3>(kept);
        Rgb sum;
        for (int k = 0; k < head.samples; ++k) {
            const Vec3 to = read<Vec3>(kept);
            const Rgb value = read<Rgb>(kept);
            if (!tracer.occluded_by_dynamic(shadow_ray(p, ng, to, (head.distant >> k) & 1))) sum += value;
        }
        Rgb c;
        c += sum / float(m_direct_samples);
        if (is_finite(c)) direct += c;
    }
    return direct;
}

}  // namespace steadylight
