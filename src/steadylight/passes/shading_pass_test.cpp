// The shading pass (shading_pass.h) on scenes with known answers: the light a glossy floor sees
// in a flat mirror (shading/mirror_images.h) taken as its image's direct light; and every pixel
// of the images it returns written, as their unfilled memory needs.
#include "steadylight/passes/shading_pass.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "support/freed_blocks.h"
#include "support/scene_builder.h"

namespace steadylight {
namespace {

using testing::add_material;
using testing::add_object;
using testing::leave_in_freed_blocks;
using testing::make_empty_scene;

/// A glossy floor (y = 0, x in [0, 4]) under a small light at x = 2, seen looking towards x = 0
/// (where its glossy reflection sees the light's image): with a mirror in the plane x = 0, or
/// with the light's mirror image (at x = -2, dimmed by the mirror's reflectance) in its place.
SceneDesc glossy_floor_beside(bool mirror) {
    SceneDesc desc = make_empty_scene({4, 1.5f, 1}, {1, 0, 1}, 8, 8, 30);
    const int glossy =
        add_material(desc, {.type = MaterialType::glossy, .reflectance = {0.5f, 0.5f, 0.5f}, .roughness = 0.35f});
    add_object(desc, make_quad({0, 0, -4}, {0, 0, 8}, {4, 0, 0}), glossy);
    const Rgb Le{20, 20, 20};
    const auto light_at = [&](float x, Rgb emission) {
        add_object(desc, make_quad({x - 0.25f, 2.5f, 0.75f}, {0.5f, 0, 0}, {0, 0, 0.5f}), add_material(desc, {}),
                   emission);
    };
    light_at(2, Le);
    if (mirror) {
        const int reflect = add_material(desc, {.type = MaterialType::mirror, .reflectance = {0.9f, 0.9f, 0.9f}});
        add_object(desc, make_quad({0, 0, -4}, {0, 6, 0}, {0, 0, 8}), reflect);
    } else {
        light_at(-2, Le * 0.9f);
    }
    return desc;
}

/// The mean of the direct layer over the image, by the shading pass alone (no indirect light).
double mean_direct_light(const SceneDesc& desc) {
    const Scene scene(desc);
    const PreparedFrame frame(scene, 0);
    ShadingSettings settings;
    settings.samples_per_pixel = 64;
    settings.direct_samples = 16;
    const auto none = [](auto&&...) { return Rgb{}; };
    const ShadedFrame shaded = shade_frame(frame.context(), settings, PhotonMap{}, none, none);
    double sum = 0;
    for (const Rgb& c : shaded.direct.pixels) sum += luminance(c);
    return sum / double(shaded.direct.pixels.size());
}

// The light a glossy floor sees in a flat mirror is sampled as a light (its image), so it is the
// image's direct light, not left to the floor's sampled bounce (which gave sparkles). The image
// is rendered alone and added: the light and its image in one scene would test the choice
// between two lights too.
TEST(MirrorImages, GlossyFloorTakesTheLightInAMirrorAsItsImagesDirectLight) {
    const double with_mirror = mean_direct_light(glossy_floor_beside(true));
    SceneDesc light_alone = glossy_floor_beside(false), image_alone = light_alone;
    light_alone.objects.pop_back();
    image_alone.objects.erase(image_alone.objects.begin() + 1);
    const double light = mean_direct_light(light_alone), image = mean_direct_light(image_alone);
    EXPECT_GT(image, light);  // the image's share is large enough to test
    EXPECT_NEAR(with_mirror / (light + image), 1, 0.01);
}

/// Every image of a frame, in a fixed order.
std::vector<const Image*> images_of(const ShadedFrame& frame, int extra_layers) {
    std::vector<const Image*> images{&frame.beauty, &frame.direct, &frame.indirect, &frame.caustic, &frame.specular};
    for (int e = 0; e < extra_layers; ++e) images.push_back(&frame.extra[size_t(e)]);
    if (frame.alpha) images.push_back(&*frame.alpha);
    return images;
}

// shade_frame's images are made unfilled (base/unfilled_allocator.h), so a pixel it did not write
// would show what the memory held before: the same frame shaded after the heap held NaNs and
// after it held ones is the same, bit for bit, in every image, and finite.
TEST(ShadeFrame, WritesEveryPixelOfEveryImage) {
    SceneDesc desc = glossy_floor_beside(true);
    desc.camera.transparent_background = true;  // the alpha image too
    const Scene scene(desc);
    const PreparedFrame frame(scene, 0);
    ShadingSettings settings;
    settings.samples_per_pixel = 4;
    const auto none = [](auto&&...) { return Rgb{}; };
    const auto some = [](auto&&...) { return Rgb{0.25f, 0.5f, 0.75f}; };
    const int extra_layers = 2;
    const size_t pixels = size_t(desc.camera.width) * size_t(desc.camera.height);
    const auto shade_after = [&](float left) {
        leave_in_freed_blocks(pixels, left);
        return shade_frame(frame.context(), settings, PhotonMap{}, some, none, Visibility::everything, nullptr,
                           extra_layers);
    };
    const ShadedFrame after_nan = shade_after(std::numeric_limits<float>::quiet_NaN());
    const ShadedFrame after_one = shade_after(1);
    const std::vector<const Image*> a = images_of(after_nan, extra_layers), b = images_of(after_one, extra_layers);
    ASSERT_EQ(a.size(), size_t(5 + extra_layers + 1));
    for (size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a[i]->pixels.size(), pixels) << "image " << i;
        ASSERT_EQ(b[i]->pixels.size(), pixels) << "image " << i;
        EXPECT_EQ(std::memcmp(a[i]->pixels.data(), b[i]->pixels.data(), pixels * sizeof(Rgb)), 0) << "image " << i;
        for (const Rgb& c : a[i]->pixels) ASSERT_TRUE(std::isfinite(c.r + c.g + c.b)) << "image " << i;
    }
}

}  // namespace
}  // namespace steadylight
