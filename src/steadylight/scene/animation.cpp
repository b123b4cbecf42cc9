#include "steadylight/scene/animation.h"

#include <algorithm>

namespace steadylight {
namespace {

Vec3 mix(Vec3 a, Vec3 b, float t) { return lerp(a, b, t); }
Quat mix(Quat a, Quat b, float t) { return slerp(a, b, t); }
Rgb mix(Rgb a, Rgb b, float t) { return a * (1 - t) + b * t; }

/// Vectors and colours: the cubic Hermite basis, component by component.
template <class T>
T hermite(T p0, T m0, T p1, T m1, float t) {
    const float t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * p1 + (t3 - t2) * m1;
}

Quat hermite(Quat p0, Quat m0, Quat p1, Quat m1, float t) {
    // glTF: cubic-spline rotations are interpolated component-wise, then normalised.
    const Vec3 xyz =
        hermite(Vec3{p0.x, p0.y, p0.z}, Vec3{m0.x, m0.y, m0.z}, Vec3{p1.x, p1.y, p1.z}, Vec3{m1.x, m1.y, m1.z}, t);
    const float t2 = t * t, t3 = t2 * t;
    const float w =
        (2 * t3 - 3 * t2 + 1) * p0.w + (t3 - 2 * t2 + t) * m0.w + (-2 * t3 + 3 * t2) * p1.w + (t3 - t2) * m1.w;
    return normalize(Quat{xyz.x, xyz.y, xyz.z, w});
}

Vec3 scaled(Vec3 v, float s) { return v * s; }
Quat scaled(Quat q, float s) { return {q.x * s, q.y * s, q.z * s, q.w * s}; }
Rgb scaled(Rgb c, float s) { return c * s; }

}  // namespace

template <class T>
T Track<T>::evaluate(float time_s) const {
    const bool cubic = interpolation == Interpolation::cubic_spline;
    const auto value = [&](size_t key) { return values[cubic ? 3 * key + 1 : key]; };
    if (time_s <= times.front()) return value(0);
    if (time_s >= times.back()) return value(times.size() - 1);
    // Find the key interval [k, k+1] holding time_s.
    const size_t k = size_t(std::upper_bound(times.begin(), times.end(), time_s) - times.begin()) - 1;
    const float dt = times[k + 1] - times[k];
    const float t = (time_s - times[k]) / dt;
    switch (interpolation) {
        case Interpolation::step:
            return value(k);
        case Interpolation::linear:
            return mix(value(k), value(k + 1), t);
        case Interpolation::cubic_spline:
            return hermite(value(k), scaled(values[3 * k + 2], dt), value(k + 1), scaled(values[3 * (k + 1)], dt), t);
    }
    return value(k);
}

template <class T>
bool Track<T>::is_constant() const {
    if (interpolation != Interpolation::cubic_spline)
        return std::all_of(values.begin(), values.end(), [&](const T& v) { return v == values[0]; });
    // A cubic spline stands still when all its values agree and all its tangents vanish.
    for (size_t i = 0; i < values.size(); ++i) {
        const bool is_tangent = i % 3 != 1;
        if (is_tangent ? !(scaled(values[i], 0.0f) == values[i]) : !(values[i] == values[1])) return false;
    }
    return true;
}

template struct Track<Vec3>;
template struct Track<Quat>;
template struct Track<Rgb>;

Transform AnimatedTrs::evaluate(float time_s) const {
    const Vec3 t = translation_track ? translation_track->evaluate(time_s) : translation;
    const Quat r = rotation_track ? rotation_track->evaluate(time_s) : rotation;
    const Vec3 s = scale_track ? scale_track->evaluate(time_s) : scale;
    return Transform::from_trs(t, r, s);
}

bool AnimatedTrs::is_animated() const {
    return (translation_track && !translation_track->is_constant()) ||
           (rotation_track && !rotation_track->is_constant()) || (scale_track && !scale_track->is_constant());
}

float AnimatedTrs::duration_s() const {
    float d = 0;
    if (translation_track) d = std::max(d, translation_track->times.back());
    if (rotation_track) d = std::max(d, rotation_track->times.back());
    if (scale_track) d = std::max(d, scale_track->times.back());
    return d;
}

Transform evaluate_chain(const std::vector<AnimatedTrs>& chain, float time_s) {
    Transform world_from_local;
    for (const AnimatedTrs& node : chain) world_from_local = world_from_local * node.evaluate(time_s);
    return world_from_local;
}

bool is_chain_scaled(const std::vector<AnimatedTrs>& chain) {
    return std::any_of(chain.begin(), chain.end(),
                       [](const AnimatedTrs& n) { return n.scale_track && !n.scale_track->is_constant(); });
}

bool is_chain_animated(const std::vector<AnimatedTrs>& chain) {
    return std::any_of(chain.begin(), chain.end(), [](const AnimatedTrs& n) { return n.is_animated(); });
}

}  // namespace steadylight
