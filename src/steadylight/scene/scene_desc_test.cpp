#include "steadylight/scene/scene_desc.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "steadylight/base/error.h"
#include "steadylight/scene/scene.h"
#include "steadylight/scene/shapes.h"
#include "support/input_error.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

const std::string scenes_dir = std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/";
// A ceiling lamp off for frames 0-9 and on for 10-19; a spot lamp whose intensity doubles then.
const std::string light_switch_scene = std::string(STEADYLIGHT_SOURCE_DIR) + "/tests/scenes/light_switch.json";

/// A scratch folder per test, removed afterwards.
class SceneFiles : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir = fs::temp_directory_path() /
                ("steadylight_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::create_directories(m_dir);
    }
    void TearDown() override { fs::remove_all(m_dir); }

    std::string write(const std::string& name, const std::string& text) const {
        const std::string path = (m_dir / name).string();
        std::ofstream(path) << text;
        return path;
    }

    /// Writes a scene whose objects are `objects` (a JSON array body) and returns its path.
    std::string write_scene(const std::string& objects, const std::string& extra = "") const {
        return write("scene.json", R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
            "materials": {"white": {"type": "lambert", "reflectance": 0.5}},
            "objects": [)" + objects + "]" +
                                       extra + "}");
    }

    /// Expects loading `path` to fail with a message containing every one of `parts`.
    static void expect_error(const std::string& path, const std::vector<std::string>& parts) {
        try {
            load_scene_desc(path);
            ADD_FAILURE() << "no error for " << path;
        } catch (const InputError& e) {
            for (const std::string& part : parts)
                EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        }
    }

    fs::path m_dir;
};

const std::string floor_quad =
    R"({"name": "floor", "shape": {"type": "quad", "corner": [0,0,0], "edge_u": [0,0,1], "edge_v": [1,0,0]}, "material": "white"})";

TEST(SceneDesc, BallMatchesItsSpec) {
    const Scene scene(load_scene_desc(scenes_dir + "ball.json"));
    EXPECT_EQ(scene.frame_count(), 60);
    EXPECT_EQ(scene.desc().camera.width, 320);
    ASSERT_EQ(scene.dynamic_objects().size(), 1u);
    const int ball = scene.dynamic_objects()[0];
    EXPECT_EQ(scene.object(ball).name, "ball");
    // centre(t) = (4.5 - 3.5 t, 0.5 + 1.5 |sin(2 pi t)|, 1.2), t = f / 59.
    for (const int f : {0, 15, 44, 59}) {
        const float t = float(f) / 59;
        const Vec3 c = scene.evaluate(f).world_from_object[size_t(ball)].point({});
        EXPECT_NEAR(c.x, 4.5f - 3.5f * t, 1e-5f);
        EXPECT_NEAR(c.y, 0.5f + 1.5f * std::abs(std::sin(2 * pi * t)), 1e-5f);
        EXPECT_NEAR(c.z, 1.2f, 1e-6f);
    }
}

TEST(SceneDesc, FpsSourceSaysWhereTheRateCameFrom) {
    EXPECT_EQ(describe_fps_source(SceneDesc{}), "default");
    const SceneDesc ball = load_scene_desc(scenes_dir + "ball.json");
    EXPECT_EQ(ball.fps_source, FpsSource::scene_file);
    EXPECT_EQ(describe_fps_source(ball), "from the scene file");
}

TEST(SceneDesc, CameraRightIsWorldMinusXInBall) {
    const Scene scene(load_scene_desc(scenes_dir + "ball.json"));
    const Camera camera = scene.evaluate(0).camera;
    const Ray left = camera.generate_ray(0, 120), right = camera.generate_ray(320, 120);
    EXPECT_GT(left.d.x, 0);   // the green wall (x = 5.5) is on the left
    EXPECT_LT(right.d.x, 0);  // the red wall (x = 0) on the right
}

TEST(SceneDesc, TableHasTwoDynamicObjectsAndTwoLights) {
    const Scene scene(load_scene_desc(scenes_dir + "table.json"));
    EXPECT_EQ(scene.dynamic_objects().size(), 2u);
    int lights = 0;
    for (const ObjectDesc& object : scene.objects()) lights += object.is_emitter();
    EXPECT_EQ(lights, 2);
}

TEST(SceneDesc, CornellIsStatic) {
    const Scene scene(load_scene_desc(scenes_dir + "cornell.json"));
    EXPECT_TRUE(scene.dynamic_objects().empty());
    EXPECT_EQ(scene.frame_count(), 1);
}

