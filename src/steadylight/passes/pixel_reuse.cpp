#include "steadylight/passes/pixel_reuse.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <mutex>
#include <optional>

#include "steadylight/base/hash.h"
#include "steadylight/base/parallel.h"

namespace steadylight {

namespace {

/// Sum `i` of a pixel's sums, in StaticFrame's order: direct, indirect, caustic, specular, extras.
Rgb& sum_at(PixelSums& sums, int i) {
    switch (i) {
        case 0:
            return sums.direct;
        case 1:
            return sums.indirect;
        case 2:
            return sums.caustic;
        case 3:
            return sums.specular;
        default:
            return sums.extra[size_t(i - 4)];
    }
}

template <class T>
T read(const std::byte* at) {
    T value;
    std::memcpy(&value, at, sizeof(T));
    return value;
}

template <class T>
void append(std::vector<std::byte>& bytes, const T& value) {
    const size_t at = bytes.size();
    bytes.resize(at + sizeof(T));
    std::memcpy(bytes.data() + at, &value, sizeof(T));
}

bool same_bits(Rgb a, Rgb b) { return std::memcmp(&a, &b, sizeof(Rgb)) == 0; }

// A point, a normal and which of the tile's record sets it interpolated.
constexpr size_t look_up_bytes = 2 * sizeof(Vec3) + sizeof(uint16_t);

}  // namespace

Vec3 KeptLookUps::point(int look_up) const { return read<Vec3>(m_look_ups + size_t(look_up) * look_up_bytes); }

Vec3 KeptLookUps::normal(int look_up) const {
    return read<Vec3>(m_look_ups + size_t(look_up) * look_up_bytes + sizeof(Vec3));
}

int KeptLookUps::record_set(int look_up) const {
    return read<uint16_t>(m_look_ups + size_t(look_up) * look_up_bytes + 2 * sizeof(Vec3));
}

void KeptLookUps::records(int look_up, std::vector<uint32_t>& out) const {
    m_record_sets->get(record_set(look_up), out);
}

std::vector<uint8_t> TileRecordSets::sets_meeting(const std::vector<uint8_t>& records) const {
    std::vector<uint64_t> marked(size_t(words), 0);
    for (size_t i = 0; i < ids.size(); ++i)
        if (records[ids[i]]) marked[i / 64] |= uint64_t(1) << (i % 64);
    std::vector<uint8_t> meeting(size_t(sets), 0);
    for (int set = 0; set < sets; ++set)
        for (int word = 0; word < words; ++word)
            if (bits[size_t(set * words + word)] & marked[size_t(word)]) {
                meeting[size_t(set)] = 1;
                break;
            }
    return meeting;
}

void TileRecordSets::get(int set, std::vector<uint32_t>& out) const {
    out.clear();
    for (int word = 0; word < words; ++word)
        for (uint64_t bits_left = bits[size_t(set * words + word)]; bits_left; bits_left &= bits_left - 1)
            out.push_back(ids[size_t(word * 64 + std::countr_zero(bits_left))]);
}

TileRecordSets TileRecordSets::of(const std::vector<uint32_t>& sets) {
    // Each set's ids lie at [begin + 1, begin + 1 + sets[begin]).
    const auto for_each_set = [&](auto&& f) {
        size_t set = 0;
        for (size_t begin = 0; begin < sets.size(); begin += 1 + sets[begin], ++set)
            f(set, sets.begin() + ptrdiff_t(begin + 1), sets.begin() + ptrdiff_t(begin + 1 + sets[begin]));
        return set;
    };
    TileRecordSets packed;
    const size_t count =
        for_each_set([&](size_t, auto first, auto last) { packed.ids.insert(packed.ids.end(), first, last); });
    std::sort(packed.ids.begin(), packed.ids.end());
    packed.ids.erase(std::unique(packed.ids.begin(), packed.ids.end()), packed.ids.end());
    packed.ids.shrink_to_fit();
    packed.words = int((packed.ids.size() + 63) / 64);
    packed.sets = int(count);
    packed.bits.assign(count * size_t(packed.words), 0);
    for_each_set([&](size_t set, auto first, auto last) {
        for (auto id = first; id != last; ++id) {
            const size_t at = size_t(std::lower_bound(packed.ids.begin(), packed.ids.end(), *id) - packed.ids.begin());
            packed.bits[set * size_t(packed.words) + at / 64] |= uint64_t(1) << (at % 64);
        }
    });
    return packed;
}

Rgb KeptLookUps::albedo(int ray) const { return read<Rgb>(m_albedos + size_t(ray_byte(ray) >> 2) * sizeof(Rgb)); }

size_t StaticFrame::tile_of(size_t pixel) const {
    // The row by a multiplication, put right where rounding left it one off: a division took
    // most of the time of recording a camera ray's look-up, which asks this each time.
    size_t y = size_t(double(pixel) * m_inverse_width);
    if (y * size_t(width) > pixel)
        --y;
    else if ((y + 1) * size_t(width) <= pixel)
        ++y;
    const size_t x = pixel - y * size_t(width);
    return y / shading_tile_size * size_t(m_tiles_x) + x / shading_tile_size;
}

PixelSums StaticFrame::sums(size_t pixel) const {
    const KeptPixel& kept = m_pixels[pixel];
    const std::byte* at = values_of(pixel);
    PixelSums sums;
    for (int i = 0; i < kept_sums; ++i)
        if (((kept.kept >> (2 * i)) & 3) == stored) sum_at(sums, i) = read<Rgb>(at), at += sizeof(Rgb);
    for (int i = 0; i < kept_sums; ++i)
        if (((kept.kept >> (2 * i)) & 3) == same_as_indirect) sum_at(sums, i) = sums.indirect;
    const uint32_t covered = (kept.kept >> (2 * kept_sums)) & 3;
    sums.covered = covered == stored ? read<float>(at) : covered == every_ray ? float(samples) : 0.0f;
    return sums;
}

Rgb StaticFrame::direct(size_t pixel) const {
    // The direct sum is sum 0 and the indirect one sum 1: whichever is stored comes first.
    const KeptPixel& kept = m_pixels[pixel];
    const uint32_t direct = kept.kept & 3, indirect = (kept.kept >> 2) & 3;
    if (direct == stored || (direct == same_as_indirect && indirect == stored)) return read<Rgb>(values_of(pixel));
    return {};
}

KeptLookUps StaticFrame::look_ups(size_t pixel) const {
    const KeptPixel& kept = m_pixels[pixel];
    if (kept.look_ups == 0) return {};
    const std::byte* at = values_of(pixel);
    for (int i = 0; i < kept_sums; ++i) at += ((kept.kept >> (2 * i)) & 3) == stored ? sizeof(Rgb) : 0;
    at += ((kept.kept >> (2 * kept_sums)) & 3) == stored ? sizeof(float) : 0;
    const std::byte* albedos = at + kept.look_ups * look_up_bytes;
    return {kept.look_ups,  at,
            albedos,        reinterpret_cast<const uint8_t*>(albedos + kept.albedos * sizeof(Rgb)),
            kept.same_rays, &m_tile_record_sets[tile_of(pixel)]};
}

std::vector<std::vector<uint8_t>> StaticFrame::marked_sets(const std::vector<uint8_t>& records) const {
    std::vector<std::vector<uint8_t>> marked(m_tile_record_sets.size());
    parallel_for_chunks(long(marked.size()), 64, [&](long begin, long end) {
        for (long tile = begin; tile < end; ++tile)
            marked[size_t(tile)] = m_tile_record_sets[size_t(tile)].sets_meeting(records);
    });
    return marked;
}

bool StaticFrame::interpolates_marked(size_t pixel, const std::vector<std::vector<uint8_t>>& marked_sets) const {
    const KeptLookUps kept = look_ups(pixel);
    const std::vector<uint8_t>& tile_sets = marked_sets[tile_of(pixel)];
    for (int i = 0; i < kept.count(); ++i)
        if (tile_sets[size_t(kept.record_set(i))]) return true;
    return false;
}

size_t StaticFrame::bytes() const {
    size_t bytes = m_pixels.capacity() * sizeof(KeptPixel) + m_tiles.capacity() * sizeof(m_tiles[0]);
    for (const std::vector<std::byte>& tile : m_tiles) bytes += tile.capacity();
    bytes += m_tile_record_sets.capacity() * sizeof(m_tile_record_sets[0]);
    for (const TileRecordSets& sets : m_tile_record_sets) bytes += sets.bytes();
    return bytes;
}

StaticFrameMaker::StaticFrameMaker(StaticFrame& out, const FrameState& frame, int samples,
                                   const IrradianceCache& records, double max_bytes)
    : m_out(out), m_records(records), m_max_bytes(max_bytes) {
    const Camera& camera = frame.camera;
    out.made_at = frame;
    out.width = camera.width, out.height = camera.height, out.samples = samples;
    out.m_pixels.clear();
    out.m_pixels.resize(size_t(camera.width) * size_t(camera.height));  // each made by begin()
    out.m_tiles_x = (camera.width + shading_tile_size - 1) / shading_tile_size;
    out.m_inverse_width = 1.0 / camera.width;
    const size_t tiles = size_t(out.m_tiles_x) * size_t((camera.height + shading_tile_size - 1) / shading_tile_size);
    out.m_tiles.assign(tiles, {});
    out.m_tile_record_sets.assign(tiles, {});
    m_pending.resize(tiles);
    m_pending_sets.resize(tiles);
    m_bytes = out.m_pixels.size() * sizeof(StaticFrame::KeptPixel);
}

PixelSource::Shading StaticFrameMaker::begin(int, int, size_t pixel, PixelSums&) {
    m_out.m_pixels[pixel] = {};
    Pending& pending = m_pending[m_out.tile_of(pixel)];
    pending.look_ups = 0;
    pending.albedos.clear();
    pending.rays.clear();
    pending.has_ids.fill(false);
    return Shading::all;
}

void StaticFrameMaker::add_look_up_records(size_t pixel, int entry, const std::vector<uint32_t>& ids) {
    Pending& pending = m_pending[m_out.tile_of(pixel)];
    pending.ids[size_t(entry)] = ids;
    pending.has_ids[size_t(entry)] = true;
}

void StaticFrameMaker::add_look_up(size_t pixel, int sample, int entry, Vec3 p, Vec3 n, Rgb albedo_over_pi) {
    Pending& pending = m_pending[m_out.tile_of(pixel)];
    if (pending.rays.empty()) pending.rays.assign(size_t(m_out.samples), KeptLookUps::no_ray);
    pending.p[size_t(entry)] = p, pending.n[size_t(entry)] = n;
    pending.look_ups = std::max(pending.look_ups, entry + 1);
    const auto known = std::find_if(pending.albedos.begin(), pending.albedos.end(),
                                    [&](Rgb a) { return same_bits(a, albedo_over_pi); });
    const size_t albedo = size_t(known - pending.albedos.begin());
    if (known == pending.albedos.end()) {
        // A textured surface can give every camera ray an albedo of its own: past this many the
        // pixel's look-ups are not kept (it is shaded again when its records change).
        if (albedo == KeptLookUps::max_albedos) {
            add_flags(pixel, PixelRecorder::unkept);
            return;
        }
        pending.albedos.push_back(albedo_over_pi);
    }
    pending.rays[size_t(sample)] = uint8_t(entry | int(albedo << 2));
}

void StaticFrameMaker::finish(size_t pixel, PixelSums& sums) {
    if (m_too_big) return;
    StaticFrame::KeptPixel& kept = m_out.m_pixels[pixel];
    std::vector<std::byte>& bytes = m_out.m_tiles[m_out.tile_of(pixel)];
    kept.at = uint32_t(bytes.size());
    for (int i = 0; i < StaticFrame::kept_sums; ++i) {
        const Rgb value = sum_at(sums, i);
        const uint32_t how = same_bits(value, Rgb{})                     ? StaticFrame::zero
                             : i != 1 && same_bits(value, sums.indirect) ? StaticFrame::same_as_indirect
                                                                         : StaticFrame::stored;
        kept.kept |= how << (2 * i);
        if (how == StaticFrame::stored) append(bytes, value);
    }
    const uint32_t covered = sums.covered == 0                      ? StaticFrame::zero
                             : sums.covered == float(m_out.samples) ? StaticFrame::every_ray
                                                                    : StaticFrame::stored;
    kept.kept |= covered << (2 * StaticFrame::kept_sums);
    if (covered == StaticFrame::stored) append(bytes, sums.covered);
    const size_t tile = m_out.tile_of(pixel);
    Pending& pending = m_pending[tile];
    if (!(kept.trace.flags & PixelRecorder::unkept) && pending.look_ups > 0) {
        kept.look_ups = uint8_t(pending.look_ups), kept.albedos = uint8_t(pending.albedos.size());
        for (int i = 0; i < pending.look_ups; ++i) {
            // The records its look-up used: at the first reach that found any, as shading looks up.
            const Vec3 p = pending.p[size_t(i)], n = pending.n[size_t(i)];
            std::vector<uint32_t>& ids = pending.ids[size_t(i)];
            if (!pending.has_ids[size_t(i)]) {
                m_records.usable_ids(p, n, 1, ids);
                if (ids.empty()) m_records.usable_ids(p, n, 2, ids);
            }
            append(bytes, p), append(bytes, n), append(bytes, record_set(tile, ids));
        }
        for (const Rgb albedo : pending.albedos) append(bytes, albedo);
        // Most pixels' camera rays all look up one point under one albedo.
        kept.same_rays =
            std::all_of(pending.rays.begin(), pending.rays.end(), [&](uint8_t ray) { return ray == pending.rays[0]; });
        if (kept.same_rays)
            append(bytes, pending.rays[0]);
        else
            for (const uint8_t ray : pending.rays) append(bytes, ray);
    }
    PendingSets& sets = m_pending_sets[tile];
    sets.value_bytes += bytes.size() - kept.at;
    // The tile's last pixel: its record sets are complete.
    const int tile_x = int(tile % size_t(m_out.m_tiles_x)), tile_y = int(tile / size_t(m_out.m_tiles_x));
    const int tile_pixels = std::min(shading_tile_size, m_out.width - tile_x * shading_tile_size) *
                            std::min(shading_tile_size, m_out.height - tile_y * shading_tile_size);
    if (++sets.pixels_done == tile_pixels) pack_record_sets(tile);
}

uint16_t StaticFrameMaker::record_set(size_t tile, const std::vector<uint32_t>& ids) {
    // A tile has at most shading_tile_size^2 pixels of PixelMemo::capacity look-ups each.
    static_assert(shading_tile_size * shading_tile_size * PixelMemo::capacity <= 65536);
    PendingSets& pending = m_pending_sets[tile];
    const uint64_t checksum = checksum64(ids.data(), ids.size() * sizeof(uint32_t));
    for (auto [same, end] = pending.index.equal_range(checksum); same != end; ++same) {
        const auto first = pending.sets.begin() + ptrdiff_t(pending.at[same->second]);
        if (*first == ids.size() && std::equal(ids.begin(), ids.end(), first + 1)) return same->second;
    }
    const auto set = uint16_t(pending.at.size());
    pending.at.push_back(uint32_t(pending.sets.size()));
    pending.sets.push_back(uint32_t(ids.size()));
    pending.sets.insert(pending.sets.end(), ids.begin(), ids.end());
    pending.index.emplace(checksum, set);
    return set;
}

void StaticFrameMaker::pack_record_sets(size_t tile) {
    PendingSets& pending = m_pending_sets[tile];
    TileRecordSets& packed = m_out.m_tile_record_sets[tile];
    packed = TileRecordSets::of(pending.sets);
    if (double(m_bytes += pending.value_bytes + packed.bytes()) > m_max_bytes) m_too_big = true;
    pending = {};
}

void StaticFrameMaker::finish_frame() {
    for (std::vector<std::byte>& tile : m_out.m_tiles) tile.shrink_to_fit();
    for (size_t tile = 0; tile < m_pending_sets.size(); ++tile)
        if (!m_pending_sets[tile].sets.empty()) pack_record_sets(tile);  // a tile not shaded whole
}

void PixelTrace::add_distant_direction(Vec3 w) {
    for (int axis = 0; axis < 3; ++axis) {
        const float scaled = w[axis] * 127;
        to_distant_lo[size_t(axis)] =
            std::min(to_distant_lo[size_t(axis)], int8_t(std::clamp(std::floor(scaled), -127.0f, 127.0f)));
        to_distant_hi[size_t(axis)] =
            std::max(to_distant_hi[size_t(axis)], int8_t(std::clamp(std::ceil(scaled), -127.0f, 127.0f)));
    }
}

// The box's cone: about the direction of its centre, out to its farthest corner. A ray from a
// point p of `from` that meets s is the ray from from's centre along the same direction, moved
// by at most from's radius: it meets s widened by that radius, which from the centre lies within
// its angular radius of the direction towards it.
bool may_meet_rays(const BoundingSphere& s, const BoundingSphere& from, std::array<int8_t, 3> lo,
                   std::array<int8_t, 3> hi) {
    if (s.empty() || from.empty()) return false;
    const Vec3 box_lo{float(lo[0]), float(lo[1]), float(lo[2])}, box_hi{float(hi[0]), float(hi[1]), float(hi[2])};
    const Vec3 to_s = s.center - from.center;
    const float distance = length(to_s), reach = s.radius + from.radius;
    if (distance <= reach) return true;
    // A box holding the origin (or touching it) leaves every direction open.
    if (box_lo.x <= 0 && box_hi.x >= 0 && box_lo.y <= 0 && box_hi.y >= 0 && box_lo.z <= 0 && box_hi.z >= 0) return true;
    const Vec3 axis = normalize((box_lo + box_hi) * 0.5f);
    float cone = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 c{corner & 1 ? box_hi.x : box_lo.x, corner & 2 ? box_hi.y : box_lo.y,
                     corner & 4 ? box_hi.z : box_lo.z};
        cone = std::max(cone, std::acos(std::clamp(dot(axis, normalize(c)), -1.0f, 1.0f)));
    }
    const float angle_to_s = std::acos(std::clamp(dot(axis, to_s / distance), -1.0f, 1.0f));
    // A margin for rounding: a thousandth of a radian.
    return angle_to_s <= cone + std::asin(reach / distance) + 1e-3f;
}

