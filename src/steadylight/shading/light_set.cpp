#include <algorithm>
#include <cmath>

#include "steadylight/shading/light.h"

namespace steadylight {

float area_to_solid_angle(float pdf_area, Vec3 ref, Vec3 p, Vec3 n) {
    const Vec3 d = p - ref;
    const float distance2 = length2(d);
    const float cos_light = std::abs(dot(n, d)) / std::sqrt(distance2);
    return cos_light > 0 ? pdf_area * distance2 / cos_light : 0;
}

LightSet::LightSet(const Scene& scene, const FrameState& frame)
    : m_light_of_object(scene.objects().size(), -1) {
    for (int object = 0; object < int(scene.objects().size()); ++object) {
        if (is_black(frame.emission[size_t(object)])) continue;
        m_light_of_object[size_t(object)] = int(m_lights.size());
        m_lights.push_back(make_area_light(scene, frame, object));
    }
    for (size_t i = 0; i < scene.desc().point_lights.size(); ++i)
        if (!is_black(frame.point_light_intensity[i]))
            m_lights.push_back(make_point_light(scene.desc().point_lights[i], frame.point_light_intensity[i]));

    // Choose lights in proportion to power; uniformly if none has any.
    float total = 0;
    for (const auto& light : m_lights) total += light->power();
    for (size_t i = 0; i < m_lights.size(); ++i) {
        const float weight = total > 0 ? m_lights[i]->power() / total : 1.0f / float(m_lights.size());
        m_cdf.push_back((m_cdf.empty() ? 0 : m_cdf.back()) + weight);
    }
    if (!m_cdf.empty()) m_cdf.back() = 1;
}

std::pair<size_t, float> LightSet::choose(float u_select) const {
    const size_t i = std::min(size_t(std::upper_bound(m_cdf.begin(), m_cdf.end(), u_select) - m_cdf.begin()),
                              m_lights.size() - 1);
    return {i, m_cdf[i] - (i ? m_cdf[i - 1] : 0)};
}

std::optional<EmissionSample> LightSet::sample_emission(float u_select, Vec2 u_position, Vec2 u_direction) const {
    if (m_lights.empty()) return std::nullopt;
    const auto [i, p_select] = choose(u_select);
    if (p_select <= 0) return std::nullopt;
    std::optional<EmissionSample> s = m_lights[i]->sample_emission(u_position, u_direction);
    if (s) s->power = s->power / p_select;
    return s;
}

std::optional<LightSample> LightSet::sample(Vec3 ref, float u_select, Vec2 u) const {
    if (m_lights.empty()) return std::nullopt;
    const auto [i, p_select] = choose(u_select);
    if (p_select <= 0) return std::nullopt;
    std::optional<LightSample> s = m_lights[i]->sample_li(ref, u);
    if (!s || !(s->pdf > 0)) return std::nullopt;
    s->pdf *= p_select;
    return s;
}

std::optional<LightSample> LightSet::sample_reusing(Vec3 ref, Vec2 u) const {
    if (m_lights.empty()) return std::nullopt;
    const auto [i, p_select] = choose(u.x);
    if (p_select <= 0) return std::nullopt;
    // u.x is uniform over the chosen light's share of [0,1): rescaled, it is uniform again.
    const float lo = i ? m_cdf[i - 1] : 0;
    const float u_light = std::clamp((u.x - lo) / p_select, 0.0f, 0x1.fffffep-1f);
    std::optional<LightSample> s = m_lights[i]->sample_li(ref, {u_light, u.y});
    if (!s || !(s->pdf > 0)) return std::nullopt;
    s->pdf *= p_select;
    return s;
}

float LightSet::pdf_emitter(int object, Vec3 ref, Vec3 p, Vec3 n) const {
    const int i = m_light_of_object[size_t(object)];
    if (i < 0) return 0;
    const float p_select = m_cdf[size_t(i)] - (i ? m_cdf[size_t(i) - 1] : 0);
    return p_select * m_lights[size_t(i)]->pdf_li(ref, p, n);
}

}  // namespace steadylight
