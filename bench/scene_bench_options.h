// The options the scene benchmarks share: --scenes a,b (of scenes/), --frames N, --size WxH,
// and any other "--name N" as a number by name; and a scene of scenes/ opened at that size.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "steadylight/scene/scene.h"
#include "steadylight/shading/frame_context.h"
#include "steadylight/trace/ray_tracer.h"

struct SceneBenchOptions {
    std::vector<std::string> scenes{"ball", "table"};
    int frames = 60;
    int width = 320, height = 240;
    std::map<std::string, int> numbers;  // the other options, by name without the dashes

    int number(const std::string& name, int fallback) const {
        const auto found = numbers.find(name);
        return found == numbers.end() ? fallback : found->second;
    }
};

inline SceneBenchOptions parse_scene_bench_options(int argc, char** argv, int default_frames) {
    SceneBenchOptions o;
    o.frames = default_frames;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--frames"))
            o.frames = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--size"))
            std::sscanf(argv[i + 1], "%dx%d", &o.width, &o.height);
        else if (!std::strcmp(argv[i], "--scenes")) {
            o.scenes.clear();
            std::stringstream list(argv[i + 1]);
            for (std::string name; std::getline(list, name, ',');) o.scenes.push_back(name);
        } else if (!std::strncmp(argv[i], "--", 2)) {
            o.numbers[argv[i] + 2] = std::atoi(argv[i + 1]);
        }
    }
    return o;
}

/// scenes/<name>.json at the options' size, with its ray tracer (at frame 0) and materials. The
/// tracer refers to the scene: it stays where it is made.
struct BenchScene {
    steadylight::Scene scene;
    steadylight::RayTracer tracer;
    steadylight::Bsdfs bsdfs;

    BenchScene(const std::string& name, const SceneBenchOptions& options)
        : scene(sized(name, options)), tracer(scene, scene.evaluate(0)), bsdfs(steadylight::make_bsdfs(scene)) {}
    BenchScene(const BenchScene&) = delete;
    BenchScene& operator=(const BenchScene&) = delete;

private:
    static steadylight::Scene sized(const std::string& name, const SceneBenchOptions& options) {
        steadylight::Scene scene(
            steadylight::load_scene_desc(std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/" + name + ".json"));
        scene.set_resolution(options.width, options.height);
        return scene;
    }
};
