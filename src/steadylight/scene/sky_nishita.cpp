/* SPDX-License-Identifier: Apache-2.0
 * Copyright 2011-2022 Blender Foundation.
 * Modifications copyright 2026 the steadylight authors.
 *
 * Licensed under the Apache License, Version 2.0 (the "License"); you may not use this file
 * except in compliance with the License. You may obtain a copy of the License at
 * http://www.apache.org/licenses/LICENSE-2.0 (and in LICENSE at the top of this repository).
 * Unless required by applicable law or agreed to in writing, software distributed under the
 * License is distributed on an "AS IS" BASIS, WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND,
 * either express or implied. See the License for the specific language governing permissions
 * and limitations under the License. */

// Blender's Sky Texture (Nishita) as Cycles shows it (sky_nishita.h). Ported from Blender 3.4's
// Cycles: the precomputation's parameters from intern/cycles/scene/shader_nodes.cpp
// (SkyTextureNode::compile, sky_texture_precompute_nishita) and scene/image_sky.cpp (SkyLoader:
// the texture's size), the look-up from kernel/svm/sky.h (sky_radiance_nishita) and the texture
// filtering from kernel/device/cpu/image.h (linear, extend). Changed from the original: the sky
// and its sun disc are evaluated apart (nishita_sky_image, nishita_sky_sun) instead of in one
// shader node, directions come in glTF axes, the sky image averages each pixel over sub-samples,
// and Cycles' XYZ-to-RGB matrix is written out.
#include "steadylight/scene/sky_nishita.h"

#include <algorithm>
#include <cmath>

#include "steadylight/base/parallel.h"
#include "steadylight/scene/sky_nishita_atmosphere.h"

