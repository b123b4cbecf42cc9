/* SPDX-License-Identifier: Apache-2.0
 * Copyright 2011-2020 Blender Foundation.
 * Modifications copyright 2026 the steadylight authors.
 *
 * Licensed under the Apache License, Version 2.0 (the "License"); you may not use this file
 * except in compliance with the License. You may obtain a copy of the License at
 * http://www.apache.org/licenses/LICENSE-2.0 (and in LICENSE at the top of this repository).
 * Unless required by applicable law or agreed to in writing, software distributed under the
 * License is distributed on an "AS IS" BASIS, WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND,
 * either express or implied. See the License for the specific language governing permissions
 * and limitations under the License. */

// Blender's Nishita sky model (sky_nishita_atmosphere.h), ported from Blender 3.4's
// intern/sky/source/sky_nishita.cpp. Changed from the original: steadylight's Vec3 in place of
// intern/sky's float3, the results returned as structs (NishitaSkyTexture, NishitaSunEdges)
// instead of written through pointers, the texture's rows computed in parallel here rather than
// by the caller, and steadylight's names and layout; the constants, tables and arithmetic are
// Blender's, in float as there.
#include "steadylight/scene/sky_nishita_atmosphere.h"

#include <array>
#include <cmath>

#include "steadylight/base/parallel.h"

