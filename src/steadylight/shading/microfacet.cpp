// GGX and its albedo tables (microfacet.h).
#include "steadylight/shading/microfacet.h"

#include <algorithm>
#include <cmath>

#include "steadylight/shading/albedo_table.h"

namespace steadylight {
namespace {

constexpr int table_strata = 32;  // per axis: 1024 samples per entry

/// Integrates the single-scattering albedo by sampling visible normals: each sample weighs
/// f cos / pdf = G2 / G1(wo), times the Fresnel term: 1, and Schlick's (1 - wo.h)^5.
AlbedoTable::Channels integrate_albedo(float mu, float roughness) {
    const Ggx ggx(roughness * roughness);
    const Vec3 wo{std::sqrt(std::max(0.0f, 1 - mu * mu)), 0, mu};
    double e = 0, es = 0;
    for (int a = 0; a < table_strata; ++a)
        for (int b = 0; b < table_strata; ++b) {
            const Vec2 u{(float(a) + 0.5f) / table_strata, (float(b) + 0.5f) / table_strata};
            const Vec3 h = ggx.sample_visible_normal(wo, u);
            const Vec3 wi = reflect(wo, h);
            if (wi.z <= 0) continue;
            const double w = ggx.g2(wo, wi) / ggx.g1(wo);
            e += w;
            es += w * std::pow(1 - std::clamp(double(dot(wo, h)), 0.0, 1.0), 5.0);
        }
    const double n = double(table_strata) * table_strata;
    return {float(e / n), float(es / n)};
}

const AlbedoTable& table() {
    static const AlbedoTable t(64, 32, min_pbr_roughness, integrate_albedo);
    return t;
}

}  // namespace

float Ggx::d(Vec3 h) const {
    const float a2 = m_alpha * m_alpha;
    const float d = h.z * h.z * (a2 - 1) + 1;
    return a2 / (pi * d * d);
}

float Ggx::lambda(Vec3 w) const {
    const float cos2 = w.z * w.z;
    if (cos2 <= 0) return 1e30f;
    const float tan2 = std::max(0.0f, 1 - cos2) / cos2;
    return (std::sqrt(1 + m_alpha * m_alpha * tan2) - 1) / 2;
}

Vec3 Ggx::sample_visible_normal(Vec3 wo, Vec2 u) const {
    // Stretch the view to the unit-roughness configuration, sample the projected hemisphere
    // there, and unstretch (Heitz 2018, listing 1).
    const Vec3 vh = normalize(Vec3{m_alpha * wo.x, m_alpha * wo.y, wo.z});
    const float lensq = vh.x * vh.x + vh.y * vh.y;
    const Vec3 t1 = lensq > 0 ? Vec3{-vh.y, vh.x, 0} / std::sqrt(lensq) : Vec3{1, 0, 0};
    const Vec3 t2 = cross(vh, t1);
    const float r = std::sqrt(u.x), phi = 2 * pi * u.y;
    const float p1 = r * std::cos(phi);
    const float s = 0.5f * (1 + vh.z);
    const float p2 = (1 - s) * std::sqrt(std::max(0.0f, 1 - p1 * p1)) + s * r * std::sin(phi);
    const Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.0f, 1 - p1 * p1 - p2 * p2));
    return normalize(Vec3{m_alpha * nh.x, m_alpha * nh.y, std::max(1e-6f, nh.z)});
}

float Ggx::pdf_reflection(Vec3 wo, Vec3 wi) const {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    const Vec3 h = normalize(wo + wi);
    // Visible-normal density over the Jacobian 4 wo.h of reflection: G1(wo) D(h) / (4 wo.z).
    return g1(wo) * d(h) / (4 * wo.z);
}

GgxAlbedo ggx_albedo(float cos_theta, float roughness) {
    const AlbedoTable::Channels e = table().at(cos_theta, roughness);
    return {e[0], e[1]};
}

GgxAlbedo ggx_average_albedo(float roughness) {
    const AlbedoTable::Channels e = table().average(roughness);
    return {e[0], e[1]};
}

}  // namespace steadylight
