// Validation of the photon-mapping passes' settings (photon_mapping_settings.h).
#include "steadylight/passes/photon_mapping_settings.h"

#include "steadylight/base/settings_check.h"

namespace steadylight {

void validate(const PhotonMappingSettings& settings, const std::string& where) {
    validate(settings.photons, where + "/photons");
    validate(settings.irradiance_estimate, where + "/irradiance_estimate");
    check_setting_range(where + "/irradiance_stride", settings.irradiance_stride, 1, 1 << 20);
    validate(settings.gather, where + "/gather");
    validate(settings.cache, where + "/cache");
    validate(settings.shading, where + "/shading");
}

}  // namespace steadylight