TEST(SceneDesc, SwitchedLightsHaveTheFramesEmissionAndIntensity) {
    const Scene scene(load_scene_desc(light_switch_scene));
    const ObjectDesc& lamp = scene.object(1);
    ASSERT_TRUE(lamp.emission_track.has_value());
    EXPECT_TRUE(lamp.is_emitter());
    EXPECT_TRUE(lamp.is_emission_animated());
    EXPECT_TRUE(scene.desc().point_lights[0].is_intensity_animated());
    EXPECT_EQ(scene.evaluate(0).emission[1], Rgb{});
    EXPECT_EQ(scene.evaluate(9).emission[1], Rgb{});
    EXPECT_EQ(scene.evaluate(10).emission[1], (Rgb{17, 12, 4}));
    EXPECT_EQ(scene.evaluate(19).emission[1], (Rgb{17, 12, 4}));
    EXPECT_EQ(scene.evaluate(10).emission[0], Rgb{});  // the room is no light
    EXPECT_EQ(scene.evaluate(9).point_lights[0].intensity, (Rgb{3, 3, 3}));
    EXPECT_EQ(scene.evaluate(10).point_lights[0].intensity, (Rgb{6, 6, 6}));
}

TEST(SceneDesc, LightSwitchedOnStartsASegmentAndStaysStatic) {
    const Scene scene(load_scene_desc(light_switch_scene));
    ASSERT_EQ(scene.segments().size(), 2u);
    EXPECT_EQ(scene.segments()[0].first, 0);
    EXPECT_EQ(scene.segments()[0].last, 9);
    EXPECT_EQ(scene.segments()[1].first, 10);
    EXPECT_EQ(scene.segments()[1].last, 19);
    // A light with a new value per segment does not move: its geometry is static.
    EXPECT_TRUE(scene.dynamic_objects().empty());
}

TEST(SceneDesc, LightTrackBuiltInCodeIsValidatedToo) {
    SceneDesc desc = load_scene_desc(light_switch_scene);
    desc.objects[1].emission_track->values[1] = {1, std::nanf(""), 1};
    EXPECT_NE(testing::input_error_of([&] { const Scene scene(desc); }).find("ceiling lamp"), std::string::npos);
    desc = load_scene_desc(light_switch_scene);
    desc.point_lights[0].intensity_track->values[0] = {-1, 0, 0};
    EXPECT_NE(testing::input_error_of([&] { const Scene scene(desc); }).find("desk lamp"), std::string::npos);
    desc = load_scene_desc(light_switch_scene);
    desc.point_lights[0].intensity_track->times = {1, 0};
    EXPECT_NE(testing::input_error_of([&] { const Scene scene(desc); }).find("increasing"), std::string::npos);
}

// A lamp's translation track replaces its position and its rotation track turns its direction;
// a sun's rotation track turns its direction.
TEST_F(SceneFiles, LightTracksMoveLampsAndTurnSuns) {
    const float s = std::sin(pi / 4), c = std::cos(pi / 4);
    const std::string lights = fmt::format(R"(, "frames": {{"count": 6, "fps": 2}},
        "lights": [{{"type": "spot", "name": "torch", "position": [9, 9, 9], "direction": [0, -1, 0], "intensity": 1,
                    "animation": {{"translation": {{"times": [0, 1], "values": [[0, 1, 0], [2, 1, 0]]}},
                                  "rotation": {{"times": [0, 1], "values": [[0, 0, 0, 1], [0, 0, {}, {}]]}}}}}},
                   {{"type": "point", "name": "bulb", "position": [0, 2, 0], "intensity": 1}},
                   {{"type": "sun", "name": "noon", "direction": [0, -1, 0], "irradiance": 1,
                    "animation": {{"rotation": {{"interpolation": "step", "times": [0, 2],
                                                 "values": [[0, 0, 0, 1], [0, 0, {}, {}]]}}}}}}])",
                                           s, c, s, c);
    const Scene scene(load_scene_desc(write_scene(floor_quad, lights)));
    const PointLightDesc& torch = scene.desc().point_lights[0];
    EXPECT_TRUE(torch.is_moving());
    EXPECT_FALSE(scene.desc().point_lights[1].is_moving());
    EXPECT_TRUE(scene.desc().suns[0].is_moving());
    EXPECT_EQ(scene.evaluate(0).point_lights[0].position, (Vec3{0, 1, 0}));  // the track, not "position"
    const PointLightPose at_end = scene.evaluate(2).point_lights[0];
    EXPECT_NEAR(at_end.position.x, 2, 1e-6f);
    EXPECT_NEAR(at_end.direction.x, 1, 1e-6f);  // (0, -1, 0) turned a quarter about z
    EXPECT_NEAR(at_end.direction.y, 0, 1e-6f);
    EXPECT_EQ(scene.evaluate(5).point_lights[1].position, (Vec3{0, 2, 0}));
    EXPECT_NEAR(scene.evaluate(3).sun_directions[0].y, -1, 1e-6f);
    EXPECT_NEAR(scene.evaluate(4).sun_directions[0].x, 1, 1e-6f);  // the step key at 2 s: frame 4
    // Lamps and suns that move are lit apart from the static pass: they keep the one segment.
    EXPECT_EQ(scene.segments().size(), 1u);
}

