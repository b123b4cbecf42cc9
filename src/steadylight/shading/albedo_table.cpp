// Directional albedo tables (albedo_table.h).
#include "steadylight/shading/albedo_table.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "steadylight/base/parallel.h"

namespace steadylight {
namespace {

AlbedoTable::Channels mix(AlbedoTable::Channels a, AlbedoTable::Channels b, float t) {
    return {a[0] * (1 - t) + b[0] * t, a[1] * (1 - t) + b[1] * t};
}

}  // namespace

AlbedoTable::AlbedoTable(int mu_steps, int roughness_steps, float min_roughness,
                         const std::function<Channels(float mu, float roughness)>& albedo)
    : m_mu_steps(mu_steps), m_roughness_steps(roughness_steps) {
    // In parallel, each entry on its own. Isolated: a thread waiting here must not pick up the
    // caller's other tasks, which may be waiting for this very table.
    m_entries.resize(size_t(mu_steps) * size_t(roughness_steps));
    tbb::this_task_arena::isolate([&] {
        tbb::parallel_for(0, roughness_steps * mu_steps, [&](int entry) {
            set_render_thread_fp_modes();  // the same on every thread: the table never depends on which
            const int j = entry / mu_steps, i = entry % mu_steps;
            const float roughness = std::max(float(j) / float(roughness_steps - 1), min_roughness);
            const float x = float(i) / float(mu_steps - 1);
            m_entries[size_t(entry)] = albedo(std::max(x * x, 1e-4f), roughness);
        });
    });
    for (int j = 0; j < roughness_steps; ++j) {
        constexpr int steps = 1024;
        double sum[2] = {0, 0};
        for (int k = 0; k < steps; ++k) {
            const float mu = (float(k) + 0.5f) / steps;
            const Channels e = row_at(j, mu);
            for (int c = 0; c < 2; ++c) sum[c] += 2.0 * e[size_t(c)] * mu / steps;
        }
        m_averages.push_back({float(sum[0]), float(sum[1])});
    }
}

AlbedoTable::Channels AlbedoTable::row_at(int row, float mu) const {
    const float x = std::sqrt(std::clamp(mu, 0.0f, 1.0f)) * float(m_mu_steps - 1);
    const int i = std::min(int(x), m_mu_steps - 2);
    const size_t first = size_t(row) * size_t(m_mu_steps) + size_t(i);
    return mix(m_entries[first], m_entries[first + 1], x - float(i));
}

std::pair<int, float> AlbedoTable::roughness_cell(float roughness) const {
    const float y = std::clamp(roughness, 0.0f, 1.0f) * float(m_roughness_steps - 1);
    const int j = std::min(int(y), m_roughness_steps - 2);
    return {j, y - float(j)};
}

AlbedoTable::Channels AlbedoTable::at(float mu, float roughness) const {
    const auto [j, t] = roughness_cell(roughness);
    return mix(row_at(j, mu), row_at(j + 1, mu), t);
}

AlbedoTable::Channels AlbedoTable::average(float roughness) const {
    const auto [j, t] = roughness_cell(roughness);
    return mix(m_averages[size_t(j)], m_averages[size_t(j) + 1], t);
}

}  // namespace steadylight
