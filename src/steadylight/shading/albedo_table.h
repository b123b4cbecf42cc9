// Directional albedos tabulated over (cos theta, roughness): what Kulla and Conty's
// multiple-scattering compensation needs (Kulla & Conty 2017, "Revisiting Physically Based
// Shading at Imageworks"), for the pbr material's GGX lobes (microfacet.cpp) and for rough glass
// (rough_dielectric.cpp). Two channels per entry: GGX with Fresnel 1 and with Schlick's term, or
// glass seen from outside and from inside.
#pragma once

#include <array>
#include <functional>
#include <vector>

namespace steadylight {

class AlbedoTable {
public:
    using Channels = std::array<float, 2>;
    /// Fills the table by calling `albedo(mu, roughness)` at every entry: `mu_steps` values of
    /// cos theta in [0, 1] spaced as its square root (finer at grazing angles), `roughness_steps`
    /// roughnesses in [0, 1] (each at least `min_roughness`).
    AlbedoTable(int mu_steps, int roughness_steps, float min_roughness,
                const std::function<Channels(float mu, float roughness)>& albedo);

    /// E(mu, roughness), interpolated linearly in both.
    Channels at(float mu, float roughness) const;
    /// The cosine-weighted average 2 * integral of E(mu) mu dmu, of the interpolated table itself,
    /// so that a lobe (1 - E(wo)) (1 - E(wi)) / (pi (1 - E_avg)) integrates to exactly 1 - E(wo).
    Channels average(float roughness) const;

private:
    Channels row_at(int row, float mu) const;
    std::pair<int, float> roughness_cell(float roughness) const;

    int m_mu_steps, m_roughness_steps;
    std::vector<Channels> m_entries;  // row by row, a row per roughness
    std::vector<Channels> m_averages;
};

}  // namespace steadylight