TEST_F(SceneFiles, BadLightTracksNameTheFileAndThePointer) {
    const auto lamp = [&](const std::string& animation) {
        return write_scene(floor_quad, R"(, "lights": [{"type": "point", "position": [0, 1, 0], "intensity": 1,
                                                        "animation": )" +
                                           animation + "}]");
    };
    expect_error(lamp(R"({"rotation": {"times": [0, 1], "values": [[0, 0, 0, 1], [0, 0, 0, 0]]}})"),
                 {"scene.json:/lights/0/animation/rotation/values/1", "quaternion must not be zero"});
    expect_error(lamp(R"({"translation": {"times": [1, 0], "values": [[0, 1, 0], [1, 1, 0]]}})"),
                 {"scene.json:/lights/0/animation/translation/times", "strictly increasing"});
    expect_error(lamp(R"({"translation": {"times": [0, 1], "values": [[0, 1, 0], [3.5e38, 1, 0]]}})"),
                 {"scene.json:/lights/0/animation/translation/values", "not finite"});
    expect_error(lamp(R"({"translation": {"times": [0, 1], "values": [[0, 1, 0], [NaN, 1, 0]]}})"), {"scene.json"});
    expect_error(lamp(R"({"scale": {"times": [0], "values": [[2, 2, 2]]}})"),
                 {"scene.json:/lights/0/animation/scale", "no size"});
    expect_error(write_scene(floor_quad, R"(, "lights": [{"type": "sun", "direction": [0, -1, 0],
                     "animation": {"translation": {"times": [0], "values": [[0, 1, 0]]}}}])"),
                 {"scene.json:/lights/0/animation/translation", "a sun has no position"});
}

TEST(SceneDesc, BoxNormalsPointOutward) {
    const TriangleMesh box = make_box({0, 0, 0}, {1, 2, 3});
    for (size_t i = 0; i < box.indices.size(); i += 3) {
        const Vec3 a = box.positions[size_t(box.indices[i])], b = box.positions[size_t(box.indices[i + 1])],
                   c = box.positions[size_t(box.indices[i + 2])];
        EXPECT_GT(dot(cross(b - a, c - a), (a + b + c) / 3), 0);
    }
}

TEST_F(SceneFiles, MarkedObjectIsDynamicWithoutAnimation) {
    const std::string marked = floor_quad.substr(0, floor_quad.size() - 1) + R"(, "dynamic": true})";
    const SceneDesc desc = load_scene_desc(write_scene(marked));
    EXPECT_TRUE(desc.objects[0].is_dynamic());
}

TEST_F(SceneFiles, LoadsObjMeshRelativeToTheScene) {
    write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const SceneDesc desc =
        load_scene_desc(write_scene(R"({"shape": {"type": "mesh", "file": "tri.obj"}, "material": "white"})"));
    EXPECT_EQ(std::get<TriangleMesh>(desc.objects[0].geometry).indices.size(), 3u);
}

// Paths may lead anywhere by default; with --confine-inputs only inside the scene file's folder,
// symbolic links resolved, so a link inside that points outside is refused too.
TEST_F(SceneFiles, ConfinedInputsMustLieInsideTheSceneFilesFolder) {
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    write("outside.obj", triangle);
    fs::create_directories(m_dir / "scene");
    write("scene/inside.obj", triangle);
    fs::create_symlink(m_dir / "outside.obj", m_dir / "scene" / "link.obj");
    const auto scene_with_mesh = [&](const std::string& file) {
        return write("scene/scene.json", R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
            "materials": {"white": {"type": "lambert", "reflectance": 0.5}},
            "objects": [{"shape": {"type": "mesh", "file": ")" +
                                             file + R"("}, "material": "white"}]})");
    };
    for (const char* file : {"../outside.obj", "link.obj", "inside.obj"})
        EXPECT_NO_THROW(load_scene_desc(scene_with_mesh(file))) << file;
    EXPECT_NO_THROW(load_scene_desc(scene_with_mesh("inside.obj"), true));
    for (const char* file : {"../outside.obj", "link.obj"}) {
        const std::string message = testing::input_error_of([&] { load_scene_desc(scene_with_mesh(file), true); });
        EXPECT_NE(message.find("/objects/0/shape/file"), std::string::npos) << message;
        EXPECT_NE(message.find("lies outside the scene file's folder"), std::string::npos) << message;
    }
}

// Lines end where tinyobjloader ends them, at a lone carriage return too: the statements after
// one are read as a mesh's or left out, never handed over unchecked (a fuzzing finding).
TEST_F(SceneFiles, ObjLinesEndingInALoneCarriageReturnAreFiltered) {
    write("old_mac.obj", "v 0 0 0\rv 1 0 0\rv 0 1 0\rvw 1 0 1e999\rf 1 2 3\r");
    const SceneDesc desc =
        load_scene_desc(write_scene(R"({"shape": {"type": "mesh", "file": "old_mac.obj"}, "material": "white"})"));
    const TriangleMesh& mesh = std::get<TriangleMesh>(desc.objects[0].geometry);
    EXPECT_EQ(mesh.positions.size(), 3u);
    EXPECT_EQ(mesh.indices.size(), 3u);
}

