// The memory model (memory_model.cpp): estimates, limits and the error that names what to lower.
#include "steadylight/run/memory_model.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "steadylight/base/error.h"
#include "support/scene_builder.h"

namespace steadylight {
namespace {

std::string error_of(const MemoryEstimate& need, size_t limit) {
    try {
        check_memory(need, {limit, "a test limit"});
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(MemoryModel, GrowsWithPixelsPhotonsTrianglesAndTheWorldImage) {
    SceneDesc desc = testing::make_empty_scene({0, 0, -3}, {0, 0, 0}, 100, 50);
    testing::add_object(desc, make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), testing::add_material(desc, {}), {1, 1, 1});
    const Scene scene(std::move(desc));
    EXPECT_EQ(triangle_count(scene.desc()), 2);
    RenderSettings settings;
    settings.method = Method::photon;
    settings.photon.photons = {.global_photons = 1000, .caustic_photons = 3000};
    const MemoryEstimate photon = estimate_memory(settings, scene);
    EXPECT_DOUBLE_EQ(photon.pixels, 100 * 50 * 300.0);
    EXPECT_DOUBLE_EQ(photon.photons, 4000 * 650.0);
    EXPECT_DOUBLE_EQ(photon.scene, 2 * 160.0);
    for (const Method layered : {Method::localized, Method::frozen}) {
        settings.method = layered;
        EXPECT_DOUBLE_EQ(estimate_memory(settings, scene).pixels, 100 * 50 * 540.0);
    }
    settings.method = Method::path;
    const MemoryEstimate path = estimate_memory(settings, scene);
    EXPECT_DOUBLE_EQ(path.pixels, 100 * 50 * 60.0);
    EXPECT_EQ(path.photons, 0);
    // A world image counts with the scene, a uniform world not.
    SceneDesc lit = scene.desc();
    lit.world = WorldDesc::uniform({1, 1, 1});
    EXPECT_DOUBLE_EQ(estimate_memory(settings, Scene(lit)).scene, 2 * 160.0);
    lit.world->radiance = std::make_shared<EnvironmentMap>(Image(64, 32), 1.0f, 0.0f);
    EXPECT_DOUBLE_EQ(estimate_memory(settings, Scene(lit)).scene, 2 * 160.0 + 64 * 32 * 48.0);
}

TEST(MemoryModel, TooMuchIsAnErrorNamingWhatToLower) {
    const MemoryEstimate image_bound{.scene = 1e6, .pixels = 67e9, .photons = 1e8};
    EXPECT_EQ(error_of(image_bound, size_t(100e9)), "");
    const std::string image = error_of(image_bound, size_t(24e9));
    EXPECT_NE(image.find("needs about 67.2 GB"), std::string::npos) << image;
    EXPECT_NE(image.find("more than the 24.0 GB available (a test limit)"), std::string::npos) << image;
    EXPECT_NE(image.find("lower --size"), std::string::npos) << image;
    EXPECT_NE(error_of({.scene = 1e6, .pixels = 1e7, .photons = 30e9}, size_t(24e9))
                  .find("lower --photons and --caustic-photons"),
              std::string::npos);
    EXPECT_NE(error_of({.scene = 40e9, .pixels = 1e7, .photons = 1e8}, size_t(24e9))
                  .find("the scene's triangles or world image"),
              std::string::npos);
}

TEST(MemoryModel, SlurmsLimitCounts) {
    const MemoryLimit machine = memory_available();
    EXPECT_GT(machine.bytes, size_t(0));
    setenv("SLURM_MEM_PER_NODE", "100", 1);
    const MemoryLimit slurm = memory_available();
    unsetenv("SLURM_MEM_PER_NODE");
    EXPECT_EQ(slurm.bytes, size_t(100) * 1024 * 1024);
    EXPECT_EQ(slurm.source, "Slurm's SLURM_MEM_PER_NODE");
    setenv("SLURM_MEM_PER_CPU", "64", 1);
    setenv("SLURM_CPUS_ON_NODE", "2", 1);
    const MemoryLimit per_cpu = memory_available();
    unsetenv("SLURM_MEM_PER_CPU");
    unsetenv("SLURM_CPUS_ON_NODE");
    EXPECT_EQ(per_cpu.bytes, size_t(128) * 1024 * 1024);
}

}  // namespace
}  // namespace steadylight