PixelSource::Shading PixelReuse::begin(int x, int y, size_t pixel, PixelSums& sums) {
    const PixelWork work = m_plan.work[pixel];
    if (work == PixelWork::redo) return Shading::all;
    if (work == PixelWork::redo_but_direct) return Shading::all_but_direct;
    sums = m_base.sums(pixel);
    if (reused_layers) reused_layers(x, y, m_base.trace(pixel), sums);
    if (work == PixelWork::look_up_again ||
        (work == PixelWork::direct_again && (m_plan.changed[pixel] & indirect_term)))
        look_up_again(x, y, pixel, sums);
    if (work != PixelWork::direct_again) return Shading::none;
    if (const std::byte* kept = m_kept ? m_kept->find(x, y) : nullptr) {
        sums.direct = m_kept->direct_light(kept, *m_tracer);
        ++m_direct_from_kept;
        return Shading::none;
    }
    return Shading::direct_only;
}

DirectLightLog* PixelReuse::direct_light_log(int x, int y, size_t pixel) {
    return m_kept && m_plan.work[pixel] == PixelWork::direct_again ? m_kept->log_for(x, y, pixel) : nullptr;
}

void PixelReuse::finish(size_t pixel, PixelSums& sums) {
    const PixelWork work = m_plan.work[pixel];
    if (work == PixelWork::redo_but_direct) sums.direct = m_base.direct(pixel);
    if (work == PixelWork::direct_again && m_kept) {
        const int x = int(pixel % size_t(m_base.width)), y = int(pixel / size_t(m_base.width));
        m_kept->keep(x, y, pixel);
    }
}