// Glass is smooth unless it says otherwise; rough and absorbing glass take their keys.
TEST_F(SceneFiles, GlassIsSmoothByDefaultAndTakesRoughnessAndAbsorption) {
    const SceneDesc desc =
        load_scene_desc(write("glass.json", R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
        "materials": {"clear": {"type": "dielectric"},
                      "amber": {"type": "dielectric", "roughness": 0.2, "attenuation_color": [0.9, 0.5, 0.2],
                                "attenuation_distance": 0.25}},
        "objects": [{"shape": {"type": "sphere", "radius": 1}, "material": "clear"},
                    {"shape": {"type": "sphere", "radius": 1}, "material": "amber"}]})"));
    const MaterialDesc& clear = desc.materials[size_t(desc.objects[0].material)];
    const MaterialDesc& amber = desc.materials[size_t(desc.objects[1].material)];
    EXPECT_EQ(clear.roughness, 0);
    EXPECT_TRUE(is_black(clear.absorption()));
    EXPECT_FLOAT_EQ(amber.roughness, 0.2f);
    EXPECT_NEAR(amber.absorption().b, -std::log(0.2f) / 0.25f, 1e-4f);
    expect_error(write("bad.json", R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
        "materials": {"glass": {"type": "dielectric", "attenuation_distance": 0}}, "objects": []})"),
                 {"bad.json:/materials/glass/attenuation_distance", "positive"});
}

TEST_F(SceneFiles, MissingFileIsAnError) { expect_error((m_dir / "nope.json").string(), {"nope.json", "cannot open"}); }

// 2^32 + 2 frames would wrap to 2 in an int: refused, never read as another number.
TEST_F(SceneFiles, IntegerBeyondIntIsAnError) {
    for (const char* count : {"4294967298", "18446744073709551615", "-4294967298"})
        expect_error(
            write("big.json",
                  std::string(R"({"frames": {"count": )") + count +
                      R"(}, "camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]}, "materials": {}, "objects": []})"),
            {"big.json:/frames/count", "expected an integer within"});
}

// A name longer than the file system allows is not found, like any other (it made the standard
// library throw past the loader: a fuzzing finding).
TEST_F(SceneFiles, FileNameTooLongIsNotFound) {
    const std::string name(5000, 'n');
    expect_error(write("gltf.json", R"({"gltf": ")" + name + R"(.glb"})"), {"file not found"});
    expect_error(write_scene(R"({"shape": {"type": "mesh", "file": ")" + name + R"(.obj"}, "material": "white"})"),
                 {"not found"});
}

