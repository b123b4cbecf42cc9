// The method table: names, settings, and the layers each method's frames really have.
#include "steadylight/methods/method.h"

#include <gtest/gtest.h>

#include "steadylight/base/error.h"
#include "steadylight/passes/segment_pass.h"
#include "support/input_error.h"

namespace steadylight {
namespace {

TEST(Methods, EveryMethodIsFoundByItsName) {
    for (const MethodInfo& info : methods()) {
        ASSERT_NE(find_method(info.name), nullptr) << info.name;
        EXPECT_EQ(find_method(info.name)->method, info.method);
        EXPECT_EQ(&method_info(info.method), &info);
        EXPECT_EQ(parse_method(info.name, "--method"), info.method);
    }
    EXPECT_EQ(methods().front().method, MethodSettings{}.method);  // the default first
    EXPECT_EQ(method_names(), "localized, photon, frozen, path");
}

TEST(Methods, UnknownNameIsAnInputErrorListingTheMethods) {
    EXPECT_EQ(find_method("fast"), nullptr);
    EXPECT_EQ(testing::input_error_of([] { parse_method("fast", "--method"); }),
              "--method: unknown method \"fast\" (localized, photon, frozen, path)");
}

TEST(Methods, OnlyTheLocalizedMethodsHaveAStaticPassAndPhotonIsTheReference) {
    EXPECT_TRUE(method_info(Method::localized).has_static_pass);
    EXPECT_TRUE(method_info(Method::frozen).has_static_pass);
    EXPECT_FALSE(method_info(Method::photon).has_static_pass);
    EXPECT_FALSE(method_info(Method::path).has_static_pass);
    for (const MethodInfo& info : methods()) EXPECT_EQ(info.is_reference, info.method == Method::photon) << info.name;
}

TEST(Methods, SettingsJsonHoldsWhatTheMethodReads) {
    MethodSettings settings;
    for (const MethodInfo& info : methods()) {
        settings.method = info.method;
        const nlohmann::json json = method_settings_json(settings);
        EXPECT_EQ(json.contains("path"), info.reads.path) << info.name;
        EXPECT_EQ(json.contains("photon"), info.reads.photon) << info.name;
        EXPECT_EQ(json.contains("localized"), info.reads.localized) << info.name;
        EXPECT_NO_THROW(validate(settings)) << info.name;
    }
}

TEST(Methods, ValidationChecksTheChosenMethodsSettingsOnly) {
    MethodSettings settings;
    settings.localized.tau_lower = 2;  // above tau_upper = 1
    EXPECT_EQ(testing::input_error_of([&] { validate(settings); }),
              "settings /localized/tau_upper: must be larger than tau_lower (--tau-upper, --tau-lower)");
    settings.method = Method::photon;  // reads no localized settings
    EXPECT_NO_THROW(validate(settings));
    settings.photon.cache.min_spacing_px = 40;  // above max_spacing_px = 32
    EXPECT_THROW(validate(settings), InputError);
    settings.method = Method::path;
    settings.path.samples_per_pixel = 0;
    EXPECT_EQ(testing::input_error_of([&] { validate(settings); }),
              "settings /path/samples_per_pixel: 0 is outside [1, 1048576]");
}

TEST(Methods, FramesHaveTheTablesLayersAndStatistics) {
    Scene scene(load_scene_desc(std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/ball.json"));
    scene.set_resolution(8, 6);
    MethodSettings settings;
    settings.photon.photons = {.global_photons = 4000, .caustic_photons = 1000};
    settings.photon.shading.samples_per_pixel = settings.path.samples_per_pixel = 1;
    RayTracer tracer(scene, scene.evaluate(0));
    const StaticSolution solution{run_segment_pass(scene, tracer, {0, 0}, settings.photon)};
    const PreparedFrame frame(scene, 0);
    for (const MethodInfo& info : methods()) {
        settings.method = info.method;
        const RenderedFrame rendered = info.render_frame(frame.context(), info.has_static_pass ? &solution : nullptr,
                                                         settings, AnalysisLayers::made);
        EXPECT_EQ(rendered.beauty.width, 8);
        std::vector<std::string_view> names;
        for (const NamedImage& layer : rendered.layers) {
            names.push_back(layer.name);
            EXPECT_EQ(layer.pixel_count(), rendered.beauty.pixels.size()) << layer.name;
            // Grey: one value per pixel, the influence and the masks.
            EXPECT_EQ(layer.grey() != nullptr, layer.name == "influence" || layer.name == "dynamic" ||
                                                   layer.name == "changed" || layer.name.ends_with("records"))
                << layer.name;
            for (size_t i = 0; i < layer.pixel_count(); ++i)
                ASSERT_TRUE(is_finite(layer.colour_at(i)) && max_component(layer.colour_at(i)) <= 1000) << layer.name;
        }
        std::vector<std::string_view> table_names;
        for (const LayerInfo& layer : info.layers) {
            table_names.push_back(layer.name);
            // The light's terms are the same four in every method that has AOVs; the rest show
            // how the method worked.
            const bool is_term = layer.name == "direct" || layer.name == "indirect" || layer.name == "caustic" ||
                                 layer.name == "specular";
            EXPECT_EQ(layer.kind, is_term ? LayerKind::term : LayerKind::analysis) << layer.name;
        }
        EXPECT_EQ(names, table_names) << info.name;
        // Every method has statistics, the path tracer too (time, samples, rays).
        ASSERT_TRUE(rendered.stats.has_value()) << info.name;
        EXPECT_EQ(rendered.stats->method, info.name);
        EXPECT_GT(rendered.stats->total_s, 0) << info.name;
    }
}

}  // namespace
}  // namespace steadylight
