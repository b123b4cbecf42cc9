// GGX and its albedo tables (microfacet.h).
#include "steadylight/shading/microfacet.h"

#include <array>
#include <cmath>

namespace steadylight {
namespace {

constexpr int table_mu = 64;         // cos theta from 0 to 1, spaced as its square root (finer at grazing)
constexpr int table_roughness = 32;  // roughness from 0 to 1
constexpr int table_strata = 32;     // per axis: 1024 samples per entry

struct AlbedoTables {
    std::array<std::array<GgxAlbedo, table_mu>, table_roughness> e{};
    std::array<GgxAlbedo, table_roughness> average{};
};

float mu_of(int i) {
    const float x = float(i) / float(table_mu - 1);
    return std::max(x * x, 1e-4f);
}
float roughness_of(int j) { return std::max(float(j) / float(table_roughness - 1), min_pbr_roughness); }

/// Integrates the single-scattering albedo by sampling visible normals: each sample weighs
/// f cos / pdf = G2 / G1(wo), times the Fresnel term.
GgxAlbedo integrate_albedo(float mu, float roughness) {
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

/// Linear interpolation in a row of the table.
GgxAlbedo lookup_row(const std::array<GgxAlbedo, table_mu>& row, float mu) {
    const float x = std::sqrt(std::clamp(mu, 0.0f, 1.0f)) * float(table_mu - 1);
    const int i = std::min(int(x), table_mu - 2);
    const float t = x - float(i);
    return {row[size_t(i)].e * (1 - t) + row[size_t(i) + 1].e * t,
            row[size_t(i)].e_schlick * (1 - t) + row[size_t(i) + 1].e_schlick * t};
}

AlbedoTables build_tables() {
    AlbedoTables tables;
    for (int j = 0; j < table_roughness; ++j) {
        auto& row = tables.e[size_t(j)];
        for (int i = 0; i < table_mu; ++i) row[size_t(i)] = integrate_albedo(mu_of(i), roughness_of(j));
        // The averages integrate the interpolated row itself, so that the compensation lobes
        // (which use both) integrate to exactly what they should.
        constexpr int steps = 1024;
        double e = 0, es = 0;
        for (int k = 0; k < steps; ++k) {
            const float mu = (float(k) + 0.5f) / steps;
            const GgxAlbedo a = lookup_row(row, mu);
            e += 2.0 * a.e * mu / steps;
            es += 2.0 * a.e_schlick * mu / steps;
        }
        tables.average[size_t(j)] = {float(e), float(es)};
    }
    return tables;
}

const AlbedoTables& tables() {
    static const AlbedoTables t = build_tables();
    return t;
}

/// The roughness row below `roughness` and the weight of the row above.
std::pair<int, float> roughness_cell(float roughness) {
    const float y = std::clamp(roughness, 0.0f, 1.0f) * float(table_roughness - 1);
    const int j = std::min(int(y), table_roughness - 2);
    return {j, y - float(j)};
}

GgxAlbedo mix(GgxAlbedo a, GgxAlbedo b, float t) {
    return {a.e * (1 - t) + b.e * t, a.e_schlick * (1 - t) + b.e_schlick * t};
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
    const auto [j, t] = roughness_cell(roughness);
    return mix(lookup_row(tables().e[size_t(j)], cos_theta), lookup_row(tables().e[size_t(j) + 1], cos_theta), t);
}

GgxAlbedo ggx_average_albedo(float roughness) {
    const auto [j, t] = roughness_cell(roughness);
    return mix(tables().average[size_t(j)], tables().average[size_t(j) + 1], t);
}

}  // namespace steadylight
