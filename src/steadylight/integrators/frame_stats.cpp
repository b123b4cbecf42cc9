#include "steadylight/integrators/frame_stats.h"

#include <fmt/format.h>

namespace steadylight {

void to_json(nlohmann::json& json, const FrameStats& s) {
    json = {{"method", s.method},
            {"frame", s.frame},
            {"photons",
             {{"global_emitted", s.global_photons_emitted},
              {"global_stored", s.global_photons_stored},
              {"caustic_emitted", s.caustic_photons_emitted},
              {"caustic_stored", s.caustic_photons_stored},
              {"dynamic_stored", s.dynamic_photons_stored},
              {"irradiance_precomputed", s.irradiance_photons}}},
            {"irradiance_records", s.irradiance_records},
            {"static_records", s.static_records},
            {"fallback_gathers", s.fallback_gathers},
            {"gather_rays", s.gather_rays},
            {"seconds",
             {{"photon_tracing", s.photon_tracing_s},
              {"cache", s.cache_s},
              {"influence", s.influence_s},
              {"correction", s.correction_s},
              {"direct", s.direct_s},
              {"caustics", s.caustics_s},
              {"total", s.total_s}}}};
}

void from_json(const nlohmann::json& json, FrameStats& s) {
    json.at("method").get_to(s.method);
    json.at("frame").get_to(s.frame);
    const nlohmann::json& photons = json.at("photons");
    photons.at("global_emitted").get_to(s.global_photons_emitted);
    photons.at("global_stored").get_to(s.global_photons_stored);
    photons.at("caustic_emitted").get_to(s.caustic_photons_emitted);
    photons.at("caustic_stored").get_to(s.caustic_photons_stored);
    photons.at("dynamic_stored").get_to(s.dynamic_photons_stored);
    photons.at("irradiance_precomputed").get_to(s.irradiance_photons);
    json.at("irradiance_records").get_to(s.irradiance_records);
    json.at("static_records").get_to(s.static_records);
    json.at("fallback_gathers").get_to(s.fallback_gathers);
    json.at("gather_rays").get_to(s.gather_rays);
    const nlohmann::json& seconds = json.at("seconds");
    seconds.at("photon_tracing").get_to(s.photon_tracing_s);
    seconds.at("cache").get_to(s.cache_s);
    seconds.at("influence").get_to(s.influence_s);
    seconds.at("correction").get_to(s.correction_s);
    seconds.at("direct").get_to(s.direct_s);
    seconds.at("caustics").get_to(s.caustics_s);
    seconds.at("total").get_to(s.total_s);
}

std::string summarize(const FrameStats& s) {
    std::string text = fmt::format("photons {}k/{}k stored, records {}, gather rays {:.2f}M | photons {:.2f} s, cache {:.2f} s, ",
                                   s.global_photons_stored / 1000, s.caustic_photons_stored / 1000, s.irradiance_records,
                                   double(s.gather_rays) / 1e6, s.photon_tracing_s, s.cache_s);
    if (s.method != "photon")
        text += fmt::format("influence {:.2f} s, L_t {:.2f} s, ", s.influence_s, s.correction_s);
    return text + fmt::format("shading {:.2f} s (caustics {:.2f} s cpu)", s.direct_s, s.caustics_s);
}

}  // namespace steadylight
