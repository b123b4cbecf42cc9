// Validation of the localized method's settings (localized_settings.h).
#include "steadylight/passes/localized_settings.h"

#include "steadylight/base/settings_check.h"

namespace steadylight {

void validate(const LocalizedSettings& settings, const std::string& where) {
    check_setting_range(where + "/influence_photons", settings.influence_photons, 1, 100000);
    const CorrectionSettings& correction = settings.correction;
    check_setting_range(where + "/correction/radius", correction.radius, 1e-6f, 1e6f);
    check_setting_range(where + "/correction/levels", correction.levels, 1, max_correction_levels);
    check_setting_range(where + "/correction/noise_sigmas", correction.noise_sigmas, 0.0f, 100.0f);
    check_setting_range(where + "/correction/signal_sigmas", correction.signal_sigmas, 0.0f, 100.0f);
    check_setting(correction.noise_sigmas <= correction.signal_sigmas, where + "/correction/signal_sigmas",
                  "must be at least noise_sigmas");
    check_setting_range(where + "/correction/point_spacing", correction.point_spacing, 0.0f, 4.0f);
    check_setting_range(where + "/influence_step", settings.influence_step, 0, 1024);
    check_setting_range(where + "/tau_lower", settings.tau_lower, 0.0f, 1e6f);
    check_setting_range(where + "/tau_upper", settings.tau_upper, 0.0f, 1e6f);
    check_setting(settings.tau_lower < settings.tau_upper, where + "/tau_upper",
                  "must be larger than tau_lower (--tau-upper, --tau-lower)");
}

}  // namespace steadylight
