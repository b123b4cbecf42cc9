// Textures at surfaces: alpha cut-outs for every kind of ray, base colour x vertex colour, and
// normal maps, on a scene of one textured quad.
#include <gtest/gtest.h>

#include <cmath>

#include "steadylight/scene/mesh_attributes.h"
#include "steadylight/scene/shapes.h"
#include "steadylight/shading/surface_point.h"
#include "support/scene_builder.h"

namespace steadylight {
namespace {

/// A 2 x 1 image with opaque red on the left, transparent on the right.
TextureImage half_cut_out() {
    return {.name = "mask", .width = 2, .height = 1, .rgba = {255, 0, 0, 255, 255, 0, 0, 0}};
}

/// A 2 x 2 quad in the plane y = 0, facing +y, with uv = (x + 1) / 2, (z + 1) / 2, under a
/// camera looking down; its material is `material` with texture image 0 = `image`.
SceneDesc quad_with_texture(MaterialDesc material, TextureImage image) {
    SceneDesc desc = testing::make_empty_scene({0, 5, 0.001f}, {0, 0, 0});
    desc.images.push_back(std::move(image));
    const int m = testing::add_material(desc, material);
    TriangleMesh quad = make_quad({-1, 0, -1}, {0, 0, 2}, {2, 0, 0});
    quad.normals.assign(4, Vec3{0, 1, 0});
    quad.uv0 = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};  // corners at z = -1, z = +1 (x = -1), then x = +1
    testing::add_object(desc, quad, m);
    return desc;
}

MaterialDesc masked(AlphaMode mode) {
    return {.type = MaterialType::pbr,
            .reflectance = {1, 1, 1},
            .alpha_mode = mode,
            .base_color_texture = {.image = 0, .filter = TextureFilter::nearest}};
}

// Alpha MASK cuts holes that camera rays (intersect) and shadow and photon rays alike pass.
TEST(TexturedSurface, AlphaMaskCutsHolesForEveryRay) {
    for (const AlphaMode mode : {AlphaMode::mask, AlphaMode::blend}) {
        const Scene scene(quad_with_texture(masked(mode), half_cut_out()));
        const RayTracer tracer(scene, scene.evaluate(0));
        const Ray opaque{{-0.5f, 5, 0}, {0, -1, 0}}, cut{{0.5f, 5, 0}, {0, -1, 0}};
        EXPECT_TRUE(tracer.intersect(opaque).has_value());
        EXPECT_TRUE(tracer.occluded(opaque));
        EXPECT_FALSE(tracer.intersect(cut).has_value());
        EXPECT_FALSE(tracer.occluded(cut));
    }
    // OPAQUE ignores alpha.
    const Scene scene(quad_with_texture(masked(AlphaMode::opaque), half_cut_out()));
    const RayTracer tracer(scene, scene.evaluate(0));
    EXPECT_TRUE(tracer.intersect({{0.5f, 5, 0}, {0, -1, 0}}).has_value());
}

// The base colour texture multiplies the base colour factor and vertex colours, sRGB decoded.
TEST(TexturedSurface, BaseColourIsFactorTimesTextureTimesVertexColour) {
    SceneDesc desc = quad_with_texture({.type = MaterialType::pbr,
                                        .reflectance = {0.5f, 1, 1},
                                        .base_color_texture = {.image = 0, .filter = TextureFilter::nearest}},
                                       {.name = "grey", .width = 1, .height = 1, .rgba = {128, 255, 255, 255}});
    auto& mesh = std::get<TriangleMesh>(desc.objects[0].geometry);
    mesh.colors.assign(4, Rgba{1, 0.5f, 1, 1});
    const Rgba c = base_color_at(desc, desc.materials[0], surface_attributes(mesh, {0, 0.3f, 0.3f}));
    EXPECT_NEAR(c[0], 0.5f * srgb_to_linear(128), 1e-6f);
    EXPECT_NEAR(c[1], 0.5f, 1e-6f);
    EXPECT_NEAR(c[2], 1, 1e-6f);
}

// A normal map texel (0.5 + 0.5 sin 45deg, 0.5, 0.5 + 0.5 cos 45deg) tilts the shading normal
// 45 degrees towards the tangent (+u); the cache's normal (ns) stays the interpolated one.
TEST(TexturedSurface, NormalMapTiltsTheBsdfFrameNotTheInterpolatedNormal) {
    const uint8_t x = uint8_t(std::lround(255 * (0.5 + 0.5 * std::sqrt(0.5)))), mid = 128;
    MaterialDesc material{.type = MaterialType::pbr, .normal_texture = {.image = 0, .filter = TextureFilter::nearest}};
    SceneDesc desc =
        quad_with_texture(material, {.name = "normals", .width = 1, .height = 1, .rgba = {x, mid, x, 255}});
    auto& mesh = std::get<TriangleMesh>(desc.objects[0].geometry);
    generate_tangents(mesh, 0);
    const Scene scene(std::move(desc));
    const FrameState frame = scene.evaluate(0);
    const RayTracer tracer(scene, frame);
    const Ray ray{{0.2f, 5, 0.1f}, {0, -1, 0}};
    const std::optional<Hit> hit = tracer.intersect(ray);
    ASSERT_TRUE(hit);
    const SurfacePoint sp = make_surface_point(scene, frame, ray, *hit);
    EXPECT_NEAR(sp.ns.y, 1, 1e-6f);
    // u grows with x on this quad, so the tangent is +x.
    EXPECT_NEAR(sp.nm.x, std::sqrt(0.5f), 0.01f);
    EXPECT_NEAR(sp.nm.y, std::sqrt(0.5f), 0.01f);
    EXPECT_NEAR(sp.nm.z, 0, 0.01f);
}

// An emissive texture tints the emission where a ray meets the light and where a light sample
// lands: the black half of a black-and-white light emits nothing.
TEST(TexturedSurface, EmissiveTextureTintsTheLight) {
    MaterialDesc material{.type = MaterialType::pbr,
                          .reflectance = {0, 0, 0},
                          .emissive_texture = {.image = 0, .filter = TextureFilter::nearest}};
    SceneDesc desc = quad_with_texture(
        material, {.name = "half", .width = 2, .height = 1, .rgba = {255, 255, 255, 255, 0, 0, 0, 255}});
    desc.objects[0].emission = {2, 2, 2};
    const Scene scene(std::move(desc));
    const PreparedFrame prepared(scene, 0);
    const FrameContext& context = prepared.context();
    for (const float x : {-0.5f, 0.5f}) {
        const Ray ray{{x, 5, 0}, {0, -1, 0}};
        const std::optional<Hit> hit = context.tracer.intersect(ray);
        ASSERT_TRUE(hit);
        const SurfacePoint sp = make_surface_point(scene, context.frame, ray, *hit);
        EXPECT_NEAR(emitted_radiance_at(context, sp, -ray.d).r, x < 0 ? 2.0f : 0.0f, 1e-6f);
    }
    // Light samples seen from above: Li is 2 or 0 as the point lands on the white or black half.
    int white = 0, black = 0;
    for (int i = 0; i < 64; ++i) {
        const std::optional<LightSample> s =
            context.lights.sample({0, 1, 0}, 0.5f, {(float(i % 8) + 0.5f) / 8, (float(i / 8) + 0.5f) / 8});
        if (!s) {
            ++black;
            continue;
        }  // a black sample is no sample
        EXPECT_NEAR(s->Li.g, 2.0f, 1e-6f);
        EXPECT_LT(s->p.x, 0.0f);
        ++white;
    }
    EXPECT_GT(white, 10);
    EXPECT_GT(black, 10);
}

}  // namespace
}  // namespace steadylight