// The name starts every output file's name: one that could lead a path out of the output folder,
// or make a name the file system refuses, is an error naming /name.
TEST_F(SceneFiles, SceneNameThatCannotNameAFileIsRefused) {
    const std::pair<std::string, std::string> cases[] = {
        {R"("../escaped")", "holds a path separator"},
        {R"("x<script>alert(1)</script>")", "holds a path separator"},
        {R"("a\\b")", "holds a path separator"},
        {R"("..")", "is a folder's name"},
        {R"(".")", "is a folder's name"},
        {R"("")", "is empty"},
        {R"("bell\u0007")", "holds a control character"},
        {R"("nul\u0000byte")", "holds a control character"},
        {'"' + std::string(max_scene_name_bytes + 1, 'n') + '"', "129 bytes long, more than 128"},
    };
    for (const auto& [name, why] : cases)
        expect_error(write_scene(floor_quad, R"(, "name": )" + name), {"scene.json:/name", why});
    // The longest name allowed, and names with spaces, dots and markup but no separator, are fine.
    EXPECT_EQ(load_scene_desc(write_scene(floor_quad, R"(, "name": ")" + std::string(max_scene_name_bytes, 'n') + '"'))
                  .name.size(),
              max_scene_name_bytes);
    EXPECT_EQ(load_scene_desc(write_scene(floor_quad, R"(, "name": "a <b> & c.d")")).name, "a <b> & c.d");
}

// Only regular files are read: a device never ends (reading /dev/zero as a mesh ran until
// killed) and a FIFO blocks its reader; both are refused at once, naming the file.
TEST_F(SceneFiles, MeshThatIsADeviceOrAFifoIsRefusedNotRead) {
    expect_error(write_scene(R"({"shape": {"type": "mesh", "file": "/dev/zero"}, "material": "white"})"),
                 {"/dev/zero", "not a regular file: it is a device"});
    ASSERT_EQ(::mkfifo((m_dir / "pipe.obj").c_str(), 0600), 0);
    expect_error(write_scene(R"({"shape": {"type": "mesh", "file": "pipe.obj"}, "material": "white"})"),
                 {"pipe.obj", "not a regular file: it is a FIFO"});
    ASSERT_EQ(::mkfifo((m_dir / "pipe.json").c_str(), 0600), 0);
    expect_error((m_dir / "pipe.json").string(), {"pipe.json", "it is a FIFO"});
    expect_error(m_dir.string(), {"it is a folder"});
}

TEST_F(SceneFiles, SyntaxErrorNamesTheFile) {
    expect_error(write("bad.json", "{\"camera\": "), {"bad.json", "invalid JSON"});
}

TEST_F(SceneFiles, NanIsAnError) {
    expect_error(write_scene(R"({"shape": {"type": "sphere", "radius": NaN}, "material": "white"})"),
                 {"scene.json", "invalid JSON"});
}

TEST_F(SceneFiles, InfiniteNumberIsAnError) {
    expect_error(write_scene(R"({"shape": {"type": "sphere", "radius": 1e999}, "material": "white"})"),
                 {"scene.json", "overflow"});
}

TEST_F(SceneFiles, MissingFieldNamesItsPointer) {
    expect_error(write_scene(R"({"shape": {"type": "sphere"}, "material": "white"})"),
                 {"scene.json:/objects/0/shape/radius", "missing required field"});
}

TEST_F(SceneFiles, WrongTypeNamesItsPointer) {
    expect_error(write_scene(R"({"shape": {"type": "sphere", "radius": "big"}, "material": "white"})"),
                 {"/objects/0/shape/radius", "expected a number"});
}

TEST_F(SceneFiles, MissingMeshFileIsAnError) {
    expect_error(write_scene(R"({"shape": {"type": "mesh", "file": "gone.obj"}, "material": "white"})"),
                 {"/objects/0/shape/file", "gone.obj", "not found"});
}

TEST_F(SceneFiles, BrokenObjIsAnError) {
    write("broken.obj", "this is not an OBJ file\n");
    expect_error(write_scene(R"({"shape": {"type": "mesh", "file": "broken.obj"}, "material": "white"})"),
                 {"broken.obj"});
}

TEST_F(SceneFiles, ZeroAreaLightIsAnError) {
    expect_error(
        write_scene(
            R"({"name": "lamp", "shape": {"type": "quad", "corner": [0,1,0], "edge_u": [1,0,0], "edge_v": [2,0,0]}, "emission": 5})"),
        {"lamp", "zero area"});
}

TEST_F(SceneFiles, UnknownMaterialIsAnError) {
    expect_error(write_scene(R"({"shape": {"type": "sphere", "radius": 1}, "material": "glas"})"),
                 {"unknown material \"glas\""});
}

TEST_F(SceneFiles, NonIncreasingKeyTimesAreAnError) {
    const std::string animated = floor_quad.substr(0, floor_quad.size() - 1) +
                                 R"(, "animation": {"translation": {"times": [0, 0], "values": [[0,0,0],[1,0,0]]}}})";
    expect_error(write_scene(animated), {"/objects/0/animation/translation/times", "increasing"});
}

TEST_F(SceneFiles, ZeroScaleIsAnError) {
    const std::string flat = floor_quad.substr(0, floor_quad.size() - 1) + R"(, "transform": {"scale": [0, 1, 1]}})";
    expect_error(write_scene(flat), {"floor", "singular"});
}

TEST_F(SceneFiles, SegmentsSplitTheAnimationWhereTheFileSays) {
    const Scene scene(load_scene_desc(write_scene(floor_quad, R"(, "frames": {"count": 10}, "segments": [0, 4, 7])")));
    ASSERT_EQ(scene.segments().size(), 3u);
    EXPECT_EQ(scene.segments()[1].first, 4);
    EXPECT_EQ(scene.segments()[1].last, 6);
    EXPECT_EQ(scene.segment_of(9).first, 7);
}

TEST_F(SceneFiles, MoreFramesThanAnAnimationMayHaveAreAnError) {
    expect_error(write_scene(floor_quad, R"(, "frames": {"count": 1000001})"), {"1000001 frames", "at most 1000000"});
}

TEST_F(SceneFiles, SegmentStartsMustIncreaseWithinTheAnimation) {
    expect_error(write_scene(floor_quad, R"(, "frames": {"count": 10}, "segments": [5, 3])"),
                 {"/segments", "increase"});
    expect_error(write_scene(floor_quad, R"(, "frames": {"count": 10}, "segments": [12])"), {"/segments", "within"});
}

// An emitter that moves is lit apart and keeps the segment; one that grows changes its power every
// frame, and every frame is its own segment.
TEST_F(SceneFiles, EmitterThatGrowsMakesEveryFrameItsOwnSegment) {
    const std::string moves = R"({"shape": {"type": "sphere", "radius": 0.1}, "emission": 5,
        "animation": {"translation": {"times": [0, 1], "values": [[0,1,0],[1,1,0]]}}})";
    const std::string frames = R"(, "frames": {"count": 4, "fps": 4})";
    const Scene moving(load_scene_desc(write_scene(moves, frames)));
    EXPECT_TRUE(moving.object(0).is_moving_light());
    EXPECT_EQ(moving.segments().size(), 1u);
    const std::string grows = R"({"shape": {"type": "sphere", "radius": 0.1}, "emission": 5,
        "animation": {"scale": {"times": [0, 1], "values": [[1,1,1],[2,2,2]]}}})";
    const Scene growing(load_scene_desc(write_scene(grows, frames)));
    EXPECT_FALSE(growing.object(0).is_moving_light());
    EXPECT_EQ(growing.segments().size(), 4u);
}

