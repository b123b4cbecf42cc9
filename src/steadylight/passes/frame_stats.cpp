#include "steadylight/passes/frame_stats.h"

#include <fmt/format.h>

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
    visit("/irradiance_records", s.irradiance_records);
    visit("/static_records", s.static_records);
    visit("/fallback_gathers", s.fallback_gathers);
    visit("/gather_rays", s.gather_rays);
    visit("/seconds/photon_tracing", s.photon_tracing_s);
    visit("/seconds/cache", s.cache_s);
    visit("/seconds/influence", s.influence_s);
    visit("/seconds/correction", s.correction_s);
    visit("/seconds/direct", s.direct_s);
    visit("/seconds/caustics", s.caustics_s);
    visit("/seconds/total", s.total_s);
}

}  // namespace

void to_json(nlohmann::json& json, const FrameStats& s) {
    json = nlohmann::json::object();
    for_each_json_field(s, [&](const char* pointer, const auto& value) { json[nlohmann::json::json_pointer(pointer)] = value; });
}

void from_json(const nlohmann::json& json, FrameStats& s) {
    for_each_json_field(s, [&](const char* pointer, auto& value) { json.at(nlohmann::json::json_pointer(pointer)).get_to(value); });
}

std::string summarize(const FrameStats& s) {
    std::string text = fmt::format("photons {}k/{}k stored, records {}, gather rays {:.2f}M | photons {:.2f} s, cache {:.2f} s, ",
                                   s.global_photons_stored / 1000, s.caustic_photons_stored / 1000, s.irradiance_records,
                                   double(s.gather_rays) / 1e6, s.photon_tracing_s, s.cache_s);
    if (s.influence_s > 0 || s.correction_s > 0)  // the localized method's own phases
        text += fmt::format("influence {:.2f} s, L_t {:.2f} s, ", s.influence_s, s.correction_s);
    return text + fmt::format("shading {:.2f} s (caustics {:.2f} s cpu)", s.direct_s, s.caustics_s);
}

}  // namespace steadylight
