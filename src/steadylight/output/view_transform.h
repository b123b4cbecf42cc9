// The view transform that turns a linear radiance image into 8-bit sRGB for PNGs and video:
// linear -> exposure (x 2^EV) -> view curve (standard: clamp to [0, 1]; filmic: John Hable's
// "Uncharted 2" curve, GDC 2010 "Uncharted 2: HDR Lighting") -> sRGB OETF (IEC 61966-2-1)
// -> 8 bits with a fixed, deterministic dither. The EXR keeps the linear values untouched.
#pragma once

#include <string>
#include <vector>

#include "steadylight/base/image.h"

namespace steadylight {

enum class ViewCurve { standard, filmic };

struct ViewTransform {
    float exposure_ev = 0;  // linear values are scaled by 2^exposure_ev
    ViewCurve curve = ViewCurve::standard;
    bool dither = true;  // +-1/2 code value of fixed noise before rounding
};

/// "standard" or "filmic"; throws InputError naming `option` otherwise.
ViewCurve parse_view_curve(const std::string& name, const std::string& option = "--view-transform");

/// The linear value after exposure: v * 2^ev.
float apply_exposure(float v, float exposure_ev);

/// Hable's filmic curve, scaled so that linear 11.2 / 2 (the white point after his exposure bias
/// of 2) maps to 1: monotonic, 0 -> 0, and clamped to at most 1. Input is linear, >= 0.
float filmic_curve(float v);

/// The view curve of `transform` applied to a linear value (after exposure); result in [0, 1].
float apply_view_curve(float v, ViewCurve curve);

/// The sRGB transfer curve (IEC 61966-2-1) for a linear value, clamped to [0, 1] first.
float linear_to_srgb(float v);

/// The image as 8-bit sRGB bytes, RGB interleaved, row-major: every pixel and channel through
/// exposure, the view curve, sRGB encoding, dither (a hash of x, y and channel, the same in
/// every frame so that it does not flicker) and rounding.
/// With `alpha` (a grey image of the same size, read from its red channel) the bytes are RGBA
/// with straight alpha, as PNG stores it: `image` is premultiplied by alpha, so each pixel is
/// divided by its alpha first (0 where alpha is 0), and only then transformed: the curves are
/// not linear, and a surface's edge pixels must keep the surface's colour, not a darker one.
/// Alpha is a share, stored linearly and rounded without dither (0 and 1 stay 0 and 255).
std::vector<unsigned char> encode_srgb8(const Image& image, const ViewTransform& transform,
                                        const Image* alpha = nullptr);

}  // namespace steadylight
