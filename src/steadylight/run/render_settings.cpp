// Validation of a run's settings (render_settings.h).
#include "steadylight/run/render_settings.h"

#include "steadylight/base/settings_check.h"

namespace steadylight {

void validate(const RenderSettings& settings) {
    if (settings.width) check_setting_range("/size", *settings.width, 1, 1 << 16);
    if (settings.height) check_setting_range("/size", *settings.height, 1, 1 << 16);
    validate(settings.output);
    validate(static_cast<const MethodSettings&>(settings));
}

}  // namespace steadylight
