// The memory model (memory_model.h).
#include "steadylight/run/memory_model.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>

#include <fmt/format.h>

#include "steadylight/base/error.h"

namespace steadylight {
namespace {

constexpr double fixed_bytes = 64e6;
constexpr double bytes_per_triangle = 160;
constexpr double bytes_per_pixel_photon = 300;
// localized and frozen: their dozen layers, the static frame, its kept light samples (at most 40)
constexpr double bytes_per_pixel_localized = 540;
constexpr double bytes_per_pixel_path = 60;
constexpr double bytes_per_pixel_alpha = 12;  // the alpha image of --transparent-background
constexpr double bytes_per_photon_path = 650;
constexpr double bytes_per_world_pixel = 48;

/// A limit in bytes from a file holding one number ("max" or a huge value: none).
std::optional<size_t> limit_from_file(const char* path) {
    std::ifstream in(path);
    size_t bytes = 0;
    if (!(in >> bytes) || bytes == 0 || bytes >= (size_t(1) << 60)) return std::nullopt;
    return bytes;
}

/// A limit in bytes from an environment variable in megabytes.
std::optional<size_t> megabytes_from_env(const char* name, size_t times = 1) {
    const char* value = std::getenv(name);
    if (!value) return std::nullopt;
    char* end = nullptr;
    const unsigned long long megabytes = std::strtoull(value, &end, 10);
    if (end == value || megabytes == 0) return std::nullopt;
    return size_t(megabytes) * 1024 * 1024 * times;
}

std::string gigabytes(double bytes) { return fmt::format("{:.1f} GB", bytes / 1e9); }

}  // namespace

double MemoryEstimate::total() const { return fixed_bytes + scene + pixels + photons; }

long triangle_count(const SceneDesc& desc) {
    long triangles = 0;
    for (const ObjectDesc& object : desc.objects)
        if (const auto* mesh = std::get_if<TriangleMesh>(&object.geometry)) triangles += long(mesh->indices.size() / 3);
    return triangles;
}

MemoryEstimate estimate_memory(const RenderSettings& settings, const Scene& scene) {
    MemoryEstimate need;
    need.scene = bytes_per_triangle * double(triangle_count(scene.desc()));
    if (scene.desc().world) need.scene += bytes_per_world_pixel * double(scene.desc().world->radiance->pixel_count());
    const Camera& camera = scene.evaluate(0).camera;
    const bool path = settings.method == Method::path;
    const double per_pixel = path                                ? bytes_per_pixel_path
                             : settings.method == Method::photon ? bytes_per_pixel_photon
                                                                 : bytes_per_pixel_localized;
    need.pixels = double(camera.width) * double(camera.height) *
                  (per_pixel + (settings.output.transparent_background ? bytes_per_pixel_alpha : 0));
    if (!path)
        need.photons = bytes_per_photon_path * (double(settings.photon.photons.global_photons) +
                                                double(settings.photon.photons.caustic_photons));
    return need;
}

MemoryLimit memory_available() {
    MemoryLimit limit{size_t(sysconf(_SC_PHYS_PAGES)) * size_t(sysconf(_SC_PAGE_SIZE)), "physical memory"};
    const auto lower = [&](std::optional<size_t> bytes, const char* source) {
        if (bytes && *bytes < limit.bytes) limit = {*bytes, source};
    };
    lower(limit_from_file("/sys/fs/cgroup/memory.max"), "the cgroup's memory.max");
    lower(limit_from_file("/sys/fs/cgroup/memory/memory.limit_in_bytes"), "the cgroup's memory.limit_in_bytes");
    lower(megabytes_from_env("SLURM_MEM_PER_NODE"), "Slurm's SLURM_MEM_PER_NODE");
    if (const char* cpus = std::getenv("SLURM_CPUS_ON_NODE"))
        lower(megabytes_from_env("SLURM_MEM_PER_CPU", size_t(std::max(1, std::atoi(cpus)))),
              "Slurm's SLURM_MEM_PER_CPU");
    return limit;
}

void check_memory(const MemoryEstimate& need, const MemoryLimit& limit) {
    if (need.total() <= double(limit.bytes)) return;
    const char* option = need.pixels >= need.photons && need.pixels >= need.scene ? "--size"
                         : need.photons >= need.scene                             ? "--photons and --caustic-photons"
                                                      : "the scene's triangles or world image";
    throw InputError("memory",
                     fmt::format("this render needs about {} (image {}, photons {}, scene {}), more than the {} "
                                 "available ({}); lower {} (docs/usage.md, \"Memory\")",
                                 gigabytes(need.total()), gigabytes(need.pixels), gigabytes(need.photons),
                                 gigabytes(need.scene), gigabytes(double(limit.bytes)), limit.source, option));
}

}  // namespace steadylight