std::string sphere_light_with_track(const std::string& track) {
    return R"({"name": "bulb", "shape": {"type": "sphere", "center": [0, 1, 0], "radius": 0.1}, "animation": {"emission": )" +
           track + "}}";
}

TEST_F(SceneFiles, LinearEmissionTrackMakesEveryChangingFrameItsOwnSegment) {
    // Frames at t = 0, 0.25, 0.5, 0.75: the ramp ends at frame 2, then nothing changes.
    const Scene scene(load_scene_desc(write_scene(
        sphere_light_with_track(R"({"interpolation": "linear", "times": [0, 0.5], "values": [[0, 0, 0], [2, 4, 6]]})"),
        R"(, "frames": {"count": 4, "fps": 4})")));
    EXPECT_EQ(scene.evaluate(1).emission[0], (Rgb{1, 2, 3}));
    EXPECT_EQ(scene.evaluate(3).emission[0], (Rgb{2, 4, 6}));
    ASSERT_EQ(scene.segments().size(), 3u);
    EXPECT_EQ(scene.segments()[1].first, 1);
    EXPECT_EQ(scene.segments()[1].last, 1);
    EXPECT_EQ(scene.segments()[2].first, 2);
    EXPECT_EQ(scene.segments()[2].last, 3);
    EXPECT_FALSE(scene.object(0).is_dynamic());
}

TEST_F(SceneFiles, ConstantEmissionTrackNeitherAnimatesNorSplits) {
    const Scene scene(
        load_scene_desc(write_scene(sphere_light_with_track(R"({"times": [0, 1], "values": [5, [5, 5, 5]]})"),
                                    R"(, "frames": {"count": 20, "fps": 10})")));
    EXPECT_FALSE(scene.object(0).is_emission_animated());
    EXPECT_EQ(scene.segments().size(), 1u);
}

TEST_F(SceneFiles, LampIntensityTrackStepsAndSplitsBesideTheExplicitSegments) {
    const std::string lamp = R"(, "frames": {"count": 10, "fps": 10}, "segments": [3],
        "lights": [{"type": "point", "position": [0, 1, 0],
                    "animation": {"intensity": {"interpolation": "step", "times": [0.5], "values": [[1, 2, 3]]}}},
                   {"type": "point", "position": [0, 1, 0], "intensity": 1,
                    "animation": {"intensity": {"interpolation": "step", "times": [0, 0.7], "values": [1, 0]}}}])";
    const Scene scene(load_scene_desc(write_scene(floor_quad, lamp)));
    EXPECT_EQ(scene.evaluate(0).point_lights[0].intensity, (Rgb{1, 2, 3}));  // held before the first key
    EXPECT_EQ(scene.evaluate(6).point_lights[1].intensity, (Rgb{1, 1, 1}));
    EXPECT_EQ(scene.evaluate(7).point_lights[1].intensity, Rgb{});  // switched off
    ASSERT_EQ(scene.segments().size(), 3u);
    EXPECT_EQ(scene.segments()[1].first, 3);
    EXPECT_EQ(scene.segments()[1].last, 6);
    EXPECT_EQ(scene.segments()[2].first, 7);
}

TEST_F(SceneFiles, LampSwitchedOffStartsASegment) {
    const std::string lamp = R"(, "frames": {"count": 10, "fps": 10},
        "lights": [{"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0],
                    "animation": {"intensity": {"interpolation": "step", "times": [0, 0.7], "values": [1, 0]}}}])";
    const Scene scene(load_scene_desc(write_scene(floor_quad, lamp)));
    ASSERT_EQ(scene.segments().size(), 2u);
    EXPECT_EQ(scene.segments()[1].first, 7);
}

