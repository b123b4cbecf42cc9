#include "steadylight/passes/frame_stats.h"

#include <fmt/format.h>

#include <type_traits>

namespace steadylight {

namespace {

/// Calls `visit(json_pointer, member)` for every field, so that writing and reading the JSON
/// file cannot drift apart.
template <typename Stats, typename Visit>
void for_each_json_field(Stats& s, Visit&& visit) {
    visit("/method", s.method);
    visit("/frame", s.frame);
    visit("/photons/global_emitted", s.global_photons_emitted);
    visit("/photons/global_stored", s.global_photons_stored);
    visit("/photons/caustic_emitted", s.caustic_photons_emitted);
    visit("/photons/caustic_stored", s.caustic_photons_stored);
    visit("/photons/dynamic_stored", s.dynamic_photons_stored);
    visit("/photons/irradiance_precomputed", s.irradiance_photons);
    visit("/photons/irradiance_reused", s.irradiance_reused);
    visit("/photons/irradiance_from_lists", s.irradiance_from_lists);
    visit("/photons/irradiance_carried", s.irradiance_carried);
    visit("/irradiance_records", s.irradiance_records);
    visit("/static_records", s.static_records);
    visit("/fallback_gathers", s.fallback_gathers);
    visit("/gather_rays", s.gather_rays);
    visit("/seconds/photon_tracing", s.photon_tracing_s);
    visit("/seconds/cache", s.cache_s);
    visit("/seconds/influence", s.influence_s);
    visit("/seconds/correction", s.correction_s);
    visit("/seconds/shading", s.shading_s);
    visit("/seconds/caustics", s.caustics_s);
    visit("/seconds/total", s.total_s);
}

/// The fields added after the first statistics files were written: a file may lack them (an
/// older run's, which `steadylight report` still reads), and they then read as zero.
template <typename Stats, typename Visit>
void for_each_later_json_field(Stats& s, Visit&& visit) {
    visit("/path/camera_samples", s.camera_samples);
    visit("/path/rays", s.path_rays);
    visit("/path/vertices", s.path_vertices);
    visit("/photons/retraced_paths", s.retraced_photon_paths);
    visit("/pixels/reused", s.pixels_reused);
    visit("/pixels/looked_up_again", s.pixels_looked_up_again);
    visit("/pixels/direct_again", s.pixels_direct_again);
    visit("/pixels/direct_from_kept", s.pixels_direct_from_kept);
    visit("/pixels/redone_but_direct", s.pixels_redone_but_direct);
    visit("/pixels/redone", s.pixels_redone);
    visit("/pixels/changed_camera", s.pixels_changed[0]);
    visit("/pixels/changed_direct", s.pixels_changed[1]);
    visit("/pixels/changed_indirect", s.pixels_changed[2]);
    visit("/pixels/changed_caustic", s.pixels_changed[3]);
    visit("/non_finite_values", s.non_finite_values);
}

/// Whether the frame ran photon-mapping passes: photons, records, gathers or their phases' time.
bool has_photon_mapping_figures(const FrameStats& s) {
    return s.global_photons_emitted > 0 || s.caustic_photons_emitted > 0 || s.irradiance_records > 0 ||
           s.static_records > 0 || s.gather_rays > 0 || s.photon_tracing_s > 0 || s.cache_s > 0 || s.shading_s > 0;
}

std::string summarize_photon_mapping(const FrameStats& s) {
    std::string text = fmt::format(
        "photons {}k/{}k stored, records {}, gather rays {:.2f}M, photon paths traced {} | "
        "photons {:.2f} s, cache {:.2f} s, ",
        s.global_photons_stored / 1000, s.caustic_photons_stored / 1000, s.irradiance_records,
        double(s.gather_rays) / 1e6, s.retraced_photon_paths, s.photon_tracing_s, s.cache_s);
    if (s.influence_s > 0 || s.correction_s > 0)  // the localized method's own phases
        text += fmt::format("influence {:.2f} s, L_t {:.2f} s, ", s.influence_s, s.correction_s);
    if (const long pixels = s.pixels_reused + s.pixels_looked_up_again + s.pixels_direct_again +
                            s.pixels_redone_but_direct + s.pixels_redone) {
        const auto share = [&](long part) { return 100.0 * double(part) / double(pixels); };
        text += fmt::format(
            "pixels reused {:.1f}%, looked up again {:.1f}%, direct again {:.1f}% ({:.1f}% from kept samples), "
            "redone but direct {:.1f}%, redone {:.1f}%, ",
            share(s.pixels_reused), share(s.pixels_looked_up_again), share(s.pixels_direct_again),
            share(s.pixels_direct_from_kept), share(s.pixels_redone_but_direct), share(s.pixels_redone));
    }
    return text + fmt::format("shading {:.2f} s (caustics {:.2f} s cpu)", s.shading_s, s.caustics_s);
}

/// The path tracer's figures; `s.camera_samples` > 0.
std::string summarize_paths(const FrameStats& s) {
    const double samples = double(s.camera_samples);
    return fmt::format("camera samples {:.2f}M, rays {:.2f}M ({:.2f} a sample), path length {:.2f} vertices",
                       samples / 1e6, double(s.path_rays) / 1e6, double(s.path_rays) / samples,
                       double(s.path_vertices) / samples);
}

}  // namespace

void to_json(nlohmann::json& json, const FrameStats& s) {
    json = nlohmann::json::object();
    const auto write = [&](const char* pointer, const auto& value) {
        json[nlohmann::json::json_pointer(pointer)] = value;
    };
    for_each_json_field(s, write);
    for_each_later_json_field(s, write);
    if (s.distant_photons_inside >= 0) json["distant_photons_inside"] = s.distant_photons_inside;
}

void from_json(const nlohmann::json& json, FrameStats& s) {
    // Files written before the shading time had a key of its own name it /seconds/direct.
    const nlohmann::json::json_pointer shading("/seconds/shading"), direct("/seconds/direct");
    if (!json.contains(shading) && json.contains(direct)) {
        nlohmann::json renamed = json;
        renamed[shading] = json.at(direct);
        return from_json(renamed, s);
    }
    for_each_json_field(
        s, [&](const char* pointer, auto& value) { json.at(nlohmann::json::json_pointer(pointer)).get_to(value); });
    for_each_later_json_field(s, [&](const char* pointer, auto& value) {
        using Value = std::decay_t<decltype(value)>;
        const nlohmann::json::json_pointer at(pointer);
        value = json.contains(at) ? json.at(at).get<Value>() : Value{};
    });
    s.distant_photons_inside = json.value("distant_photons_inside", -1.0);
}

std::string summarize(const FrameStats& s) {
    // Each group of figures only where the frame has some; a frame without any still gets the
    // photon-mapping line, as every frame did before the path tracer had statistics.
    const bool paths = s.camera_samples > 0;
    std::string text = has_photon_mapping_figures(s) || !paths ? summarize_photon_mapping(s) : "";
    if (paths) text += (text.empty() ? "" : " | ") + summarize_paths(s);
    if (s.distant_photons_inside >= 0)
        text += fmt::format(" | distant photons inside {:.1f}%", 100 * s.distant_photons_inside);
    if (s.non_finite_values > 0) text += fmt::format(" | {} non-finite values written as 0", s.non_finite_values);
    return text;
}

}  // namespace steadylight
