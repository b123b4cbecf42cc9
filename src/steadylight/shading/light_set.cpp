#include <algorithm>
#include <array>
#include <cmath>

#include "steadylight/base/sampling.h"
#include "steadylight/shading/light.h"

namespace steadylight {

float importance_bound(float intensity, Vec3 ref, Vec3 n, Vec3 center, float radius, Vec3 light_n) {
    const Vec3 d = center - ref;
    const float distance2 = length2(d);
    // Inside the bounding sphere nothing can be bounded: count the light at its radius.
    if (distance2 <= radius * radius) return intensity / std::max(radius * radius, 1e-12f);
    const float distance = std::sqrt(distance2);
    const Vec3 wi = d / distance;
    const float theta_bound = std::asin(std::min(1.0f, radius / distance));
    // Each cosine is bounded by tilting its direction towards the normal by the sphere's angle.
    const auto cos_bound = [&](float cos_theta) {
        return std::cos(std::max(0.0f, std::acos(std::clamp(cos_theta, -1.0f, 1.0f)) - theta_bound));
    };
    const float cos_ref = cos_bound(dot(n, wi));
    const float cos_light = length2(light_n) > 0 ? cos_bound(dot(light_n, -wi)) : 1.0f;
    if (cos_ref <= 0 || cos_light <= 0) return 0;
    return intensity * cos_ref * cos_light / distance2;
}

float area_to_solid_angle(float pdf_area, Vec3 ref, Vec3 p, Vec3 n) {
    const Vec3 d = p - ref;
    const float distance2 = length2(d);
    const float cos_light = std::abs(dot(n, d)) / std::sqrt(distance2);
    return cos_light > 0 ? pdf_area * distance2 / cos_light : 0;
}

namespace {

/// A cdf over `lights` (indices into `all`) by power; uniform if none has any.
std::vector<float> power_cdf(const std::vector<std::unique_ptr<Light>>& all, const std::vector<size_t>& lights) {
    float total = 0;
    for (const size_t i : lights) total += all[i]->power();
    std::vector<float> cdf;
    for (const size_t i : lights) {
        const float weight = total > 0 ? all[i]->power() / total : 1.0f / float(lights.size());
        cdf.push_back((cdf.empty() ? 0 : cdf.back()) + weight);
    }
    if (!cdf.empty()) cdf.back() = 1;
    return cdf;
}

/// The entry of `cdf` that `u` picks and its probability.
std::pair<size_t, float> pick(const std::vector<float>& cdf, float u) {
    const size_t i = std::min(size_t(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin()), cdf.size() - 1);
    return {i, cdf[i] - (i ? cdf[i - 1] : 0)};
}

}  // namespace

LightSet::LightSet(const Scene& scene, const FrameState& frame) : m_light_of_object(scene.objects().size(), -1) {
    std::vector<bool> moving;
    for (int object = 0; object < int(scene.objects().size()); ++object) {
        if (is_black(frame.emission[size_t(object)])) continue;
        m_light_of_object[size_t(object)] = int(m_lights.size());
        m_lights.push_back(make_area_light(scene, frame, object));
        moving.push_back(scene.object(object).is_moving_light());
    }
    for (size_t i = 0; i < scene.desc().point_lights.size(); ++i)
        if (!is_black(frame.point_lights[i].intensity)) {
            m_lights.push_back(make_point_light(scene.desc().point_lights[i], frame.point_lights[i]));
            moving.push_back(scene.desc().point_lights[i].is_moving());
        }
    m_first_distant = m_lights.size();
    for (size_t i = 0; i < scene.desc().suns.size(); ++i)
        if (!is_black(scene.desc().suns[i].irradiance)) {
            m_lights.push_back(make_sun_light(scene.desc().suns[i], frame.sun_directions[i], scene.bounds(),
                                              scene.desc().portals, scene.distant_photon_targets()));
            moving.push_back(scene.desc().suns[i].is_moving());
        }
    if (scene.desc().world && !scene.desc().world->radiance->is_black()) {
        m_lights.push_back(make_world_light(*scene.desc().world, scene.bounds(), scene.desc().portals,
                                            scene.distant_photon_targets()));
        moving.push_back(false);
    }

    // Choose lights in proportion to power; uniformly if none has any.
    std::vector<size_t> every(m_lights.size());
    for (size_t i = 0; i < m_lights.size(); ++i) {
        every[i] = i;
        m_group_lights[moving[i]].push_back(i);
        m_group_power[moving[i]] += m_lights[i]->power();
    }
    m_cdf = power_cdf(m_lights, every);
    for (int group = 0; group < 2; ++group) m_group_cdf[group] = power_cdf(m_lights, m_group_lights[group]);
}

std::pair<size_t, float> LightSet::choose(float u_select) const { return pick(m_cdf, u_select); }

std::pair<size_t, float> LightSet::choose(PhotonGroup group, float u_select) const {
    const auto [member, p_select] = pick(m_group_cdf[int(group)], u_select);
    return {m_group_lights[int(group)][member], p_select};
}

PhotonSplit LightSet::split(long paths) const {
    const float still = m_group_power[0], moving = m_group_power[1];
    if (m_group_lights[1].empty()) return {paths, paths};
    if (m_group_lights[0].empty()) return {0, paths};
    const float share = still + moving > 0 ? still / (still + moving) : 0.5f;
    const long count =
        std::clamp(long(std::lround(double(share) * double(paths))), std::min(1L, paths - 1), std::max(paths - 1, 0L));
    return {count, paths};
}

std::optional<EmissionSample> LightSet::emission_from(size_t i, float p_select, Vec2 u_position,
                                                      Vec2 u_direction) const {
    if (p_select <= 0) return std::nullopt;
    std::optional<EmissionSample> s = m_lights[i]->sample_emission(u_position, u_direction);
    if (s) {
        s->power = s->power / p_select;
        s->from_far_away = i >= m_first_distant;
    }
    return s;
}

std::optional<EmissionSample> LightSet::sample_emission(float u_select, Vec2 u_position, Vec2 u_direction) const {
    if (m_lights.empty()) return std::nullopt;
    const auto [i, p_select] = choose(u_select);
    return emission_from(i, p_select, u_position, u_direction);
}

std::optional<EmissionSample> LightSet::sample_emission(PhotonGroup group, float u_select, Vec2 u_position,
                                                        Vec2 u_direction) const {
    if (m_group_lights[int(group)].empty()) return std::nullopt;
    const auto [i, p_select] = choose(group, u_select);
    return emission_from(i, p_select, u_position, u_direction);
}

std::optional<EmissionPoint> LightSet::sample_emission_point(PhotonGroup group, float u_select, Vec2 u_position) const {
    if (m_group_lights[int(group)].empty()) return std::nullopt;
    const auto [i, p_select] = choose(group, u_select);
    if (p_select <= 0) return std::nullopt;
    EmissionPoint at = m_lights[i]->sample_emission_point(u_position);
    at.light = i;
    at.pdf *= p_select;
    return at;
}

std::optional<LightSample> LightSet::sample(Vec3 ref, float u_select, Vec2 u, Vec3 n) const {
    if (m_lights.empty()) return std::nullopt;
    const auto [i, p_select] = choose(u_select);
    if (p_select <= 0) return std::nullopt;
    std::optional<LightSample> s = m_lights[i]->sample_li(ref, u, n);
    if (!s || !(s->pdf > 0)) return std::nullopt;
    s->pdf *= p_select;
    return s;
}

std::optional<LightSample> LightSet::sample_reusing(Vec3 ref, Vec2 u) const {
    if (m_lights.empty()) return std::nullopt;
    const auto [i, p_select] = choose(u.x);
    if (p_select <= 0) return std::nullopt;
    return sample_chosen(i, i ? m_cdf[i - 1] : 0, p_select, ref, {}, u);
}

std::optional<LightSample> LightSet::sample_chosen(size_t i, float lo, float p_select, Vec3 ref, Vec3 n, Vec2 u) const {
    // u.x is uniform over the chosen light's share of [0,1): rescaled, it is uniform again.
    const float u_light = std::clamp((u.x - lo) / p_select, 0.0f, 0x1.fffffep-1f);
    std::optional<LightSample> s = m_lights[i]->sample_li(ref, {u_light, u.y}, n);
    if (!s || !(s->pdf > 0)) return std::nullopt;
    s->pdf *= p_select;
    return s;
}

std::optional<LightSample> LightSet::sample_reusing(Vec3 ref, Vec3 n, Vec2 u) const {
    const size_t count = m_lights.size();
    if (count == 0 || count > max_lights_by_importance) return sample_reusing(ref, u);
    // A single light is chosen whatever its importance, which decides only whether its sampling
    // is told the normal (not where the importance is 0): one that does not read it is sampled
    // straight away, the same bits without the importance computed.
    if (count == 1 && !m_lights[0]->samples_by_normal()) return sample_chosen(0, 0, 1, ref, n, u);
    // A share of the power choice keeps every light possible however rough the bound is.
    constexpr float power_share = 0.1f;
    std::array<float, max_lights_by_importance> cdf;
    float total = 0;
    for (size_t i = 0; i < count; ++i) total += (cdf[i] = m_lights[i]->importance(ref, n));
    if (!(total > 0) || !std::isfinite(total)) return sample_reusing(ref, u);
    float sum = 0;
    for (size_t i = 0; i < count; ++i)
        cdf[i] = (sum += (1 - power_share) * cdf[i] / total + power_share * (m_cdf[i] - (i ? m_cdf[i - 1] : 0)));
    cdf[count - 1] = 1;
    const size_t i =
        std::min(size_t(std::upper_bound(cdf.begin(), cdf.begin() + long(count), u.x) - cdf.begin()), count - 1);
    const float lo = i ? cdf[i - 1] : 0, p_select = cdf[i] - lo;
    if (!(p_select > 0)) return std::nullopt;
    return sample_chosen(i, lo, p_select, ref, n, u);
}

std::vector<BoundingSphere> LightSet::bounds() const {
    std::vector<BoundingSphere> out;
    for (const std::unique_ptr<Light>& light : m_lights) out.push_back(light->bounds());
    return out;
}

float LightSet::pdf_emitter(int object, Vec3 ref, Vec3 p, Vec3 n) const {
    const int i = m_light_of_object[size_t(object)];
    if (i < 0) return 0;
    const float p_select = m_cdf[size_t(i)] - (i ? m_cdf[size_t(i) - 1] : 0);
    return p_select * m_lights[size_t(i)]->pdf_li(ref, p, n);
}

Rgb LightSet::escaped_radiance(Vec3 w) const {
    Rgb L;
    for (size_t i = m_first_distant; i < m_lights.size(); ++i) L += m_lights[i]->escaped_radiance(w);
    return L;
}

Rgb LightSet::escaped_radiance(Vec3 ref, Vec3 w, Vec3 n, float bsdf_pdf) const {
    Rgb L;
    for (size_t i = m_first_distant; i < m_lights.size(); ++i) {
        const Rgb Le = m_lights[i]->escaped_radiance(w);
        if (is_black(Le)) continue;
        const float light_pdf = (m_cdf[i] - (i ? m_cdf[i - 1] : 0)) * m_lights[i]->pdf_escaped(ref, w, n);
        L += Le * power_heuristic(bsdf_pdf, light_pdf);
    }
    return L;
}

}  // namespace steadylight
