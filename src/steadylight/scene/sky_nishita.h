// Blender's default Sky Texture (Nishita model) as Cycles renders it (Blender 3.4): the sky as an
// equirectangular image for the world, and its sun disc for a sun light. The atmosphere is
// computed as Blender computes it (sky_nishita_atmosphere.h); this half lays it out, looks it up
// and turns it into linear Rec. 709 RGB the way Cycles does (sky_nishita.cpp, Apache-2.0, with
// Blender's notice there), so that a scene set up in Blender shows the same sky here.
// tests/references/nishita_sky/ holds Cycles' renders it is checked against.
//
// Directions are in glTF axes (y up); Blender's are z up: Blender (x, y, z) = glTF (x, -z, y).
// The sun stands sun_elevation above the horizon, turned sun_rotation clockwise seen from above
// from Blender's +y (glTF -z) towards Blender's +x (glTF +x):
//   glTF direction = (cos e sin r, sin e, -cos e cos r),  e = sun_elevation, r = sun_rotation.
#pragma once

#include <optional>

#include "steadylight/base/color.h"
#include "steadylight/base/image.h"
#include "steadylight/base/vec.h"

namespace steadylight {

/// Blender's Sky Texture, Nishita model, with Blender's parameter names and units (angles in
/// radians as bpy stores them). As Cycles does, the altitude is clamped to [1, 59999] m and the
/// sun's size to at least 0.0005 rad (0.029 degrees).
struct NishitaSkyParams {
    float sun_elevation = 0.2617994f;  // Blender's defaults: 15 degrees
    float sun_rotation = 0;
    float sun_size = 0.009512f;  // 0.545 degrees
    float sun_intensity = 1;
    bool sun_disc = true;
    float altitude = 0;  // metres
    float air_density = 1, dust_density = 1, ozone_density = 1;
};

/// The sky without its sun disc, as Cycles shows it (its units: what a camera sees directly),
/// as an equirectangular image of width x width/2 in glTF axes mapped as Blender's Environment
/// Texture (glTF y up; centre column looks down +x; u = atan2(z, x)/2pi + 1/2,
/// v = asin(y)/pi + 1/2, v = 1 the top row). Each pixel is the sky's average over the pixel's
/// rectangle in (u, v), as Cycles renders it with a one-pixel box filter.
/// Below the horizon, as Cycles: the sky's colour at the horizon fading as (1 + 2.5 y)^3 to black
/// at y = -0.4 (23.6 degrees down), and black below. A sun below the horizon still lights the sky
/// (twilight) through the atmosphere model. `width` must be even and positive.
Image nishita_sky_image(const NishitaSkyParams& params, int width);

/// The sun disc (when sun_disc): unit direction towards the sun in glTF axes, its radiance as
/// Cycles shows it at the disc's centre, and its angular diameter (sun_size, at least 0.0005).
/// Cycles shows the disc in place of the sky behind it, at sun_intensity times the sun's radiance
/// through the atmosphere, which it interpolates linearly in elevation from the disc's bottom
/// edge to its top edge, darkened towards the limb by 1 - 0.6 (1 - sqrt(1 - (a/h)^2)) at angle a
/// from the centre (h half the diameter): the disc's mean radiance is 0.8 times `radiance`.
/// Cycles shows no part of the disc below the horizon; when the centre is below it (the sun half
/// set) `radiance` is the one Cycles shows at the horizon. No sun when sun_disc is off or the disc
/// is wholly below the horizon.
struct NishitaSun {
    Vec3 direction;
    Rgb radiance;
    float angle_radians = 0;
};
std::optional<NishitaSun> nishita_sky_sun(const NishitaSkyParams& params);

}  // namespace steadylight
