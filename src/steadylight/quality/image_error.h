// How far a rendered image is from a reference: the one figure the truth suite uses everywhere
// (its tests, bench/quality_bench, the README; docs/design.md). Y is the Rec. 709 luminance of
// linear RGB, not clamped; the pixels that see an emitter, and a one-pixel border around them,
// are left out (their values are the light's own, and anti-aliasing there is all noise).
//   relative RMSE = sqrt(mean (Y - Y_ref)^2) / mean Y_ref, per pixel and after averaging 4x4
//   blocks (which forgives per-pixel noise but not a wrong region), and the ratio of the means.
// Temporal noise compares the frame-to-frame change of a method with that of a reference
// rendered with common random numbers (`--method path --fixed-seed`): where no path meets a
// moving object the reference's change is exactly zero, elsewhere an unbiased estimate.
#pragma once

#include <cstdint>
#include <vector>

#include "steadylight/base/image.h"
#include "steadylight/shading/frame_context.h"

namespace steadylight {

/// One byte per pixel, row by row: 1 for a pixel left out of the figures. Empty: none.
using PixelMask = std::vector<uint8_t>;

struct ImageError {
    double pixel_rmse = 0;  // relative RMSE per pixel
    double block_rmse = 0;  // relative RMSE of the means of 4x4 blocks
    double mean_ratio = 0;  // mean Y / mean Y_ref
    long pixels = 0;        // pixels compared
};

/// `image` against `reference` (same size) over the pixels `left_out` does not mark.
ImageError image_error(const Image& image, const Image& reference, const PixelMask& left_out = {});

/// The pixels whose centre sees an emitter directly, and the pixels next to them (8-connected).
PixelMask emitter_mask(const FrameContext& context);

/// Two frames of an animation, a before b.
struct FramePair {
    const Image& a;
    const Image& b;
};

struct TemporalNoise {
    double all = 0;  // over the pixels whose true change is below 20% of Y
    double far = 0;  // over the pixels whose reference changes by less than 0.2% in every pair
    /// The mean signed (method - reference) change over the far pixels, / mean Y: a method that
    /// holds still where the truth still moves a little shows it here.
    double far_signed = 0;
    /// The method's own mean |change| over the far pixels, / mean Y: free of the references'
    /// noise, it holds the true change there (below 0.2%) and the method's noise.
    double far_own = 0;
    long all_pixels = 0, far_pixels = 0;  // pixels counted, summed over the pairs
};

/// \brief mean |(Y_b - Y_a)_method - (Y_b - Y_a)_reference| / mean Y over the pairs, where Y is
/// the reference's mean of the two frames; `method[i]` and `reference[i]` are the same pair.
TemporalNoise temporal_noise(const std::vector<FramePair>& method, const std::vector<FramePair>& reference,
                             const PixelMask& left_out = {});

}  // namespace steadylight