namespace steadylight {
namespace {

constexpr float rayleigh_scale = 8e3f;        // Rayleigh scale height (m)
constexpr float mie_scale = 1.2e3f;           // Mie scale height (m)
constexpr float mie_coeff = 2e-5f;            // Mie scattering coefficient (m^-1)
constexpr float mie_G = 0.76f;                // aerosols' anisotropy
constexpr float sqr_G = mie_G * mie_G;        // its square
constexpr float earth_radius = 6360e3f;       // radius of the Earth (m)
constexpr float atmosphere_radius = 6420e3f;  // radius of the atmosphere (m)
constexpr int steps = 32;                     // segments of the primary ray
constexpr int num_wavelengths = 21;
constexpr int min_wavelength = 380;                                                       // nm
constexpr int max_wavelength = 780;                                                       // nm
constexpr float step_lambda = (max_wavelength - min_wavelength) / (num_wavelengths - 1);  // nm

using Spectrum = std::array<float, num_wavelengths>;

/// The sun's spectral irradiance at the top of the atmosphere (W m^-2 nm^-1).
constexpr Spectrum irradiance = {1.45756829855592995315f, 1.56596305559738380175f, 1.65148449067670455293f,
                                 1.71496242737209314555f, 1.75797983805020541226f, 1.78256407885924539336f,
                                 1.79095108475838560302f, 1.78541550133410664714f, 1.76815554864306845317f,
                                 1.74122069647250410362f, 1.70647127164943679389f, 1.66556087452739887134f,
                                 1.61993437242451854274f, 1.57083597368892080581f, 1.51932335059305478886f,
                                 1.46628494965214395407f, 1.41245852740172450623f, 1.35844961970384092709f,
                                 1.30474913844739281998f, 1.25174963272610817455f, 1.19975998755420620867f};
/// Rayleigh scattering coefficient (m^-1).
constexpr Spectrum rayleigh_coeff = {0.00005424820087636473f, 0.00004418549866505454f, 0.00003635151910165377f,
                                     0.00003017929012024763f, 0.00002526320226989157f, 0.00002130859310621843f,
                                     0.00001809838025320633f, 0.00001547057129129042f, 0.00001330284977336850f,
                                     0.00001150184784075764f, 0.00000999557429990163f, 0.00000872799973630707f,
                                     0.00000765513700977967f, 0.00000674217203751443f, 0.00000596134125832052f,
                                     0.00000529034598065810f, 0.00000471115687557433f, 0.00000420910481110487f,
                                     0.00000377218381260133f, 0.00000339051255477280f, 0.00000305591531679811f};
/// Ozone absorption coefficient (m^-1).
constexpr Spectrum ozone_coeff = {0.00000000325126849861f, 0.00000000585395365047f, 0.00000001977191155085f,
                                  0.00000007309568762914f, 0.00000020084561514287f, 0.00000040383958096161f,
                                  0.00000063551335912363f, 0.00000096707041180970f, 0.00000154797400424410f,
                                  0.00000209038647223331f, 0.00000246128056164565f, 0.00000273551299461512f,
                                  0.00000215125863128643f, 0.00000159051840791988f, 0.00000112356197979857f,
                                  0.00000073527551487574f, 0.00000046450130357806f, 0.00000033096079921048f,
                                  0.00000022512612292678f, 0.00000014879129266490f, 0.00000016828623364192f};
/// CIE 1931 XYZ colour matching functions at the sampled wavelengths.
constexpr std::array<Vec3, num_wavelengths> cmf_xyz = {
    {{0.00136800000f, 0.00003900000f, 0.00645000100f}, {0.01431000000f, 0.00039600000f, 0.06785001000f},
     {0.13438000000f, 0.00400000000f, 0.64560000000f}, {0.34828000000f, 0.02300000000f, 1.74706000000f},
     {0.29080000000f, 0.06000000000f, 1.66920000000f}, {0.09564000000f, 0.13902000000f, 0.81295010000f},
     {0.00490000000f, 0.32300000000f, 0.27200000000f}, {0.06327000000f, 0.71000000000f, 0.07824999000f},
     {0.29040000000f, 0.95400000000f, 0.02030000000f}, {0.59450000000f, 0.99500000000f, 0.00390000000f},
     {0.91630000000f, 0.87000000000f, 0.00165000100f}, {1.06220000000f, 0.63100000000f, 0.00080000000f},
     {0.85444990000f, 0.38100000000f, 0.00019000000f}, {0.44790000000f, 0.17500000000f, 0.00002000000f},
     {0.16490000000f, 0.06100000000f, 0.00000000000f}, {0.04677000000f, 0.01700000000f, 0.00000000000f},
     {0.01135916000f, 0.00410200000f, 0.00000000000f}, {0.00289932700f, 0.00104700000f, 0.00000000000f},
     {0.00069007860f, 0.00024920000f, 0.00000000000f}, {0.00016615050f, 0.00006000000f, 0.00000000000f},
     {0.00004150994f, 0.00001499000f, 0.00000000000f}}};

// Gauss-Laguerre quadrature for the optical depth (ray_optical_depth): the 8 standard nodes
// scaled so that the last one still lies in the atmosphere (divided by 25), and the weights with
// the e^x factor folded in. Blender computed them with sympy:
//   x, w = gauss_laguerre(8, 50); xend = 25
//   [(xi / xend).evalf(10) for xi in x]; [(wi * exp(xi) / xend).evalf(10) for xi, wi in zip(x, w)]
constexpr int quadrature_steps = 8;
constexpr std::array<float, quadrature_steps> quadrature_nodes = {0.006811185292f, 0.03614807107f, 0.09004346519f,
                                                                  0.1706680068f,   0.2818362161f,  0.4303406404f,
                                                                  0.6296271457f,   0.9145252695f};
constexpr std::array<float, quadrature_steps> quadrature_weights = {0.01750893642f, 0.04135477391f, 0.06678839063f,
                                                                    0.09507698807f, 0.1283416365f,  0.1707430204f,
                                                                    0.2327233347f,  0.3562490486f};

float sqr(float a) { return a * a; }
float reduce_add(Vec3 v) { return v.x + v.y + v.z; }

/// Blender's axes (z up): latitude is the elevation, longitude the azimuth from +x.
Vec3 geographical_to_direction(float lat, float lon) {
    return {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)};
}

Vec3 spectrum_to_xyz(const Spectrum& spectrum) {
    Vec3 xyz;
    for (int i = 0; i < num_wavelengths; ++i) xyz += cmf_xyz[size_t(i)] * spectrum[size_t(i)];
    return xyz * step_lambda;
}

// The atmosphere's density profiles, relative to sea level.
float density_rayleigh(float height) { return std::exp(-height / rayleigh_scale); }
float density_mie(float height) { return std::exp(-height / mie_scale); }
/// Ozone: a tent between 10 and 40 km, peaking at 25 km.
float density_ozone(float height) {
    if (height >= 10000.0f && height < 25000.0f) return 1.0f / 15000.0f * height - 2.0f / 3.0f;
    if (height >= 25000 && height < 40000) return -(1.0f / 15000.0f * height - 8.0f / 3.0f);
    return 0.0f;
}

float phase_rayleigh(float mu) { return 3.0f / (16.0f * pi) * (1.0f + sqr(mu)); }
/// Cornette-Shanks.
float phase_mie(float mu) {
    return (3.0f * (1.0f - sqr_G) * (1.0f + sqr(mu))) /
           (8.0f * pi * (2.0f + sqr_G) * std::pow((1.0f + sqr_G - 2.0f * mie_G * mu), 1.5f));
}

/// Whether the ray from `pos` towards `dir` hits the Earth.
bool surface_intersection(Vec3 pos, Vec3 dir) {
    if (dir.z >= 0) return false;
    const float b = -2.0f * dot(dir, -pos);
    const float c = length2(pos) - sqr(earth_radius);
    return b * b - 4.0f * c >= 0.0f;
}

/// Where the ray from `pos` (inside the atmosphere) towards `dir` leaves it.
Vec3 atmosphere_intersection(Vec3 pos, Vec3 dir) {
    const float b = -2.0f * dot(dir, -pos);
    const float c = length2(pos) - sqr(atmosphere_radius);
    const float t = (-b + std::sqrt(b * b - 4.0f * c)) / 2.0f;
    return pos + dir * t;
}

/// The optical depth along a ray to the top of the atmosphere, as (air, dust, ozone) factors of
/// their sea-level densities times metres. Gauss-Laguerre quadrature integrates f(x) e^-x over
/// [0, inf); the densities fall off roughly exponentially along the ray, so with the e^x folded
/// into the weights it integrates them with 8 evaluations.
Vec3 ray_optical_depth(Vec3 ray_origin, Vec3 ray_dir) {
    const Vec3 ray_end = atmosphere_intersection(ray_origin, ray_dir);
    const float ray_length = length(ray_end - ray_origin);
    const Vec3 segment = ray_length * ray_dir;
    Vec3 optical_depth;
    for (int i = 0; i < quadrature_steps; ++i) {
        const Vec3 P = ray_origin + quadrature_nodes[size_t(i)] * segment;
        const float height = length(P) - earth_radius;
        const Vec3 density = {density_rayleigh(height), density_mie(height), density_ozone(height)};
        optical_depth += density * quadrature_weights[size_t(i)];
    }
    return optical_depth * ray_length;
}

/// The spectral radiance scattered once towards the viewer at `ray_origin` looking down `ray_dir`.
/// The density of each kind of particle has one spectrum, so the optical depths are tracked as
/// three factors and turned into spectra per wavelength.
Spectrum single_scattering(Vec3 ray_dir, Vec3 sun_dir, Vec3 ray_origin, Vec3 density_scale) {
    const Vec3 ray_end = atmosphere_intersection(ray_origin, ray_dir);
    const float ray_length = length(ray_end - ray_origin);
    const float segment_length = ray_length / steps;
    const Vec3 segment = segment_length * ray_dir;

    Spectrum spectrum{};
    const float mu = dot(ray_dir, sun_dir);
    const Vec3 phase_function = {phase_rayleigh(mu), phase_mie(mu), 0.0f};

    // Each segment's density and in-scattering are taken at its middle.
    Vec3 optical_depth;
    Vec3 P = ray_origin + 0.5f * segment;
    for (int i = 0; i < steps; ++i) {
        const float height = length(P) - earth_radius;
        const Vec3 density = density_scale * Vec3{density_rayleigh(height), density_mie(height), density_ozone(height)};
        optical_depth += segment_length * density;

        // Sunlight reaches P unless the Earth is in the way: Tr(viewer, P) Tr(P, sun) sigma_s
        // phase L_sun over the segment's length.
        if (!surface_intersection(P, sun_dir)) {
            const Vec3 light_optical_depth = density_scale * ray_optical_depth(P, sun_dir);
            const Vec3 total_optical_depth = optical_depth + light_optical_depth;
            for (size_t wl = 0; wl < size_t(num_wavelengths); ++wl) {
                const Vec3 extinction_density =
                    total_optical_depth * Vec3{rayleigh_coeff[wl], 1.11f * mie_coeff, ozone_coeff[wl]};
                const float attenuation = std::exp(-reduce_add(extinction_density));
                const Vec3 scattering_density = density * Vec3{rayleigh_coeff[wl], mie_coeff, 0.0f};
                spectrum[wl] +=
                    attenuation * reduce_add(phase_function * scattering_density) * irradiance[wl] * segment_length;
            }
        }
        P += segment;
    }
    return spectrum;
}

/// The sun's spectral radiance seen towards `cam_dir`: its irradiance attenuated by air and dust
/// (not ozone) along the path, spread over the disc's solid angle.
Spectrum sun_radiation(Vec3 cam_dir, const NishitaAtmosphere& atmosphere, float solid_angle) {
    const Vec3 cam_pos = {0, 0, earth_radius + atmosphere.altitude};
    const Vec3 optical_depth = ray_optical_depth(cam_pos, cam_dir);
    Spectrum spectrum{};
    for (size_t i = 0; i < size_t(num_wavelengths); ++i) {
        const float transmittance = rayleigh_coeff[i] * optical_depth.x * atmosphere.air_density +
                                    1.11f * mie_coeff * optical_depth.y * atmosphere.dust_density;
        spectrum[i] = irradiance[i] * std::exp(-transmittance) / solid_angle;
    }
    return spectrum;
}

}  // namespace