namespace {

/// Where a sphere lies on the screen: the pixels whose rays may pass through it lie in `box`,
/// and among them those whose centre's ray is within the sphere's angular reach (its cosine
/// `min_cos`, about `to_centre` of length `distance`).
struct ScreenReach {
    PixelBox box;
    Vec3 to_centre;
    float distance = 0, reach = 0;
};

ScreenReach screen_reach(const Camera& camera, const BoundingSphere& sphere) {
    ScreenReach out;
    if (sphere.empty()) return out;
    const Vec3 eye = camera.generate_ray(0, 0).o;
    out.to_centre = sphere.center - eye;
    out.distance = length(out.to_centre);
    // A pixel's rays leave within this angle of its centre's ray: half its diagonal, widest at
    // the image's centre, with a margin for rounding.
    const float pixel_angle = std::atan(std::sqrt(2.0f) * camera.tan_half_fov_y / float(camera.height)) * 1.05f + 1e-6f;
    // Beyond this angle from the centre's direction, a ray misses the sphere.
    out.reach = out.distance > sphere.radius ? std::asin(sphere.radius / out.distance) + pixel_angle : pi;
    float x_lo = 0, y_lo = 0, x_hi = float(camera.width), y_hi = float(camera.height);
    if (out.reach < pi / 2) {
        // The corners of the sphere's cube: their screen box holds the sphere's, if all are in front.
        x_lo = y_lo = infinity, x_hi = y_hi = -infinity;
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 offset{corner & 1 ? 1.0f : -1.0f, corner & 2 ? 1.0f : -1.0f, corner & 4 ? 1.0f : -1.0f};
            const std::optional<Vec2> at = camera.project(sphere.center + offset * sphere.radius);
            if (!at || !std::isfinite(at->x) || !std::isfinite(at->y)) {
                x_lo = y_lo = 0, x_hi = float(camera.width), y_hi = float(camera.height);
                break;
            }
            x_lo = std::min(x_lo, at->x), x_hi = std::max(x_hi, at->x);
            y_lo = std::min(y_lo, at->y), y_hi = std::max(y_hi, at->y);
        }
    }
    if (x_hi < -1 || y_hi < -1 || x_lo > float(camera.width) + 1 || y_lo > float(camera.height) + 1) return out;
    // A pixel more each way (rounding in the projection).
    out.box = {std::max(int(std::floor(x_lo)) - 1, 0), std::max(int(std::floor(y_lo)) - 1, 0),
               std::min(int(std::ceil(x_hi)) + 1, camera.width - 1),
               std::min(int(std::ceil(y_hi)) + 1, camera.height - 1)};
    return out;
}

}  // namespace