TEST_F(SceneFiles, EmissionTrackErrorsNameTheirPointer) {
    expect_error(write_scene(sphere_light_with_track(R"({"times": [0, 1], "values": [1, -1]})")),
                 {"scene.json:/objects/0/animation/emission/values/1", "must not be negative"});
    expect_error(write_scene(sphere_light_with_track(R"({"times": [0, 1], "values": [1, [0, -2, 0]]})")),
                 {"scene.json:/objects/0/animation/emission/values/1", "must not be negative"});
    expect_error(write_scene(sphere_light_with_track(R"({"times": [1, 0], "values": [1, 2]})")),
                 {"scene.json:/objects/0/animation/emission/times", "increasing"});
    expect_error(write_scene(sphere_light_with_track(R"({"times": [0, 1], "values": [1]})")),
                 {"scene.json:/objects/0/animation/emission/values", "1 entries for 2 times"});
    expect_error(write_scene(sphere_light_with_track(R"({"times": [0], "values": [[1, 2]]})")),
                 {"scene.json:/objects/0/animation/emission/values/0", "3 numbers"});
    expect_error(write_scene(sphere_light_with_track(R"({"times": [0], "values": ["bright"]})")),
                 {"scene.json:/objects/0/animation/emission/values/0", "got \"bright\""});
    expect_error(write_scene(sphere_light_with_track(R"({"times": [0], "values": [1e999]})")),
                 {"scene.json", "overflow"});
    expect_error(write_scene(sphere_light_with_track(R"({"interpolation": "smooth", "times": [0], "values": [1]})")),
                 {"scene.json:/objects/0/animation/emission/interpolation", "unknown interpolation"});
}

TEST_F(SceneFiles, IntensityTrackErrorsNameTheirPointer) {
    const auto lamp_with_track = [](const std::string& track) {
        return R"(, "lights": [{"type": "point", "position": [0, 1, 0], "animation": {"intensity": )" + track + "}}]";
    };
    expect_error(write_scene(floor_quad, lamp_with_track(R"({"times": [0, 1], "values": [-3, 1]})")),
                 {"scene.json:/lights/0/animation/intensity/values/0", "must not be negative"});
    expect_error(write_scene(floor_quad, lamp_with_track(R"({"times": [0, 0], "values": [1, 2]})")),
                 {"scene.json:/lights/0/animation/intensity/times", "increasing"});
    expect_error(write_scene(floor_quad, lamp_with_track(R"({"times": [0, 1, 2], "values": [1, 2]})")),
                 {"scene.json:/lights/0/animation/intensity/values", "2 entries for 3 times"});
    expect_error(write_scene(floor_quad, lamp_with_track(R"({"times": [], "values": []})")),
                 {"scene.json:/lights/0/animation/intensity/times", "at least one key"});
    expect_error(write_scene(floor_quad, lamp_with_track(R"([1, 2])")),
                 {"scene.json:/lights/0/animation/intensity", "expected an object"});
}

TEST_F(SceneFiles, LightOffAtSomeFramesIsFineButZeroAreaIsNot) {
    const std::string off_then_on =
        R"({"name": "lamp", "shape": {"type": "quad", "corner": [0,1,0], "edge_u": [1,0,0], "edge_v": [0,0,1]},
        "animation": {"emission": {"interpolation": "step", "times": [0, 1], "values": [0, 5]}}})";
    const SceneDesc desc = load_scene_desc(write_scene(off_then_on, R"(, "frames": {"count": 2, "fps": 1})"));
    EXPECT_TRUE(desc.objects[0].is_emitter());  // a light, off at frame 0; it reflects nothing
    const std::string flat =
        R"({"name": "lamp", "shape": {"type": "quad", "corner": [0,1,0], "edge_u": [1,0,0], "edge_v": [2,0,0]},
        "animation": {"emission": {"interpolation": "step", "times": [0, 1], "values": [0, 5]}}})";
    expect_error(write_scene(flat), {"lamp", "zero area"});
}

/// An uncompressed Radiance HDR image of `width` x `height` pixels, all of radiance about 1.
std::string flat_hdr(int width, int height) {
    std::string bytes =
        "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n";
    for (int i = 0; i < width * height; ++i) bytes += std::string("\x80\x80\x80\x81", 4);  // 0.5 x 2^1
    return bytes;
}

TEST_F(SceneFiles, SunsAndTheWorldAreReadWithTheirUnits) {
    const SceneDesc desc = load_scene_desc(write_scene(floor_quad, R"(, "lights": [
        {"type": "sun", "name": "noon", "direction": [0, -2, 0], "irradiance": [3, 2, 1], "angle_degrees": 1}],
        "world": {"color": [0.5, 1, 2], "strength": 2},
        "portals": [{"corner": [1, 0, 0], "edge_u": [0, 0, 2], "edge_v": [0, 1, 0]}])"));
    ASSERT_EQ(desc.suns.size(), 1u);
    EXPECT_EQ(desc.suns[0].name, "noon");
    EXPECT_EQ(desc.suns[0].direction, (Vec3{0, -1, 0}));
    EXPECT_EQ(desc.suns[0].irradiance, (Rgb{3, 2, 1}));
    EXPECT_EQ(desc.suns[0].angle_deg, 1);
    ASSERT_TRUE(desc.world);
    EXPECT_EQ(desc.world->radiance->radiance({0, 1, 0}), (Rgb{1, 2, 4}));
    ASSERT_EQ(desc.portals.size(), 1u);
    EXPECT_EQ(desc.portals[0].area(), 2);
    EXPECT_EQ(desc.portals[0].inward_normal(), (Vec3{-1, 0, 0}));
}

