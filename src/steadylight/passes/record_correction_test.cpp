// L_t's correction (record_correction.h): signed photons on a floor, against the change they stand for.
#include "steadylight/passes/record_correction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>

#include "steadylight/base/halton.h"
#include "steadylight/base/rng.h"
#include "support/scene_builder.h"

namespace steadylight {
namespace {

constexpr Vec3 up{0, 1, 0};

/// A photon on the floor (y = height), arriving from above, of luminance-1-per-unit grey power.
Photon floor_photon(float x, float z, float power, float height = 0) {
    return {{x, height, z}, up, up, {power, power, power}};
}

/// `count` photons of power `power` at Halton points of [x0, x1] x [-4, 4] on the floor.
std::vector<Photon> uniform_photons(int count, float power, float x0 = -4, float x1 = 4, float height = 0) {
    std::vector<Photon> photons;
    for (int i = 0; i < count; ++i)
        photons.push_back(
            floor_photon(x0 + (x1 - x0) * halton(0, uint64_t(i)), -4 + 8 * halton(1, uint64_t(i)), power, height));
    return photons;
}

Rgb correction(const std::vector<Photon>& photons, Vec3 p, const DiscProbes* probes = nullptr) {
    const PhotonMap map(photons, long(photons.size()));
    return correction_at(CorrectionPhotons(map, CorrectionSettings{}), p, up, CorrectionSettings{}, probes);
}

// Positive and negative photons at random, equally many: no change, and the estimate says so
// exactly almost everywhere (a detail beyond 3 standard errors by chance is rare), where the
// paper's 300-nearest estimate reads their imbalance.
TEST(RecordCorrection, NoiseAloneGivesNoChange) {
    Pcg32 rng(11);
    std::vector<Photon> photons;
    for (int i = 0; i < 20'000; ++i)
        photons.push_back(floor_photon(-4 + 8 * rng.next_float(), -4 + 8 * rng.next_float(), i % 2 ? 1e-3f : -1e-3f));
    const PhotonMap map(photons, long(photons.size()));
    const CorrectionPhotons photons_read(map, CorrectionSettings{});
    int zero = 0;
    double sum = 0;
    for (int i = 0; i < 100; ++i) {
        const Vec3 p{-2 + 4 * rng.next_float(), 0, -2 + 4 * rng.next_float()};
        const Rgb delta = correction_at(photons_read, p, up, CorrectionSettings{}, nullptr);
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

// The coarse levels read the photons summed by cells: over a floor darkened smoothly about a
// point (a shadow's soft halo) amid balanced noise, the corrections differ from those that read
// every photon one by one at every level (cells of size 0) by at most a few per cent of the change.
TEST(RecordCorrection, CoarseLevelsFromCellsAgreeWithEveryPhotonOneByOne) {
    Pcg32 rng(5);
    std::vector<Photon> photons;
    for (int i = 0; i < 40'000; ++i) {
        const float x = -4 + 8 * halton(0, uint64_t(i)), z = -4 + 8 * halton(1, uint64_t(i));
        if (rng.next_float() < std::exp(-(x * x + z * z) / 2)) photons.push_back(floor_photon(x, z, -1e-3f));
        photons.push_back(floor_photon(-4 + 8 * rng.next_float(), -4 + 8 * rng.next_float(), i % 2 ? 1e-3f : -1e-3f));
    }
    const PhotonMap map(photons, long(photons.size()));
    const CorrectionSettings settings;
    const CorrectionPhotons cells(map, settings), one_by_one(map, settings, 0);
    EXPECT_LT(cells.clusters().size(), photons.size() / 4);
    EXPECT_TRUE(cells.summed_by_cells());
    EXPECT_FALSE(one_by_one.summed_by_cells());
    double difference2 = 0, change2 = 0;
    for (int i = 0; i <= 8; ++i)
        for (int j = 0; j <= 8; ++j) {
            const Vec3 p{-2 + 0.5f * float(i), 0, -2 + 0.5f * float(j)};
            const double c = luminance(correction_at(cells, p, up, settings, nullptr));
            const double e = luminance(correction_at(one_by_one, p, up, settings, nullptr));
            difference2 += (c - e) * (c - e), change2 += e * e;
        }
    EXPECT_GT(change2, 0);
    EXPECT_LT(std::sqrt(difference2 / change2), 0.02);  // 1.1% measured
}

/// The probes of a disc centred on the edge x = 0 of the floor x > 0, turned by `turn` (as
/// surface_coverage.cpp places them, at the middle of each ring's area).
DiscProbes probes_on_the_floor_beyond_x_0(float turn) {
    const OrthonormalBasis basis = OrthonormalBasis::from_normal(up);
    DiscProbes probes;
    probes.reached = 0;
    probes.turn = turn;
    for (int ring = 0; ring < DiscProbes::rings; ++ring)
        for (int j = 0; j < DiscProbes::sectors; ++j) {
            const float phi = probes.angle(ring, j);
            if (basis.to_world({std::cos(phi), std::sin(phi), 0}).x > 0)
                probes.reached |= uint16_t(1u << (ring * DiscProbes::sectors + j));
        }
    return probes;
}

// At the edge of a surface half of each disc is off it: the probes (half the cells at every
// level, on average over their turns) restore the change; without them the estimate reads half.
TEST(RecordCorrection, DiscProbesOnTheSurfaceRestoreTheChangeAtAnEdge) {
    const int count = 20'000;
    const std::vector<Photon> photons = uniform_photons(count, -1e-3f, 0, 4);
    const double truth = -1e-3 * count / 32;
    double sum = 0;
    const int turns = 32;
    for (int i = 0; i < turns; ++i) {
        DiscProbes probes[max_correction_levels];
        std::fill(std::begin(probes), std::end(probes), probes_on_the_floor_beyond_x_0((float(i) + 0.5f) / turns));
        sum += luminance(correction(photons, {0, 0, 0}, probes));
    }
    EXPECT_NEAR(sum / turns, truth, 0.03 * std::abs(truth));
    EXPECT_NEAR(luminance(correction(photons, {0, 0, 0})), truth / 2, 0.03 * std::abs(truth));
}

// The kernel weighs a disc's inner ring (the half of its area nearer the centre) three times its
// outer one: with only the inner ring on the surface it holds 3/4 of the weight.
TEST(RecordCorrection, KernelShareWeighsTheInnerRingThreeTimes) {
    EXPECT_EQ(kernel_share(DiscProbes{}), 1.0f);
    EXPECT_EQ(kernel_share(DiscProbes{.reached = 0x00ff}), 0.75f);
    EXPECT_EQ(kernel_share(DiscProbes{.reached = 0xff00}), 0.25f);
    EXPECT_EQ(kernel_share(DiscProbes{.reached = 0x0101}), 1.0f / 8);
}

// A disc with less than a quarter of the kernel's weight on the surface (two inner cells: 3/16)
// reads nothing: with only the finest disc on the surface the change is the finest level's, and
// with none on it there is no change.
TEST(RecordCorrection, DiscsMostlyOffTheSurfaceReadNothing) {
    const std::vector<Photon> photons = uniform_photons(20'000, -1e-3f);
    DiscProbes probes[max_correction_levels];
    std::fill(std::begin(probes), std::end(probes), DiscProbes{.reached = 0x0003});
    EXPECT_EQ(correction(photons, {0, 0, 0}, probes), Rgb{});
    probes[0] = DiscProbes{};
    const PhotonMap map(photons, long(photons.size()));
    const CorrectionSettings finest_only{.levels = 1};
    EXPECT_EQ(correction(photons, {0, 0, 0}, probes),
              correction_at(CorrectionPhotons(map, finest_only), {0, 0, 0}, up, finest_only, nullptr));
}

/// A floor with strips 12 cm wide and 2 cm high every 24 cm (x = 0.24 i), as coloured stripes
/// stand proud of a wall, and photons of an even change on every face that looks up.
struct StripedFloor {
    Scene scene;
    std::vector<Photon> photons;
    double change = 0;  // per unit area

    static bool on_a_strip(float x) { return std::abs(x - 0.24f * std::round(x / 0.24f)) < 0.06f; }

    StripedFloor() : scene(make_desc()) {
        const int count = 200'000;
        for (int i = 0; i < count; ++i) {
            const float x = -4 + 8 * halton(0, uint64_t(i)), z = -4 + 8 * halton(1, uint64_t(i));
            photons.push_back(floor_photon(x, z, -1e-3f, std::abs(x) < 2 && on_a_strip(x) ? 0.02f : 0.0f));
        }
        change = -1e-3 * count / 64;
    }

    static SceneDesc make_desc() {
        SceneDesc desc = testing::make_empty_scene({0, 2, -5}, {0, 0, 0});
        const int white = testing::add_material(desc, {});
        testing::add_object(desc, make_quad({-4, 0, -4}, {0, 0, 8}, {8, 0, 0}), white);
        for (int i = -8; i <= 8; ++i)
            testing::add_object(desc, make_box({0.24f * float(i), 0.01f, 0}, {0.12f, 0.02f, 8}), white);
        return desc;
    }
};

// Records between the strips and on them read the even change within 6% (on average over
// records along the strips, each probed differently). The probes of a record between two
// strips stop at the strips' sides: the photons beyond, on the strips and the floor, lie in
// cells its surface does not reach and must not count, or, divided by the small share, they
// counted up to 16 times (blender_glass's stripes: their change came out twice the true one).
TEST(RecordCorrection, RecordsAmongStripsProudOfTheSurfaceReadTheChangeThere) {
    const StripedFloor floor;
    const PreparedFrame prepared(floor.scene, 0);
    const PhotonMap map(floor.photons, long(floor.photons.size()));
    for (const float x : {0.12f, 0.0f}) {  // between two strips, on one
        IrradianceCache cache;
        const float y = StripedFloor::on_a_strip(x) ? 0.02f : 0.0f;
        for (int i = 0; i < 16; ++i)
            cache.insert({.p = {x, y, -1.5f + 0.2f * float(i)}, .n = up, .E = {10, 10, 10}, .radius = 0.1f});
        const CorrectionPoints points;
        points.make(prepared.context(), cache, CorrectionSettings{});
        const IrradianceCache corrected_cache = correct_static_cache(cache, map, CorrectionSettings{}, &points);
        double sum = 0;
        for (const IrradianceRecord& r : corrected_cache.records()) sum += luminance(r.E) - 10;
        EXPECT_NEAR(sum / 16, floor.change, 0.06 * std::abs(floor.change)) << "x = " << x;
    }
}

// Photons on a parallel surface 0.8 below (the floor under a table top) are not on the record's
// disc at any level, although the coarsest reaches 2.
TEST(RecordCorrection, PhotonsOffTheTangentPlaneDoNotCount) {
    const std::vector<Photon> photons = uniform_photons(20'000, -1e-3f, -4, 4, -0.8f);
    EXPECT_EQ(correction(photons, {0, 0, 0}), Rgb{});
}

/// A floor and a table top 0.8 above it (x, z within 1 of 0), with records every 2 cm on both
/// (on the top up to its edge x = 1) and along the table's side there, and photons of an even
/// change on the floor alone.
struct FloorAndTable {
    static constexpr float spacing = 0.02f, table_height = 0.8f;
    Scene scene;
    IrradianceCache cache;
    std::vector<Photon> photons = uniform_photons(40'000, -1e-3f);
    double change = -1e-3 * 40'000 / 64;  // per unit area

    FloorAndTable() : scene(make_desc()) {
        for (int i = 0; i <= 60; ++i)
            for (int j = 0; j <= 60; ++j) {
                const float x = -0.6f + spacing * float(i), z = -0.6f + spacing * float(j);
                cache.insert({.p = {x + 1.5f, 0, z}, .n = up, .E = {10, 10, 10}, .radius = 0.1f});
                cache.insert({.p = {x + 0.4f, table_height, z}, .n = up, .E = {10, 10, 10}, .radius = 0.1f});
                if (i < 2)
                    cache.insert({.p = {1, table_height - 0.01f * float(i), z},
                                  .n = {1, 0, 0},
                                  .E = {10, 10, 10},
                                  .radius = 0.1f});
            }
    }
    enum Surface { floor, top, side };
    static Surface surface(const IrradianceRecord& record) {
        return record.n.x > 0.5f ? side : record.p.y > table_height / 2 ? top : floor;
    }

    static SceneDesc make_desc() {
        SceneDesc desc = testing::make_empty_scene({0, 2, -5}, {0, 0, 0});
        const int white = testing::add_material(desc, {});
        testing::add_object(desc, make_quad({-4, 0, -4}, {0, 0, 8}, {8, 0, 0}), white);
        testing::add_object(desc, make_box({0, table_height - 0.025f, 0}, {2, 0.05f, 2}), white);
        return desc;
    }
};

// The points: at least the spacing apart on a surface, about a tenth of records 2 cm apart at
// the default spacing (6.25 cm), each taking its own correction; every other
// record takes points on its own surface within twice the spacing (the table's top none on its
// side), weights summing to 1, the nearest among them within the spacing.
TEST(RecordCorrection, PointsAreSpacedAndEachRecordTakesThoseOnItsSurface) {
    const FloorAndTable room;
    const PreparedFrame prepared(room.scene, 0);
    const CorrectionSettings settings;
    const float spacing = settings.point_spacing * settings.radius;
    const CorrectionPoints points;
    points.make(prepared.context(), room.cache, settings);
    const std::vector<IrradianceRecord>& records = room.cache.records();
    EXPECT_GT(points.size(), records.size() / 20);
    EXPECT_LT(points.size(), records.size() / 5);
    std::vector<int> point_of(records.size(), -1);
    for (size_t j = 0; j < points.size(); ++j) point_of[points.record(j)] = int(j);
    for (size_t j = 1; j < points.size(); ++j) ASSERT_LT(points.record(j - 1), points.record(j));
    for (size_t a = 0; a < points.size(); ++a)
        for (size_t b = a + 1; b < points.size(); ++b) {
            const IrradianceRecord &pa = records[points.record(a)], &pb = records[points.record(b)];
            if (FloorAndTable::surface(pa) == FloorAndTable::surface(pb)) {
                ASSERT_GT(length(pa.p - pb.p), spacing);
            }
        }
    for (size_t i = 0; i < records.size(); ++i) {
        const std::span<const CorrectionPoints::Taken> taken = points.taken(i);
        ASSERT_FALSE(taken.empty());
        if (point_of[i] >= 0) {
            ASSERT_EQ(taken.size(), 1u);
            EXPECT_EQ(taken[0].point, uint32_t(point_of[i]));
            EXPECT_EQ(taken[0].weight, 1.0f);
            continue;
        }
        float sum = 0, nearest = infinity;
        for (const CorrectionPoints::Taken& t : taken) {
            const IrradianceRecord& point = records[points.record(t.point)];
            EXPECT_EQ(FloorAndTable::surface(point), FloorAndTable::surface(records[i]));
            const float distance = length(point.p - records[i].p);
            EXPECT_LT(distance, 2 * spacing);
            EXPECT_GT(t.weight, 0);
            sum += t.weight, nearest = std::min(nearest, distance);
        }
        EXPECT_NEAR(sum, 1, 1e-5);
        EXPECT_LE(nearest, spacing);
    }
}

// An even change on the floor: every floor record taken from the points reads it within 3%, and
// in all no farther from it than the records' own estimates (spacing 0), the points bit for bit
// those estimates; the table, which no photon reached, keeps its records bit for bit and unflagged.
TEST(RecordCorrection, RecordsTakeAnEvenChangeFromThePoints) {
    const FloorAndTable room;
    const PreparedFrame prepared(room.scene, 0);
    const PhotonMap map(room.photons, long(room.photons.size()));
    const CorrectionSettings settings, at_every_record{.point_spacing = 0};
    const CorrectionPoints points, every_record;
    points.make(prepared.context(), room.cache, settings);
    every_record.make(prepared.context(), room.cache, at_every_record);
    ASSERT_EQ(every_record.size(), room.cache.records().size());
    std::vector<uint8_t> changed;
    const IrradianceCache corrected = correct_static_cache(room.cache, map, settings, &points, &changed);
    const IrradianceCache estimated = correct_static_cache(room.cache, map, at_every_record, &every_record);
    const std::vector<IrradianceRecord>& records = corrected.records();
    for (size_t j = 0; j < points.size(); ++j) {
        const size_t i = points.record(j);
        EXPECT_EQ(std::memcmp(&records[i].E, &estimated.records()[i].E, sizeof(Rgb)), 0) << i;
    }
    double taken_error2 = 0, estimated_error2 = 0;
    for (size_t i = 0; i < records.size(); ++i) {
        if (FloorAndTable::surface(records[i]) != FloorAndTable::floor) {
            EXPECT_EQ(std::memcmp(&records[i].E, &room.cache.records()[i].E, sizeof(Rgb)), 0) << i;
            EXPECT_EQ(changed[i], 0);
            continue;
        }
        const double taken = luminance(records[i].E) - 10, own = luminance(estimated.records()[i].E) - 10;
        EXPECT_NEAR(taken, room.change, 0.03 * std::abs(room.change)) << i;
        EXPECT_EQ(changed[i], 1);
        taken_error2 += (taken - room.change) * (taken - room.change);
        estimated_error2 += (own - room.change) * (own - room.change);
    }
    EXPECT_LE(taken_error2, estimated_error2);  // no farther from the change than each record's own estimate
}

// With a spacing of 0 every record is a point: each is corrected by its own estimate, bit for
// bit correction_at there (the estimator before points).
TEST(RecordCorrection, WithoutSpacingEveryRecordTakesItsOwnEstimate) {
    const FloorAndTable room;
    const PreparedFrame prepared(room.scene, 0);
    const PhotonMap map(room.photons, long(room.photons.size()));
    const CorrectionSettings settings{.point_spacing = 0};
    const CorrectionPoints points;
    points.make(prepared.context(), room.cache, settings);
    const IrradianceCache corrected = correct_static_cache(room.cache, map, settings, &points);
    const CorrectionPhotons photons(map, settings);
    ASSERT_EQ(points.size(), room.cache.records().size());
    for (size_t i = 0; i < points.size(); i += 7) {
        const IrradianceRecord& r = room.cache.records()[i];
        const Rgb delta = correction_at(photons, r.p, r.n, settings, points.probes(i));
        const Rgb E = {std::max(0.0f, r.E.r + delta.r), std::max(0.0f, r.E.g + delta.g),
                       std::max(0.0f, r.E.b + delta.b)};
        EXPECT_EQ(std::memcmp(&corrected.records()[i].E, &E, sizeof(Rgb)), 0) << i;
    }
}

// Without dynamic photons the records are the static ones bit for bit, and none is flagged.
TEST(RecordCorrection, NoDynamicPhotonsLeaveTheRecordsAsTheyAre) {
    IrradianceCache cache;
    cache.insert({.p = {0, 0, 0}, .n = up, .E = {0.5f, -0.0f, 0.25f}, .radius = 0.3f});
    cache.insert({.p = {1, 0, 0}, .n = up, .E = {0.1f, 0.2f, 0.3f}, .radius = 0.3f});
    std::vector<uint8_t> changed;
    const IrradianceCache corrected_cache =
        correct_static_cache(cache, PhotonMap{}, CorrectionSettings{}, nullptr, &changed);
    ASSERT_EQ(corrected_cache.records().size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(std::memcmp(&corrected_cache.records()[i].E, &cache.records()[i].E, sizeof(Rgb)), 0);
        EXPECT_EQ(changed[i], 0);
    }
}

}  // namespace
}  // namespace steadylight