void mark_sphere_on_screen(const Camera& camera, const BoundingSphere& sphere, std::vector<uint8_t>& mask,
                           Outline outline) {
    const ScreenReach on_screen = screen_reach(camera, sphere);
    const PixelBox& box = on_screen.box;
    // Within the box, the pixels whose rays come within the sphere's angular reach.
    const bool round = outline == Outline::round && on_screen.reach < pi;
    const float min_cos = round ? std::cos(on_screen.reach) : -2.0f;
    for (int y = box.y0; y <= box.y1; ++y)
        for (int x = box.x0; x <= box.x1; ++x)
            if (!round || dot(camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f).d, on_screen.to_centre) >=
                              min_cos * on_screen.distance)
                mask[size_t(y) * size_t(camera.width) + size_t(x)] = 1;
}

std::vector<uint8_t> pixels_near_dynamic(const Camera& camera, const std::vector<BoundingSphere>& dynamic) {
    std::vector<uint8_t> near(size_t(camera.width) * size_t(camera.height), 0);
    for (const BoundingSphere& object : dynamic) mark_sphere_on_screen(camera, object, near, Outline::round);
    return near;
}

void mark_spheres_on_screen(const Camera& camera, const std::vector<BoundingSphere>& spheres,
                            std::vector<uint8_t>& mask) {
    std::vector<PixelBox> boxes(spheres.size());
    parallel_for_chunks(long(spheres.size()), 256, [&](long begin, long end) {
        for (long i = begin; i < end; ++i) boxes[size_t(i)] = screen_reach(camera, spheres[size_t(i)]).box;
    });
    // By bands of rows, each marking every box's part of it.
    constexpr int band = 8;
    parallel_for_chunks((camera.height + band - 1) / band, 1, [&](long begin, long end) {
        const int y_begin = int(begin) * band, y_end = std::min(int(end) * band, camera.height);
        for (const PixelBox& box : boxes)
            for (int y = std::max(box.y0, y_begin); y <= std::min(box.y1, y_end - 1); ++y)
                std::fill_n(mask.begin() + ptrdiff_t(size_t(y) * size_t(camera.width) + size_t(box.x0)),
                            std::max(box.x1 - box.x0 + 1, 0), uint8_t(1));
    });
}

