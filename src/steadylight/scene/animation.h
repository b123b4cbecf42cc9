// Keyframe animation: tracks of translation, rotation and scale, and the placement of an object
// or camera as translation * rotation * scale whose parts are either fixed or keyframed (the glTF
// node model); tracks of colours animate emission and lamp intensity. Time is in seconds; frame f
// of a scene is shown at time f / fps.
#pragma once

#include <optional>
#include <vector>

#include "steadylight/base/color.h"
#include "steadylight/base/transform.h"

namespace steadylight {

enum class Interpolation { linear, step, cubic_spline };

/// Keyframes of one quantity. For cubic_spline, `values` holds three entries per key (in-tangent,
/// value, out-tangent) as in glTF; otherwise one. Rotations interpolate by slerp when linear.
template <class T>
struct Track {
    Interpolation interpolation = Interpolation::linear;
    std::vector<float> times;  // seconds, strictly increasing
    std::vector<T> values;

    /// The value at `time_s`, clamped to the first and last key outside their range.
    T evaluate(float time_s) const;
    /// True when every key holds the same value, so the track does not move anything.
    bool is_constant() const;
};

/// A placement whose translation, rotation and scale may each be animated.
struct AnimatedTrs {
    Vec3 translation;
    Quat rotation;
    Vec3 scale{1, 1, 1};
    std::optional<Track<Vec3>> translation_track;
    std::optional<Track<Quat>> rotation_track;
    std::optional<Track<Vec3>> scale_track;

    Transform evaluate(float time_s) const;
    bool is_animated() const;
    /// The last key time of any track (0 when nothing is animated).
    float duration_s() const;
};

/// The product of a chain of placements, parent first: a glTF node and its ancestors, or the one
/// placement of a JSON object.
Transform evaluate_chain(const std::vector<AnimatedTrs>& chain, float time_s);
bool is_chain_animated(const std::vector<AnimatedTrs>& chain);
/// True when some placement of the chain has a scale track that changes.
bool is_chain_scaled(const std::vector<AnimatedTrs>& chain);

}  // namespace steadylight