NishitaSkyTexture precompute_nishita_sky_texture(const NishitaAtmosphere& atmosphere, int width, int height) {
    NishitaSkyTexture texture{width, height, std::vector<Vec3>(size_t(width) * size_t(height))};
    const int half_width = width / 2;
    const Vec3 cam_pos = {0, 0, earth_radius + atmosphere.altitude};
    const Vec3 sun_dir = geographical_to_direction(atmosphere.sun_elevation, 0.0f);
    const Vec3 density_scale = {atmosphere.air_density, atmosphere.dust_density, atmosphere.ozone_density};
    const float latitude_step = (pi / 2) / float(height);
    const float longitude_step = (2 * pi) / float(width);
    const float half_lat_step = latitude_step / 2.0f;

    parallel_for_chunks(height, 1, [&](long begin, long end) {
        for (int y = int(begin); y < int(end); ++y) {
            // Rows crowd towards the horizon, where the sky changes fastest.
            const float latitude = (pi / 2 + half_lat_step) * sqr(float(y) / float(height));
            Vec3* row = texture.xyz.data() + size_t(y) * size_t(width);
            for (int x = 0; x < half_width; ++x) {
                const float longitude = longitude_step * float(x) - pi;
                const Vec3 dir = geographical_to_direction(latitude, longitude);
                const Vec3 xyz = spectrum_to_xyz(single_scattering(dir, sun_dir, cam_pos, density_scale));
                // The sky is symmetric about the sun's vertical.
                row[x] = xyz;
                row[width - x - 1] = xyz;
            }
        }
    });
    return texture;
}

NishitaSunEdges precompute_nishita_sun(const NishitaAtmosphere& atmosphere, float angular_diameter) {
    const float half_angular = angular_diameter / 2.0f;
    const float solid_angle = 2 * pi * (1.0f - std::cos(half_angular));
    const float bottom = atmosphere.sun_elevation - half_angular;
    const float top = atmosphere.sun_elevation + half_angular;
    const float elevation_bottom = bottom > 0.0f ? bottom : 0.0f;
    const float elevation_top = top > 0.0f ? top : 0.0f;
    const auto edge_xyz = [&](float elevation) {
        return spectrum_to_xyz(sun_radiation(geographical_to_direction(elevation, 0.0f), atmosphere, solid_angle));
    };
    return {edge_xyz(elevation_bottom), edge_xyz(elevation_top)};
}

}  // namespace steadylight