BoundingSphere pixel_points(const PixelTrace& trace) { return BoundingSphere::of_box(trace.lo, trace.hi); }

float shadow_ray_slack(const BoundingSphere& points) {
    // Shadow rays start a ray offset off their surface; a millionth of the scene's size is more.
    return points.empty() ? 0 : 1e-5f * (1 + length(points.center) + points.radius);
}

namespace {

/// Square tiles of pixels whose shadow rays cannot meet a dynamic object on their way to a
/// light, told by one test a tile instead of one a pixel: most of a frame's tiles lie far from
/// the hull of any object's shadow. A tile's test takes a sphere holding each of its pixels'
/// points and their largest slack, and grows the object by a margin far beyond the tests'
/// rounding (a ten-thousandth of the spheres' scale). A pixel's hull of segments to the light
/// lies within the tile's, so its distance from the object is at least the tile's: a tile's
/// "no" is then every pixel's computed "no", and the plan is the one tested pixel by pixel.
class ShadowFreeTiles {
public:
    ShadowFreeTiles(const Camera& camera, const StaticFrame& base, const FrameChanges& changes)
        : m_width(camera.width),
          m_tiles_x((camera.width + size - 1) / size),
          m_pairs(changes.dynamic.size() * changes.lights.size()) {
        const int tiles_y = (camera.height + size - 1) / size;
        m_free.assign(size_t(m_tiles_x) * size_t(tiles_y) * m_pairs, 0);
        parallel_for_chunks(long(m_tiles_x) * tiles_y, 64, [&](long begin, long end) {
            for (long tile = begin; tile < end; ++tile) {
                const int x0 = int(tile % m_tiles_x) * size, y0 = int(tile / m_tiles_x) * size;
                const int x1 = std::min(x0 + size, camera.width), y1 = std::min(y0 + size, camera.height);
                const auto each_pixel = [&](auto&& f) {
                    for (int y = y0; y < y1; ++y)
                        for (int x = x0; x < x1; ++x) f(base.trace(size_t(y) * size_t(m_width) + size_t(x)));
                };
                Vec3 lo{infinity, infinity, infinity}, hi{-infinity, -infinity, -infinity};
                each_pixel([&](const PixelTrace& trace) { lo = min(lo, trace.lo), hi = max(hi, trace.hi); });
                BoundingSphere points = BoundingSphere::of_box(lo, hi);
                float slack = 0;
                if (!points.empty()) {
                    // The sphere about the tile's box need not hold a pixel's sphere (a thin box
                    // at its edge pokes out): its radius reaches the farthest pixel sphere's rim.
                    points.radius = 0;
                    each_pixel([&](const PixelTrace& trace) {
                        const BoundingSphere pixel = pixel_points(trace);
                        if (pixel.empty()) return;
                        points.radius = std::max(points.radius, length(pixel.center - points.center) + pixel.radius);
                        slack = std::max(slack, shadow_ray_slack(pixel));
                    });
                }
                uint8_t* tile_free = m_free.data() + size_t(tile) * m_pairs;
                for (const BoundingSphere& object : changes.dynamic)
                    for (const BoundingSphere& light : changes.lights) {
                        const float margin =
                            1e-4f * (1 + length(object.center) + object.radius + length(points.center) + points.radius +
                                     length(light.center) + light.radius);
                        *tile_free++ = !may_meet_segments(object, points, light, slack + margin);
                    }
            }
        });
    }

