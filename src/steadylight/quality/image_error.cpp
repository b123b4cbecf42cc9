// The error and temporal-noise figures of the truth suite (image_error.h).
#include "steadylight/quality/image_error.h"

#include <cmath>

#include "steadylight/base/check.h"

namespace steadylight {
namespace {

constexpr int block_size = 4;
constexpr double small_change = 0.2;  // "true change below 20% of Y": leaves out coverage edges
constexpr double no_change = 0.002;   // "far": the reference changes by less than 0.2%

bool kept(const PixelMask& left_out, size_t i) { return left_out.empty() || !left_out[i]; }

/// Sums of Y and of the squared difference over a set of values.
struct Sums {
    double y = 0, y_ref = 0, diff2 = 0;
    long count = 0;

    void add(double value, double ref) { y += value, y_ref += ref, diff2 += (value - ref) * (value - ref), ++count; }
    double relative_rmse() const { return y_ref > 0 ? std::sqrt(diff2 / double(count)) / (y_ref / double(count)) : 0; }
};

}  // namespace

ImageError image_error(const Image& image, const Image& reference, const PixelMask& left_out) {
    SL_CHECK(image.width == reference.width && image.height == reference.height);
    Sums pixels, blocks;
    for (int by = 0; by < image.height; by += block_size)
        for (int bx = 0; bx < image.width; bx += block_size) {
            Sums block;
            for (int y = by; y < std::min(by + block_size, image.height); ++y)
                for (int x = bx; x < std::min(bx + block_size, image.width); ++x) {
                    const size_t i = size_t(y) * size_t(image.width) + size_t(x);
                    if (kept(left_out, i)) block.add(luminance(image.pixels[i]), luminance(reference.pixels[i]));
                }
            if (block.count == 0) continue;
            pixels.y += block.y, pixels.y_ref += block.y_ref, pixels.diff2 += block.diff2, pixels.count += block.count;
            blocks.add(block.y / double(block.count), block.y_ref / double(block.count));
        }
    return {pixels.relative_rmse(), blocks.relative_rmse(), pixels.y_ref > 0 ? pixels.y / pixels.y_ref : 0,
            pixels.count};
}

PixelMask emitter_mask(const FrameContext& context) {
    const Camera& camera = context.frame.camera;
    const int w = camera.width, h = camera.height;
    PixelMask sees(size_t(w) * size_t(h), 0), mask(sees.size(), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::optional<Hit> hit =
                context.tracer.intersect(camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f));
            sees[size_t(y) * size_t(w) + size_t(x)] = hit && context.scene.object(hit->object).is_emitter();
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int sx = x + dx, sy = y + dy;
                    if (sx >= 0 && sy >= 0 && sx < w && sy < h && sees[size_t(sy) * size_t(w) + size_t(sx)])
                        mask[size_t(y) * size_t(w) + size_t(x)] = 1;
                }
    return mask;
}

TemporalNoise temporal_noise(const std::vector<FramePair>& method, const std::vector<FramePair>& reference,
                             const PixelMask& left_out) {
    SL_CHECK_EQ(method.size(), reference.size());
    if (method.empty()) return {};
    const size_t n = reference.front().a.pixels.size();
    // "Far": the pixels whose reference does not change in any pair.
    std::vector<uint8_t> far(n, 1);
    for (const FramePair& r : reference)
        for (size_t i = 0; i < n; ++i) {
            const double ya = luminance(r.a.pixels[i]), yb = luminance(r.b.pixels[i]);
            if (!(std::abs(yb - ya) < no_change * 0.5 * (ya + yb))) far[i] = 0;
        }
    double all_diff = 0, all_y = 0, far_diff = 0, far_signed = 0, far_own = 0, far_y = 0;
    TemporalNoise noise;
    for (size_t p = 0; p < method.size(); ++p)
        for (size_t i = 0; i < n; ++i) {
            if (!kept(left_out, i)) continue;
            const double ra = luminance(reference[p].a.pixels[i]), rb = luminance(reference[p].b.pixels[i]);
            const double change = rb - ra, y = 0.5 * (ra + rb);
            if (!(std::abs(change) < small_change * y)) continue;
            const double own = luminance(method[p].b.pixels[i]) - luminance(method[p].a.pixels[i]);
            const double signed_diff = own - change, diff = std::abs(signed_diff);
            all_diff += diff, all_y += y, ++noise.all_pixels;
            if (far[i])
                far_diff += diff, far_signed += signed_diff, far_own += std::abs(own), far_y += y, ++noise.far_pixels;
        }
    noise.all = all_y > 0 ? all_diff / all_y : 0;
    noise.far = far_y > 0 ? far_diff / far_y : 0;
    noise.far_signed = far_y > 0 ? far_signed / far_y : 0;
    noise.far_own = far_y > 0 ? far_own / far_y : 0;
    return noise;
}

}  // namespace steadylight