TEST_F(SceneFiles, WorldImageIsReadRelativeToTheSceneTimesItsStrength) {
    write("sky.hdr", flat_hdr(8, 4));
    const SceneDesc desc = load_scene_desc(
        write_scene(floor_quad, R"(, "world": {"image": "sky.hdr", "strength": 3, "rotation_degrees": 45})"));
    ASSERT_TRUE(desc.world);
    // The pixels read as the middles of their RGBE intervals: 128.5 / 128.
    EXPECT_FLOAT_EQ(desc.world->radiance->radiance(normalize(Vec3{1, 2, 3})).g, 3 * 128.5f / 128);
    EXPECT_NE(desc.world->description.find("sky.hdr (8 x 4), strength 3, rotation 45"), std::string::npos)
        << desc.world->description;
}

// The sky's sun disc becomes a sun light named "sky sun", where Blender's angles put it, its
// irradiance scaled by the world's strength; without the disc there is none.
TEST_F(SceneFiles, NishitaSkyBringsItsSunDiscAsASun) {
    const auto sky = [&](const std::string& params, float strength) {
        return load_scene_desc(write_scene(floor_quad, R"(, "world": {"strength": )" + std::to_string(strength) +
                                                           R"(, "sky": {"model": "nishita", )" + params + "}}"));
    };
    const SceneDesc one = sky(R"("sun_elevation": 30, "sun_rotation": 90)", 1);
    ASSERT_EQ(one.suns.size(), 1u);
    EXPECT_EQ(one.suns[0].name, "sky sun");
    const Vec3 travel = one.suns[0].direction, expected = -Vec3{std::cos(pi / 6), std::sin(pi / 6), 0};
    EXPECT_LT(length(travel - expected), 1e-5f) << travel.x << " " << travel.y << " " << travel.z;
    EXPECT_NEAR(one.suns[0].angle_deg, 0.545f, 1e-3f);
    const SceneDesc two = sky(R"("sun_elevation": 30, "sun_rotation": 90)", 2);
    EXPECT_NEAR(luminance(two.suns[0].irradiance), 2 * luminance(one.suns[0].irradiance),
                1e-5f * luminance(two.suns[0].irradiance));
    EXPECT_GT(luminance(one.suns[0].irradiance), 0);
    EXPECT_TRUE(sky(R"("sun_disc": false)", 1).suns.empty());
    EXPECT_GT(one.world->radiance->mean_luminance(), 0);
}

TEST_F(SceneFiles, BadSunsAndWorldsAreErrorsNamingTheValue) {
    write("sky.hdr", flat_hdr(8, 4));
    write("square.hdr", flat_hdr(8, 8));
    const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
        {R"("lights": [{"type": "sun", "direction": [0, 0, 0], "irradiance": 1}])", {"/lights/0/direction", "zero"}},
        {R"("lights": [{"type": "sun", "direction": [0, -1, 0], "irradiance": -1}])",
         {"/lights/0/irradiance", "negative"}},
        {R"("world": {"color": [1, 1, 1], "strength": -1})", {"/world/strength"}},
        {R"("world": {"color": [1, -1, 1]})", {"/world/color", "negative"}},
        {R"("world": {"color": [1, 1, 1], "image": "sky.hdr"})", {"/world", "one of"}},
        {R"("world": {"image": "nope.exr"})", {"nope.exr", "cannot open"}},
        {R"("world": {"image": "square.hdr"})", {"square.hdr", "twice"}},
        {R"("world": {"image": "sky.hdr", "rotation_degrees": 1e30})", {"/world/rotation_degrees"}},
        {R"("world": {"sky": {"model": "hosek"}})", {"/world/sky/model", "unknown sky model \"hosek\""}},
        {R"("world": {"sky": {"sun_elevation": 95}})", {"/world/sky/sun_elevation", "[-90, 90]"}},
        {R"("world": {"sky": {"air_density": -1}})", {"/world/sky/air_density", "negative"}},
        {R"("portals": [{"corner": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [2, 0, 0]}])", {"/portals/0", "area"}},
        {R"("portals": [{"corner": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [1, 1, 0]}])",
         {"/portals/0", "right angles"}},
    };
    for (const auto& [extra, parts] : cases) expect_error(write_scene(floor_quad, ", " + extra), parts);
}

TEST_F(SceneFiles, ConfinedInputsHoldForTheWorldImage) {
    write("outside.hdr", flat_hdr(8, 4));
    fs::create_directories(m_dir / "scene");
    const std::string scene = write("scene/scene.json", R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
        "world": {"image": "../outside.hdr"}})");
    EXPECT_NO_THROW(load_scene_desc(scene));
    const std::string message = testing::input_error_of([&] { load_scene_desc(scene, true); });
    EXPECT_NE(message.find("lies outside the scene file's folder"), std::string::npos) << message;
}

TEST_F(SceneFiles, MissingCameraIsAnError) {
    expect_error(write("nocam.json", R"({"objects": []})"), {"nocam.json:/camera", "missing"});
}

}  // namespace
}  // namespace steadylight