    /// Whether pixel (x, y) lies in a tile whose shadow rays cannot meet object o on their way
    /// to light l, for each (o, l) in turn (objects outer).
    const uint8_t* free_pairs(int x, int y) const {
        return m_free.data() + (size_t(y / size) * size_t(m_tiles_x) + size_t(x / size)) * m_pairs;
    }

    /// Whether every pair of `pairs`, as free_pairs gives them, is free.
    bool all_free(const uint8_t* pairs) const {
        return std::all_of(pairs, pairs + m_pairs, [](uint8_t f) { return f; });
    }

private:
    static constexpr int size = 8;
    int m_width, m_tiles_x;
    size_t m_pairs;
    std::vector<uint8_t> m_free;  // per tile, per (object, light) pair
};

}  // namespace

PixelPlan plan_pixels(const Camera& camera, const StaticFrame& base, const FrameChanges& changes) {
    const size_t pixels = base.pixel_count();
    PixelPlan plan;
    plan.work.resize(pixels);
    plan.changed.assign(pixels, 0);
    const std::vector<std::vector<uint8_t>> changed_sets = changes.changed_records.empty()
                                                               ? std::vector<std::vector<uint8_t>>{}
                                                               : base.marked_sets(changes.changed_records);
    const ShadowFreeTiles shadow_free(camera, base, changes);
    std::mutex counts_lock;
    // Row by row: a pixel's tile comes from its x and y, and each range of rows adds its counts.
    parallel_for_chunks(camera.height, 4, [&](long y_begin, long y_end) {
        long counts[5] = {}, changed_pixels[4] = {};
        for (int y = int(y_begin); y < int(y_end); ++y)
            for (int x = 0; x < camera.width; ++x) {
                const size_t i = size_t(y) * size_t(camera.width) + size_t(x);
                const PixelTrace& trace = base.trace(i);
                const bool chains = trace.flags & PixelRecorder::chain;
                uint8_t changed = 0;
                if (changes.near_dynamic[i] || (trace.flags & PixelRecorder::open_chain)) changed |= camera_term;
                const uint8_t* tile_free = shadow_free.free_pairs(x, y);
                // The sphere about the pixel's points and its rays' slack, made only where a test
                // needs it: far from every shadow's hull, no test does.
                BoundingSphere points;
                float slack = 0;
                if (chains || trace.reached_distant_light() || !shadow_free.all_free(tile_free)) {
                    points = pixel_points(trace);
                    slack = shadow_ray_slack(points);
                }
                for (const BoundingSphere& object : changes.dynamic) {
                    if (chains && may_meet_segments(object, points, points, slack)) changed |= camera_term;
                    for (const BoundingSphere& light : changes.lights)
                        if (!*tile_free++ && may_meet_segments(object, points, light, slack)) changed |= direct_term;
                    if (trace.reached_distant_light() &&
                        may_meet_rays(object, BoundingSphere{points.center, points.radius + slack}, trace.to_distant_lo,
                                      trace.to_distant_hi))
                        changed |= direct_term;
                }
                if (changes.indirect[i] || (trace.flags & (PixelRecorder::gather | PixelRecorder::coat)) ||
                    (chains && (changes.records_changed || changes.caustics_changed)))
                    changed |= indirect_term;
                if ((trace.flags & PixelRecorder::reads_caustics) && changes.caustic[i]) changed |= caustic_term;
                // The indirect light may be looked up again where only corrected records changed
                // for a pixel whose every look-up was kept; it is kept as it is where none of the
                // records those look-ups interpolated changed (and the pixel's camera rays are not
                // traced anew).
                const bool looked_up = (changed & indirect_term) && changes.indirect[i] == FrameChanges::records &&
                                       !(trace.flags & (PixelRecorder::chain | PixelRecorder::coat |
                                                        PixelRecorder::gather | PixelRecorder::unkept));
                if (looked_up && !(changed & (camera_term | caustic_term)) && !changes.changed_records.empty() &&
                    !base.interpolates_marked(i, changed_sets))
                    changed &= uint8_t(~indirect_term);
                // Only the direct light shaded again where the camera rays meet what they met (no
                // chains either) and the other terms are the static frame's or looked up again.
                const bool direct_again = (changed & direct_term) && !(changed & (camera_term | caustic_term)) &&
                                          !chains && (!(changed & indirect_term) || looked_up);
                const PixelWork work = !changed                                            ? PixelWork::reuse
                                       : changed == indirect_term && looked_up             ? PixelWork::look_up_again
                                       : direct_again                                      ? PixelWork::direct_again
                                       : (changed & (camera_term | direct_term)) || chains ? PixelWork::redo
                                                                                           : PixelWork::redo_but_direct;
                plan.changed[i] = changed;
                plan.work[i] = work;
                ++counts[int(work)];
                for (int bit = 0; bit < 4; ++bit) changed_pixels[bit] += (changed >> bit) & 1;
            }
        const std::lock_guard<std::mutex> hold(counts_lock);
        plan.reused += counts[int(PixelWork::reuse)], plan.looked_up_again += counts[int(PixelWork::look_up_again)];
        plan.direct_again += counts[int(PixelWork::direct_again)], plan.redone += counts[int(PixelWork::redo)];
        plan.redone_but_direct += counts[int(PixelWork::redo_but_direct)];
        for (int bit = 0; bit < 4; ++bit) plan.changed_pixels[bit] += changed_pixels[bit];
    });
    return plan;
}

bool same_view_and_lights(const Scene& scene, const FrameState& frame, const FrameState& static_frame) {
    const Camera &a = frame.camera, &b = static_frame.camera;
    if (!(a.world_from_camera == b.world_from_camera) || a.tan_half_fov_y != b.tan_half_fov_y || a.width != b.width ||
        a.height != b.height)
        return false;
    if (!frame.same_lights(static_frame)) return false;
    for (const int object : scene.dynamic_objects())
        if (!is_black(frame.emission[size_t(object)])) return false;
    return true;
}

}  // namespace steadylight
