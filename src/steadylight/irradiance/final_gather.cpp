// Final gathering over M x N cosine-weighted strata, and the irradiance gradients of Ward &
// Heckbert (1992) computed from the same strata. Each stratum covers the same projected solid
// angle pi / (M N), so E is pi / (M N) times the sum of the rays' radiances. The gradient
// formulas are derived next to their code; they are the published ones (Ward & Heckbert 1992;
// Jarosz, Zwicker & Jensen 2008, §3 and appendix) with each stratum's geometric factor integrated
// exactly over the stratum instead of taken at its midpoint.
#include "steadylight/irradiance/final_gather.h"

#include <algorithm>
#include <cmath>

#include "steadylight/base/check.h"
#include "steadylight/base/rng.h"
#include "steadylight/base/settings_check.h"

namespace steadylight {
namespace {

// Any constant will do: it only has to be the same in every run, frame and machine (docs/design.md).
constexpr uint64_t fixed_directions_seed = 0x7a3a2002'5eedf00dull;

using Gradient = std::array<Vec3, 3>;

/// Adds `direction * weight` to each colour channel's gradient.
void add_to_gradient(Gradient& gradient, Vec3 direction, Rgb weight) {
    for (int c = 0; c < 3; ++c) gradient[c] += direction * weight[c];
}

/// The local unit vector in the tangent plane at azimuth `phi`.
Vec3 azimuth_vector(float phi) { return {std::cos(phi), std::sin(phi), 0.0f}; }

/// sin(theta) of the boundary between theta rings j - 1 and j: sin^2 = j / M.
float boundary_sin_theta(int j, int M) { return std::sqrt(float(j) / float(M)); }

/// The mean of tan(theta) over theta ring j under the cosine-weighted measure:
/// M * [theta - sin(theta) cos(theta)] between the ring's bounds, since
/// int tan(theta) cos(theta) sin(theta) d(theta) = (theta - sin(theta) cos(theta)) / 2 and the
/// ring's share of int cos(theta) sin(theta) d(theta) is 1 / (2M).
float ring_mean_tan_theta(int j, int M) {
    const auto antiderivative = [](float sin_theta) {
        const float cos_theta = std::sqrt(std::max(0.0f, 1 - sin_theta * sin_theta));
        return std::asin(sin_theta) - sin_theta * cos_theta;
    };
    return float(M) * (antiderivative(boundary_sin_theta(j + 1, M)) - antiderivative(boundary_sin_theta(j, M)));
}

/// Rotational gradient in the local frame (normal = +z), for E(n') ~ E + (n x n') . grad.
/// Turning n by a small angle alpha about a tangent axis a changes E = int L max(0, w.n) dw by
/// alpha int L w.(a x n) dw = alpha a . int L (n x w) dw (the horizon term vanishes with the
/// cosine), and n x w = sin(theta) v(phi), v(phi) = azimuth_vector(phi + pi/2). So
///   grad = int L sin(theta) v dw = sum_k v_k sum_j tan(theta_j) L_jk pi / (M N).
/// The published "-tan(theta_j)" pairs with v_k at phi_k - pi/2, the same vector negated (as in
/// Mitsuba 0.5 irrcache.cpp). tan(theta_j) is the ring's mean and v_k the stratum's mean
/// v(phi_c) sin(pi/N) / (pi/N), which makes the sum exact when L is constant per stratum; a ray's
/// own tan(theta) would give an estimator of infinite variance near the horizon.
Gradient rotational_gradient(const std::vector<GatherHit>& hits, int M, int N) {
    const float azimuth_mean = std::sin(pi / float(N)) / (pi / float(N));
    Gradient gradient{};
    for (int k = 0; k < N; ++k) {
        Rgb sum;
        for (int j = 0; j < M; ++j) sum += hits[size_t(j * N + k)].L * ring_mean_tan_theta(j, M);
        const Vec3 v_k = azimuth_vector(2 * pi * (float(k) + 0.5f) / float(N) + pi / 2) * azimuth_mean;
        add_to_gradient(gradient, v_k, sum * (pi / float(M * N)));
    }
    return gradient;
}

/// The distance that moves the edge between two neighbouring strata: the nearer surface's
/// silhouette (Ward & Heckbert 1992). 0 when the edge does not move (both rays escaped).
float inverse_edge_distance(const GatherHit& a, const GatherHit& b) {
    const float distance = std::min(a.distance, b.distance);
    return distance > 0 && distance < infinity ? 1.0f / distance : 0.0f;
}

/// Translational gradient in the local frame, for E(p') ~ E + (p' - p) . grad.
/// Moving p by dx (tangent) turns the direction w to a point at distance R by
/// dw = -(dx - (dx.w) w) / R, so each stratum edge sweeps projected solid angle
/// cos(theta) sin(theta) dtheta dphi from one stratum into its neighbour, and E changes by that
/// area times the difference of their radiances:
///  - the edge between rings j-1 and j of column k turns by dtheta = -cos(theta) (dx.u) / R:
///      u_k * 2 sin(pi/N) * sin(theta_j-) cos^2(theta_j-) / min(R_{j-1,k}, R_jk) * (L_jk - L_{j-1,k});
///  - the edge between columns k-1 and k of ring j (at phi_k- = 2 pi k / N) turns by
///    dphi = -(dx.v) / (R sin(theta)):
///      v_k- * (sin(theta_j+) - sin(theta_j-)) / min(R_{j,k-1}, R_jk) * (L_jk - L_{j,k-1}).
/// Jarosz et al. 2008 write 2 pi / N and cos(theta_j) (cos(theta_j-) - cos(theta_j+)) / sin(theta_j)
/// for the two integrals; these are their midpoint approximations.
Gradient translational_gradient(const std::vector<GatherHit>& hits, int M, int N) {
    const float arc = 2 * std::sin(pi / float(N));
    Gradient gradient{};
    for (int k = 0; k < N; ++k) {
        const int k_prev = (k + N - 1) % N;
        const Vec3 u_k = azimuth_vector(2 * pi * (float(k) + 0.5f) / float(N));
        const Vec3 v_k_minus = azimuth_vector(2 * pi * float(k) / float(N) + pi / 2);
        for (int j = 0; j < M; ++j) {
            const GatherHit& hit = hits[size_t(j * N + k)];
            const float sin_minus = boundary_sin_theta(j, M), sin_plus = boundary_sin_theta(j + 1, M);
            if (j > 0) {
                const GatherHit& below = hits[size_t((j - 1) * N + k)];
                const float cos2_minus = 1 - sin_minus * sin_minus;
                const float weight = arc * sin_minus * cos2_minus * inverse_edge_distance(hit, below);
                add_to_gradient(gradient, u_k, (hit.L - below.L) * weight);
            }
            const GatherHit& left = hits[size_t(j * N + k_prev)];
            const float weight = (sin_plus - sin_minus) * inverse_edge_distance(hit, left);
            add_to_gradient(gradient, v_k_minus, (hit.L - left.L) * weight);
        }
    }
    return gradient;
}

/// Turns each channel's local gradient into world space.
Gradient to_world(const OrthonormalBasis& basis, const Gradient& local) {
    return {basis.to_world(local[0]), basis.to_world(local[1]), basis.to_world(local[2])};
}

}  // namespace

std::vector<Vec3> gather_directions(const GatherSettings& settings, uint64_t seed) {
    const int M = settings.theta_strata, N = settings.phi_strata;
    SL_CHECK(M > 0 && N > 0);
    Pcg32 rng(settings.fixed_directions ? fixed_directions_seed : hash_ids(seed));
    std::vector<Vec3> directions;
    directions.reserve(size_t(M * N));
    for (int j = 0; j < M; ++j) {
        for (int k = 0; k < N; ++k) {
            // Jitter inside stratum (j, k): sin^2(theta) uniform in [j, j+1) / M, phi in [k, k+1) 2 pi / N.
            const Vec2 u = rng.next_vec2();
            const float sin2_theta = (float(j) + u.x) / float(M);
            const float sin_theta = std::sqrt(sin2_theta), cos_theta = std::sqrt(std::max(0.0f, 1 - sin2_theta));
            const float phi = 2 * pi * (float(k) + u.y) / float(N);
            directions.push_back({sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta});
        }
    }
    return directions;
}

GatherResult final_gather(Vec3 p, Vec3 n, Vec3 ng, const std::vector<Vec3>& directions, const GatherSettings& settings,
                          const GatherRadiance& radiance) {
    const int M = settings.theta_strata, N = settings.phi_strata;
    SL_CHECK(M > 0 && N > 0 && directions.size() == size_t(M * N));
    const OrthonormalBasis basis = OrthonormalBasis::from_normal(n);

    // Trace one ray per stratum.
    std::vector<GatherHit> hits(directions.size());
    for (size_t i = 0; i < directions.size(); ++i) hits[i] = radiance(spawn_ray(p, ng, basis.to_world(directions[i])));

    // Sum the radiances (equal projected solid angle per stratum) and the reciprocal distances.
    GatherResult result;
    Rgb sum_L;
    float sum_inverse_distance = 0;
    for (const GatherHit& hit : hits) {
        sum_L += hit.L;
        if (hit.distance < infinity) sum_inverse_distance += 1.0f / hit.distance;
        result.min_distance = std::min(result.min_distance, hit.distance);
    }
    result.rays = M * N;

    // Fill in the record: irradiance, harmonic mean distance (infinite when every ray escaped), gradients.
    IrradianceRecord& record = result.record;
    record.p = p;
    record.n = n;
    record.E = sum_L * (pi / float(M * N));
    record.radius = sum_inverse_distance > 0 ? float(M * N) / sum_inverse_distance : infinity;
    record.rotational_gradient = to_world(basis, rotational_gradient(hits, M, N));
    record.translational_gradient = to_world(basis, translational_gradient(hits, M, N));
    return result;
}

void validate(const GatherSettings& settings, const std::string& where) {
    check_setting_range(where + "/theta_strata", settings.theta_strata, 1, 1 << 12);
    check_setting_range(where + "/phi_strata", settings.phi_strata, 1, 1 << 12);
}

}  // namespace steadylight
