// Blender's Nishita sky model, the atmosphere half: single scattering of sunlight in a spherical
// shell of air (Rayleigh), dust (Mie) and ozone (absorption) over 21 wavelengths, integrated into
// CIE XYZ. Ported from Blender 3.4's intern/sky (sky_nishita.cpp, Apache-2.0; the notice is in
// sky_nishita_atmosphere.cpp). sky_nishita.h lays the result out and looks it up as Cycles does.
#pragma once

#include <vector>

#include "steadylight/base/vec.h"

namespace steadylight {

/// The atmosphere's parameters as the two precomputations take them: the sun's elevation in
/// radians, the viewer's altitude in metres and the three densities as factors of Earth's.
struct NishitaAtmosphere {
    float sun_elevation = 0;
    float altitude = 0;
    float air_density = 1, dust_density = 1, ozone_density = 1;
};

/// The sky as SKY_nishita_skymodel_precompute_texture computes it: `width` x `height` CIE XYZ
/// texels, rows from the horizon (row 0) up, row y at elevation (pi/2 + half a row)(y/height)^2
/// so that rows crowd towards the horizon; column x at azimuth 2 pi x / width - pi from the sun,
/// the two halves mirror images (only the first is computed).
struct NishitaSkyTexture {
    int width = 0;
    int height = 0;
    std::vector<Vec3> xyz;  // row-major from row 0
    const Vec3& at(int x, int y) const { return xyz[size_t(y) * size_t(width) + size_t(x)]; }
};
NishitaSkyTexture precompute_nishita_sky_texture(const NishitaAtmosphere& atmosphere, int width, int height);

/// The sun disc's CIE XYZ radiance seen through the atmosphere at its bottom and top edges, as
/// SKY_nishita_skymodel_precompute_sun computes it: the sun's irradiance outside the atmosphere
/// spread evenly over a disc of `angular_diameter` radians, attenuated along the path to it;
/// an edge below the horizon is taken at the horizon.
struct NishitaSunEdges {
    Vec3 bottom_xyz, top_xyz;
};
NishitaSunEdges precompute_nishita_sun(const NishitaAtmosphere& atmosphere, float angular_diameter);

}  // namespace steadylight
