// L_t's correction (record_correction.h): signed photons on a floor, against the change they stand for.
#include "steadylight/passes/record_correction.h"

#include <gtest/gtest.h>

#include <cstring>

#include "steadylight/base/halton.h"
#include "steadylight/base/rng.h"

namespace steadylight {
namespace {

constexpr Vec3 up{0, 1, 0};

/// A photon on the floor (y = height), arriving from above, of luminance-1-per-unit grey power.
Photon floor_photon(float x, float z, float power, float height = 0) { return {{x, height, z}, up, up, {power, power, power}}; }

/// `count` photons of power `power` at Halton points of [x0, x1] x [-4, 4] on the floor.
std::vector<Photon> uniform_photons(int count, float power, float x0 = -4, float x1 = 4, float height = 0) {
    std::vector<Photon> photons;
    for (int i = 0; i < count; ++i)
        photons.push_back(floor_photon(x0 + (x1 - x0) * halton(0, uint64_t(i)), -4 + 8 * halton(1, uint64_t(i)), power, height));
    return photons;
}

Rgb correction(const std::vector<Photon>& photons, Vec3 p, const float* shares = nullptr) {
    const PhotonMap map(photons, long(photons.size()));
    return correction_at(map, p, up, CorrectionSettings{}, shares);
}

// Positive and negative photons at random, equally many: no change, and the estimate says so
// exactly almost everywhere (a detail beyond 3 standard errors by chance is rare), where the
// paper's 300-nearest estimate reads their imbalance.
TEST(RecordCorrection, NoiseAloneGivesNoChange) {
    Pcg32 rng(11);
    std::vector<Photon> photons;
    for (int i = 0; i < 20'000; ++i) photons.push_back(floor_photon(-4 + 8 * rng.next_float(), -4 + 8 * rng.next_float(), i % 2 ? 1e-3f : -1e-3f));
    const PhotonMap map(photons, long(photons.size()));
    int zero = 0;
    double sum = 0;
    for (int i = 0; i < 100; ++i) {
        const Vec3 p{-2 + 4 * rng.next_float(), 0, -2 + 4 * rng.next_float()};
        const Rgb delta = correction_at(map, p, up, CorrectionSettings{}, nullptr);
        zero += delta == Rgb{};
        sum += luminance(delta);
    }
    EXPECT_GE(zero, 95);
    // One photon over the finest disc's area would be 1e-3 / 0.196 = 5e-3.
    EXPECT_LT(std::abs(sum / 100), 2e-4);
}

// A change that covers the floor evenly: kept whole, at every point whose discs lie on the floor.
TEST(RecordCorrection, EvenChangeIsKeptWhole) {
    const int count = 20'000;
    const std::vector<Photon> photons = uniform_photons(count, -1e-3f);
    const double truth = -1e-3 * count / 64;
    for (const Vec3 p : {Vec3{0, 0, 0}, Vec3{1.5f, 0, -1}, Vec3{-1.2f, 0, 1.7f}})
        EXPECT_NEAR(luminance(correction(photons, p)), truth, 0.02 * std::abs(truth)) << p.x << " " << p.z;
}

// A sharp change, a disc of radius 0.5 darkened: at its centre the finest discs that stand out
// of their noise lie inside it, and read all of it.
TEST(RecordCorrection, SharpChangeIsKeptAtItsCentre) {
    std::vector<Photon> photons;
    const double density = 4000;  // photons per m^2
    for (int i = 0; photons.size() < size_t(density * pi * 0.25); ++i) {
        const float x = -0.5f + halton(0, uint64_t(i)), z = -0.5f + halton(1, uint64_t(i));
        if (x * x + z * z <= 0.25f) photons.push_back(floor_photon(x, z, -1e-3f));
    }
    EXPECT_NEAR(luminance(correction(photons, {0, 0, 0})), -1e-3 * density, 0.04 * 1e-3 * density);
}

// At the edge of a surface half of each disc is off it: the disc's share (1/2) restores the
// change; without it the estimate reads half.
TEST(RecordCorrection, DiscShareOnTheSurfaceRestoresTheChangeAtAnEdge) {
    const int count = 20'000;
    const std::vector<Photon> photons = uniform_photons(count, -1e-3f, 0, 4);
    const double truth = -1e-3 * count / 32;
    const float halves[max_correction_levels] = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
    EXPECT_NEAR(luminance(correction(photons, {0, 0, 0}, halves)), truth, 0.03 * std::abs(truth));
    EXPECT_NEAR(luminance(correction(photons, {0, 0, 0})), truth / 2, 0.03 * std::abs(truth));
}

// Photons on a parallel surface 0.8 below (the floor under a table top) are not on the record's
// disc at any level, although the coarsest reaches 2.
TEST(RecordCorrection, PhotonsOffTheTangentPlaneDoNotCount) {
    const std::vector<Photon> photons = uniform_photons(20'000, -1e-3f, -4, 4, -0.8f);
    EXPECT_EQ(correction(photons, {0, 0, 0}), Rgb{});
}

// Without dynamic photons the records are the static ones bit for bit, and none is flagged.
TEST(RecordCorrection, NoDynamicPhotonsLeaveTheRecordsAsTheyAre) {
    IrradianceCache cache;
    cache.insert({.p = {0, 0, 0}, .n = up, .E = {0.5f, -0.0f, 0.25f}, .radius = 0.3f});
    cache.insert({.p = {1, 0, 0}, .n = up, .E = {0.1f, 0.2f, 0.3f}, .radius = 0.3f});
    std::vector<uint8_t> changed;
    const IrradianceCache corrected = corrected_cache(cache, PhotonMap{}, CorrectionSettings{}, {}, &changed);
    ASSERT_EQ(corrected.records().size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(std::memcmp(&corrected.records()[i].E, &cache.records()[i].E, sizeof(Rgb)), 0);
        EXPECT_EQ(changed[i], 0);
    }
}

}  // namespace
}  // namespace steadylight