namespace steadylight {
namespace {

// The sky texture Cycles precomputes (SkyLoader::load_metadata).
constexpr int texture_width = 512;
constexpr int texture_height = 128;
// SkyTextureNode::get_sun_size: "clamping for numerical precision".
constexpr float min_sun_size = 0.0005f;
// SkyTextureNode::compile: "below 1m causes numerical issues and above 60km is space".
constexpr float min_altitude = 1.0f;
constexpr float max_altitude = 59999.0f;

/// Cycles' CIE XYZ (D65) to linear Rec. 709 RGB: its default matrix (ShaderManager::
/// init_xyz_transforms, ITU-R BT.709). Blender 3.4 renders the sky with it: its renders match this
/// matrix to 0.01%, not the product with its colour configuration's ACES role (Cycles' D65-to-E
/// scaling and XYZ-to-ACES matrices, then the configuration's ACES to Rec. 709), which is about
/// 15% redder on a blue sky (tests/references/nishita_sky).
constexpr float xyz_to_rgb[3][3] = {{3.2404542f, -1.5371385f, -0.4985314f},
                                    {-0.9692660f, 1.8760108f, 0.0415560f},
                                    {0.0556434f, -0.2040259f, 1.0572252f}};

/// What Cycles hands its sky shader: the texture, the sun's edges and the sun's placement.
struct CyclesNishitaSky {
    NishitaSkyTexture texture;
    NishitaSunEdges sun;
    float sun_elevation = 0;
    float sun_rotation = 0;  // Cycles' own: 2 pi minus Blender's, reduced to [0, 2 pi)
    float sun_size = 0;
    float sun_intensity = 1;
};

NishitaAtmosphere clamped_atmosphere(const NishitaSkyParams& params) {
    return {params.sun_elevation, std::clamp(params.altitude, min_altitude, max_altitude), params.air_density,
            params.dust_density, params.ozone_density};
}

float cycles_sun_rotation(float sun_rotation) {
    float rotation = std::fmod(sun_rotation, 2 * pi);
    if (rotation < 0.0f) rotation += 2 * pi;
    return 2 * pi - rotation;
}

float fractf(float x) { return x - std::floor(x); }

Vec3 blender_from_gltf(Vec3 d) { return {d.x, -d.z, d.y}; }
Vec3 gltf_from_blender(Vec3 d) { return {d.x, d.z, -d.y}; }

/// Cycles' geographical_to_direction (kernel/svm/sky.h), Blender's axes: latitude is the
/// elevation, and longitude 0 looks down +y, longitude pi/2 down -x.
Vec3 geographical_to_direction(float lat, float lon) {
    return {-std::cos(lat) * std::sin(lon), std::cos(lat) * std::cos(lon), std::sin(lat)};
}

/// Cycles' bilinear texture look-up with extension "extend": texel centres at (i + 1/2)/size,
/// coordinates outside clamped to the edge texels.
Vec3 texture_lookup(const NishitaSkyTexture& texture, float x, float y) {
    const float fx = x * float(texture.width) - 0.5f, fy = y * float(texture.height) - 0.5f;
    const float ix_floor = std::floor(fx), iy_floor = std::floor(fy);
    const float tx = fx - ix_floor, ty = fy - iy_floor;
    const int ix = std::clamp(int(ix_floor), 0, texture.width - 1);
    const int nix = std::clamp(int(ix_floor) + 1, 0, texture.width - 1);
    const int iy = std::clamp(int(iy_floor), 0, texture.height - 1);
    const int niy = std::clamp(int(iy_floor) + 1, 0, texture.height - 1);
    return (1.0f - ty) * ((1.0f - tx) * texture.at(ix, iy) + tx * texture.at(nix, iy)) +
           ty * ((1.0f - tx) * texture.at(ix, niy) + tx * texture.at(nix, niy));
}

/// Cycles' xyz_to_rgb, negative channels (colours outside Rec. 709) clamped to zero.
Rgb rgb_from_xyz(Vec3 xyz) {
    const auto channel = [&](int i) {
        return std::max(0.0f, xyz_to_rgb[i][0] * xyz.x + xyz_to_rgb[i][1] * xyz.y + xyz_to_rgb[i][2] * xyz.z);
    };
    return {channel(0), channel(1), channel(2)};
}

/// The elevation of a unit direction in Blender's axes, as Cycles takes it (pi/2 - acos z).
float elevation_of(Vec3 dir) { return pi / 2 - std::acos(std::clamp(dir.z, -1.0f, 1.0f)); }

/// The sky towards `dir` (Blender's axes, unit), sun disc aside: the texture column at the
/// azimuth from the sun, the row undoing the texture's crowding towards the horizon; below the
/// horizon, the horizon's row fading to black at z = -0.4.
Vec3 sky_xyz(const CyclesNishitaSky& sky, Vec3 dir) {
    const float phi = std::atan2(dir.y, dir.x);
    const float x = fractf((-phi - pi / 2 + sky.sun_rotation) / (2 * pi));
    if (dir.z >= 0.0f) return texture_lookup(sky.texture, x, std::sqrt(std::max(0.0f, elevation_of(dir) / (pi / 2))));
    if (dir.z < -0.4f) return {};
    const float fade = 1.0f + dir.z * 2.5f;
    return texture_lookup(sky.texture, x, -0.5f) * (fade * fade * fade);
}

/// The sun disc's radiance at elevation `dir_elevation` inside it, limb darkening aside:
/// interpolated between the disc's edges, from the horizon up when the disc crosses it.
Vec3 sun_disc_xyz(const CyclesNishitaSky& sky, float dir_elevation) {
    const float half_angular = sky.sun_size / 2;
    const float y = sky.sun_elevation - half_angular > 0.0f ? (dir_elevation - sky.sun_elevation) / sky.sun_size + 0.5f
                                                            : dir_elevation / (sky.sun_elevation + half_angular);
    return (sky.sun.bottom_xyz + y * (sky.sun.top_xyz - sky.sun.bottom_xyz)) * sky.sun_intensity;
}

Vec3 sun_direction_blender(const NishitaSkyParams& params) {
    return geographical_to_direction(params.sun_elevation, cycles_sun_rotation(params.sun_rotation));
}

CyclesNishitaSky prepare_cycles_sky(const NishitaSkyParams& params) {
    const NishitaAtmosphere atmosphere = clamped_atmosphere(params);
    CyclesNishitaSky sky;
    sky.texture = precompute_nishita_sky_texture(atmosphere, texture_width, texture_height);
    sky.sun_size = std::max(params.sun_size, min_sun_size);
    sky.sun = precompute_nishita_sun(atmosphere, sky.sun_size);
    sky.sun_elevation = params.sun_elevation;
    sky.sun_rotation = cycles_sun_rotation(params.sun_rotation);
    sky.sun_intensity = params.sun_intensity;
    return sky;
}

/// The direction at azimuth `phi` (glTF's atan2(z, x)) and `elevation`, Blender's axes.
Vec3 panorama_direction(float phi, float elevation) {
    return blender_from_gltf(
        {std::cos(elevation) * std::cos(phi), std::sin(elevation), std::cos(elevation) * std::sin(phi)});
}

/// Sub-samples per pixel side for an image `width` wide: a grid about 0.18 degrees apart, so that
/// a pixel's average resolves the sky's fastest changes (the degrees above the horizon, where the
/// texture's rows crowd, and the fade below it); 2048 wide and more, the pixel's centre. Against
/// Cycles' renders 128 wide (tests/references/nishita_sky), point samples at the pixels' centres
/// are 0.4-0.9% off on average and up to 25% on the horizon's rows; 16 x 16 sub-samples 0.002-0.006%
/// on average and at most 2.2%.
int subsamples_per_side(int width) { return std::clamp(2048 / width, 1, 16); }

}  // namespace

Image nishita_sky_image(const NishitaSkyParams& params, int width) {
    const CyclesNishitaSky sky = prepare_cycles_sky(params);
    const int height = width / 2;
    const int n = subsamples_per_side(width);
    const float row_span = pi / float(height), column_span = 2 * pi / float(width);
    Image image(width, height);
    parallel_for_chunks(height, 1, [&](long begin, long end) {
        for (int row = int(begin); row < int(end); ++row) {
            for (int column = 0; column < width; ++column) {
                Rgb sum;
                for (int j = 0; j < n; ++j) {
                    // Row 0 is the top: elevation pi/2 at its upper edge.
                    const float elevation = pi / 2 - (float(row) + (float(j) + 0.5f) / float(n)) * row_span;
                    for (int i = 0; i < n; ++i) {
                        const float phi = (float(column) + (float(i) + 0.5f) / float(n)) * column_span - pi;
                        sum += rgb_from_xyz(sky_xyz(sky, panorama_direction(phi, elevation)));
                    }
                }
                image.at(column, row) = sum / float(n * n);
            }
        }
    });
    return image;
}

std::optional<NishitaSun> nishita_sky_sun(const NishitaSkyParams& params) {
    const float sun_size = std::max(params.sun_size, min_sun_size);
    if (!params.sun_disc || params.sun_elevation + sun_size / 2 <= 0.0f) return std::nullopt;
    // Only the disc's edges are needed, not the sky texture.
    CyclesNishitaSky sky;
    sky.sun_size = sun_size;
    sky.sun = precompute_nishita_sun(clamped_atmosphere(params), sun_size);
    sky.sun_elevation = params.sun_elevation;
    sky.sun_intensity = params.sun_intensity;
    const Vec3 direction = sun_direction_blender(params);
    const Rgb radiance = rgb_from_xyz(sun_disc_xyz(sky, std::max(0.0f, elevation_of(direction))));
    return NishitaSun{gltf_from_blender(direction), radiance, sun_size};
}

}  // namespace steadylight
