// The settings file: JSON round trip of the method settings, resume with same or other settings.
#include "steadylight/run/settings_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "steadylight/base/error.h"
#include "support/input_error.h"
#include "support/lock_files.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

class SettingsFile : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir = testing::fresh_test_folder();
        m_settings.scene_file = (m_dir / "scene.json").string();
        std::ofstream(m_settings.scene_file) << "{}";
        m_path = settings_file_name(m_dir.string(), "scene");
    }
    void TearDown() override { fs::remove_all(m_dir); }

    nlohmann::json json(std::vector<int> frames, int threads = 2) const {
        return make_settings_json(m_settings, {"scene", 40, 30, std::move(frames), threads});
    }
    nlohmann::json read() const { return nlohmann::json::parse(std::ifstream(m_path)); }

    fs::path m_dir;
    std::string m_path;
    RenderSettings m_settings;
};

TEST(SettingsJson, MethodSettingsRoundTrip) {
    PhotonMappingSettings photon;
    photon.photons.global_photons = 1234;
    photon.gather.fixed_directions = false;
    photon.cache.accuracy = 0.125f;
    photon.shading.caustic_estimate.k = 7;
    const nlohmann::json json = photon;
    EXPECT_EQ(json["photons"]["global_photons"], 1234);
    EXPECT_EQ(nlohmann::json(json.get<PhotonMappingSettings>()), json);

    LocalizedSettings localized;
    localized.tau_upper = 2.5f;
    EXPECT_EQ(nlohmann::json(nlohmann::json(localized).get<LocalizedSettings>()), nlohmann::json(localized));
    PathTracerSettings path{.samples_per_pixel = 3, .seed = 9};
    EXPECT_EQ(nlohmann::json(path).get<PathTracerSettings>().seed, 9u);
    path.fixed_seed = true;
    EXPECT_EQ(nlohmann::json(path)["fixed_seed"], true);
    EXPECT_TRUE(nlohmann::json(path).get<PathTracerSettings>().fixed_seed);
    // Settings written before fixed_seed existed read it as false.
    nlohmann::json older = path;
    older.erase("fixed_seed");
    EXPECT_FALSE(older.get<PathTracerSettings>().fixed_seed);
}

TEST_F(SettingsFile, HoldsTheChosenMethodsSettingsOnly) {
    const nlohmann::json localized = json({0, 1});
    EXPECT_TRUE(localized["render"].contains("photon"));
    EXPECT_TRUE(localized["render"].contains("localized"));
    EXPECT_FALSE(localized["render"].contains("path"));
    EXPECT_EQ(localized["frames"], "0-1");
    EXPECT_EQ(localized["render"]["size"], nlohmann::json({40, 30}));
    m_settings.method = Method::path;
    EXPECT_EQ(json({0})["render"].count("photon"), 0u);
    EXPECT_NE(settings_key(json({0})), settings_key(localized));
    // --fixed-seed changes the path tracer's images: it is part of the settings key.
    EXPECT_EQ(json({0})["render"]["path"]["fixed_seed"], false);
    const std::string key = settings_key(json({0}));
    m_settings.path.fixed_seed = true;
    EXPECT_NE(settings_key(json({0})), key);
}

TEST_F(SettingsFile, SameSettingsResumeAndCollectFrames) {
    write_settings_file(m_path, json({0, 1}), false);
    // Other frames, threads or date are not other settings.
    EXPECT_NO_THROW(write_settings_file(m_path, json({5}, 1), false));
    EXPECT_EQ(read()["frames"], "0-1,5");
    EXPECT_EQ(settings_key(read()), settings_key(json({})));
}

TEST_F(SettingsFile, DamagedFrameListIsReplacedByThisRunsFrames) {
    // Not a string, not a frame list, and more frames than a scene may have (which would take
    // gigabytes to list).
    for (const nlohmann::json& damaged : {nlohmann::json(5), nlohmann::json("1-x"), nlohmann::json("0-2000000000")}) {
        nlohmann::json earlier = json({0, 1});
        earlier["frames"] = damaged;
        std::ofstream(m_path) << earlier.dump();
        EXPECT_NO_THROW(write_settings_file(m_path, json({5}), false)) << damaged;
        EXPECT_EQ(read()["frames"], "5") << damaged;
    }
}

TEST_F(SettingsFile, OtherSettingsAreAnErrorNamingThem) {
    write_settings_file(m_path, json({0, 1}), false);
    m_settings.photon.photons.global_photons = 5000;
    try {
        write_settings_file(m_path, json({0, 1}), false);
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/photon/photons/global_photons: 200000 -> 5000"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("--overwrite"), std::string::npos);
    }
    EXPECT_EQ(read()["render"]["photon"]["photons"]["global_photons"], 200000);
}

TEST_F(SettingsFile, OutputSettingsShapeTheImagesButTheVideoDoesNot) {
    write_settings_file(m_path, json({0}), false);
    m_settings.output.video_file = "ball.mp4";
    EXPECT_NO_THROW(write_settings_file(m_path, json({1}), false));
    EXPECT_EQ(read()["video"], "ball.mp4");
    m_settings.output.view.exposure_ev = 1.5f;
    try {
        write_settings_file(m_path, json({2}), false);
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/output/exposure_ev: 0.0 -> 1.5"), std::string::npos) << e.what();
    }
    EXPECT_EQ(read()["render"]["output"]["exr_type"], "half");
}

TEST_F(SettingsFile, OverwriteReplacesOtherSettings) {
    write_settings_file(m_path, json({0, 1}), false);
    m_settings.method = Method::photon;
    EXPECT_NO_THROW(write_settings_file(m_path, json({1}), true));
    EXPECT_EQ(read()["render"]["method"], "photon");
    EXPECT_EQ(read()["frames"], "1");
}

TEST_F(SettingsFile, OlderFormatIsRefusedSayingWhy) {
    // A folder from before settings format 2: no version, the photon settings also under
    // "localized/base".
    nlohmann::json older = json({0, 1});
    older["render"].erase("format_version");
    older["render"]["localized"]["base"] = older["render"]["photon"];
    std::ofstream(m_path) << older.dump(2);
    const std::string error = testing::input_error_of([&] { write_settings_file(m_path, json({0, 1}), false); });
    EXPECT_NE(error.find("settings file format 1, this steadylight writes format 2"), std::string::npos) << error;
    EXPECT_NO_THROW(write_settings_file(m_path, json({0, 1}), true));
    EXPECT_EQ(read()["render"]["format_version"], settings_format_version);
}

TEST_F(SettingsFile, ChangedSceneFileIsOtherSettings) {
    write_settings_file(m_path, json({0}), false);
    std::ofstream(m_settings.scene_file) << "{ }";
    EXPECT_THROW(write_settings_file(m_path, json({0}), false), InputError);
}

}  // namespace
}  // namespace steadylight
