// Rays per second through RayTracer (the renderer's tracing interface) against raw Embree on the
// BALL scene at frame 0, for coherent camera rays and incoherent diffuse rays, closest hit and
// occlusion. "raw flat" is the plainest raw use: one Embree scene holding everything, one
// rtcIntersect1/rtcOccluded1 per ray. "raw same scenes" makes the calls RayTracer makes (static
// scene, then the instance scene) without its wrapping. Prints the ratios at the end; single
// thread; asserts nothing. Run: build/ray_tracer_bench [--benchmark_min_time=1]
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>

#include "steadylight/base/parallel.h"
#include "steadylight/base/rng.h"
#include "steadylight/base/sampling.h"
#include "steadylight/scene/scene.h"
#include "steadylight/shading/surface_point.h"
#include "steadylight/trace/ray_tracer.h"

using namespace steadylight;

namespace {

struct Fixture {
    Scene scene{load_scene_desc(std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/ball.json")};
    FrameState frame = scene.evaluate(0);
    RayTracer tracer{scene, frame};
    RTCScene flat = build_flat_embree_scene(scene, frame);
    std::vector<Ray> camera_rays;
    std::vector<Ray> diffuse_rays;

    Fixture() {
        // Camera rays in 8x8 tiles, as the renderer issues them.
        const Camera& camera = frame.camera;
        for (int ty = 0; ty < camera.height; ty += 8)
            for (int tx = 0; tx < camera.width; tx += 8)
                for (int y = ty; y < std::min(ty + 8, camera.height); ++y)
                    for (int x = tx; x < std::min(tx + 8, camera.width); ++x)
                        camera_rays.push_back(camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f));
        // One cosine-distributed bounce from every visible point.
        Pcg32 rng(1);
        for (const Ray& ray : camera_rays) {
            const std::optional<Hit> hit = tracer.intersect(ray);
            if (!hit) continue;
            const SurfacePoint sp = make_surface_point(scene, frame, ray, *hit);
            const OrthonormalBasis local = OrthonormalBasis::from_normal(dot(sp.ng, ray.d) < 0 ? sp.ng : -sp.ng);
            const Vec3 d = local.to_world(sample_cosine_hemisphere({rng.next_float(), rng.next_float()}));
            diffuse_rays.push_back(spawn_ray(sp.p, sp.ng, d));
        }
    }
    ~Fixture() { rtcReleaseScene(flat); }
};

Fixture& fixture() {
    static Fixture f;
    return f;
}

const std::vector<Ray>& rays_of(const benchmark::State& state) {
    return state.range(0) == 0 ? fixture().camera_rays : fixture().diffuse_rays;
}

RTCRayHit embree_ray_hit(const Ray& ray) {
    RTCRayHit rh;
    rh.ray = {ray.o.x, ray.o.y, ray.o.z, 0, ray.d.x, ray.d.y, ray.d.z, 0, ray.tmax, ~0u, 0, 0};
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

template <class Body>
void run(benchmark::State& state, Body body) {
    set_render_thread_fp_modes();
    const std::vector<Ray>& rays = rays_of(state);
    for (auto _ : state)
        for (const Ray& ray : rays) body(ray);
    state.counters["rays/s"] = benchmark::Counter(double(rays.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void interface_intersect(benchmark::State& state) {
    run(state, [](const Ray& ray) { benchmark::DoNotOptimize(fixture().tracer.intersect(ray)); });
}

void raw_same_scenes_intersect(benchmark::State& state) {
    run(state, [](const Ray& ray) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh = embree_ray_hit(ray);
        rtcIntersect1(fixture().tracer.static_embree_scene(), &context, &rh);
        rtcIntersect1(fixture().tracer.instance_embree_scene(), &context, &rh);
        benchmark::DoNotOptimize(rh.hit.geomID);
    });
}

void raw_flat_intersect(benchmark::State& state) {
    run(state, [](const Ray& ray) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh = embree_ray_hit(ray);
        rtcIntersect1(fixture().flat, &context, &rh);
        benchmark::DoNotOptimize(rh.hit.geomID);
    });
}

void interface_occluded(benchmark::State& state) {
    run(state, [](const Ray& ray) { benchmark::DoNotOptimize(fixture().tracer.occluded(ray)); });
}

void raw_same_scenes_occluded(benchmark::State& state) {
    run(state, [](const Ray& ray) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh = embree_ray_hit(ray);
        rtcOccluded1(fixture().tracer.static_embree_scene(), &context, &rh.ray);
        if (rh.ray.tfar != -infinity) rtcOccluded1(fixture().tracer.instance_embree_scene(), &context, &rh.ray);
        benchmark::DoNotOptimize(rh.ray.tfar);
    });
}

void raw_flat_occluded(benchmark::State& state) {
    run(state, [](const Ray& ray) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh = embree_ray_hit(ray);
        rtcOccluded1(fixture().flat, &context, &rh.ray);
        benchmark::DoNotOptimize(rh.ray.tfar);
    });
}

/// Console output as usual, and the CPU time per iteration of every run kept for the ratios
/// (CPU time, not wall time, so that a busy shared machine disturbs the ratios less).
class RecordingReporter : public benchmark::ConsoleReporter {
public:
    std::map<std::string, double> seconds;
    void ReportRuns(const std::vector<Run>& runs) override {
        for (const Run& run : runs) seconds[run.benchmark_name()] = run.GetAdjustedCPUTime();
        ConsoleReporter::ReportRuns(runs);
    }
};

void print_ratios(const RecordingReporter& reporter) {
    std::printf("\nInterface cost over raw Embree (time ratio; 1.00 = no overhead, target < 1.10):\n");
    std::printf("%-12s %-10s %14s %14s\n", "query", "rays", "vs raw flat", "vs same scenes");
    for (const char* query : {"intersect", "occluded"}) {
        for (const auto& [arg, label] : {std::pair{"0", "camera"}, std::pair{"1", "diffuse"}}) {
            const auto time = [&](const std::string& variant) {
                const auto it = reporter.seconds.find(variant + "_" + query + "/" + arg);
                return it == reporter.seconds.end() ? 0.0 : it->second;
            };
            const double interface = time("interface"), flat = time("raw_flat"), same = time("raw_same_scenes");
            if (interface > 0 && flat > 0 && same > 0)
                std::printf("%-12s %-10s %14.2f %14.2f\n", query, label, interface / flat, interface / same);
        }
    }
}

}  // namespace

BENCHMARK(interface_intersect)->Arg(0)->Arg(1);
BENCHMARK(raw_same_scenes_intersect)->Arg(0)->Arg(1);
BENCHMARK(raw_flat_intersect)->Arg(0)->Arg(1);
BENCHMARK(interface_occluded)->Arg(0)->Arg(1);
BENCHMARK(raw_same_scenes_occluded)->Arg(0)->Arg(1);
BENCHMARK(raw_flat_occluded)->Arg(0)->Arg(1);

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    std::printf("BALL frame 0: %zu camera rays, %zu diffuse rays per iteration; Arg 0 = camera, 1 = diffuse\n",
                fixture().camera_rays.size(), fixture().diffuse_rays.size());
    RecordingReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    print_ratios(reporter);
    benchmark::Shutdown();
    return 0;
}
