// The world's light: radiance arriving from infinitely far away, a uniform colour or an
// equirectangular image (scene/world_image.h), sampled in proportion to what it sends.
//
// The image is mapped as Blender's Environment Texture maps it, in glTF axes (y up): direction
// w looks up u = atan2(z, x) / 2π + ½ across the image (its centre column looks down +x, u = ¾
// down +z) and v = asin(y) / π + ½ up it (v = 1 is the top row, +y), after the rotation a about
// +y of a Mapping node's Z rotation: x' = x cos a + z sin a, z' = -x sin a + z cos a (so the
// picture turns by -a). The look-up is the nearest pixel, not a bilinear blend: the radiance is
// then constant over each pixel's patch of directions, exactly as the sampling density is, so
// that radiance / pdf varies only by the pixel's small spread of sin θ and MIS weights see the
// same picture the shading does.
//
// Sampling picks a pixel in proportion to its luminance times its solid angle (which is
// proportional to sin θ at its centre, θ the angle from +y; Pharr, Jakob and Humphreys,
// "Physically Based Rendering", 3rd ed., §14.2.4), then a direction uniformly in (u, v) inside
// it.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "steadylight/base/color.h"
#include "steadylight/base/distribution_2d.h"
#include "steadylight/base/image.h"
#include "steadylight/base/vec.h"

namespace steadylight {

/// Radiance arriving from far away in every direction: a uniform colour, or an equirectangular
/// image (Blender's Environment Texture mapping in glTF axes) turned about +y, times a strength.
class EnvironmentMap {
public:
    EnvironmentMap(Rgb radiance);  // uniform
    /// `image` of any size (scene files give 2:1 ones), its pixels finite and not negative;
    /// `strength` finite and not negative (both checked).
    EnvironmentMap(Image image, float strength, float rotation_degrees);

    /// Radiance arriving from unit direction w (pointing away from the scene, towards the sky).
    Rgb radiance(Vec3 w) const;

    struct Sample {
        Vec3 w;
        Rgb radiance;
        float pdf = 0;  // per unit solid angle
    };
    /// Directions in proportion to the image's luminance times the pixel's solid angle (uniform
    /// over the sphere for a uniform colour). std::nullopt when the map is black everywhere
    /// (nothing to find) or, rarely, for u at a pole of the image. The sample's pdf and radiance
    /// are pdf(w) and radiance(w), bit for bit.
    std::optional<Sample> sample(Vec2 u) const;
    /// The solid-angle density sample() gives w; 0 when the map is black everywhere, and at the
    /// two poles (where sin θ = 0, a set of no measure).
    float pdf(Vec3 w) const;

    /// Directions for the light a surface of unit normal `n` receives: about the image's
    /// luminance times the cosine to n (exactly to the nearest of the fixed normals, on cells of
    /// pixels; see above). For an image only: nullopt for a uniform colour (whose cosine-weighted
    /// sampling is exact), where sample() gives none, and rarely at the edge of a cell that sends
    /// nothing towards n (rounding puts the direction across it). The sample's pdf is
    /// pdf_facing(n, w).
    std::optional<Sample> sample_facing(Vec3 n, Vec2 u) const;
    /// The solid-angle density sample_facing(n, ·) gives w; 0 for a uniform colour.
    float pdf_facing(Vec3 n, Vec3 w) const;

    /// Mean luminance of the radiance over the sphere (1/4π ∫ L dω), for choosing among lights.
    float mean_luminance() const { return m_mean_luminance; }
    /// No direction sends any light.
    bool is_black() const { return m_black; }
    /// A uniform colour (no image).
    bool is_uniform() const { return m_image.pixels.empty(); }
    /// The image's pixels (0 for a uniform colour).
    size_t pixel_count() const { return m_image.pixels.size(); }
    /// Hash of everything that determines the radiance (pixels, size, strength, rotation, colour),
    /// for the static cache's staleness check.
    uint64_t hash() const;

private:
    /// Where w is looked up: (u, 1 - v), the image's x to the right and y down its rows, the
    /// distribution's coordinates; and sin θ.
    struct ImagePoint {
        Vec2 uv;
        float sin_theta = 0;
    };
    ImagePoint image_point(Vec3 w) const;
    /// The direction that looks up (u, 1 - v) = uv: image_point's inverse.
    Vec3 direction_at(Vec2 uv) const;
    /// Builds the cells and their weights per fixed normal from the pixels' sampling weights.
    void build_facing(const std::vector<float>& weights);
    /// The width in pixels of the cells in column cx (the last column may be narrower).
    int cell_width(int cx) const;

    Rgb m_radiance;  // the uniform colour; unused with an image
    Image m_image;   // empty for a uniform colour
    float m_strength = 1, m_rotation_degrees = 0;
    float m_cos_rotation = 1, m_sin_rotation = 0;
    Distribution2D m_distribution;              // over the pixels, for an image
    int m_cells_x = 0, m_cells_y = 0;           // cells of the facing sampling
    std::vector<Distribution1D> m_cell_pixels;  // per cell (row-major): over its pixels, row-major
    std::vector<Distribution1D> m_facing;       // per fixed normal: over the cells
    float m_mean_luminance = 0;
    bool m_black = true;  // no direction sends any light
};

}  // namespace steadylight
