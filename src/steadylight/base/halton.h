// The scrambled Halton sequence: quasi-random points whose dimension d uses the radical inverse
// in the d-th prime base with a fixed random permutation of the digits (pbrt-v3
// ScrambledRadicalInverse), which removes the correlations plain Halton shows between high
// dimensions. Photon i of every frame uses point i, so a frame's photons depend only on the scene
// at that frame (paper §4).
#pragma once

#include <cstdint>

namespace steadylight {

/// Dimensions available; a caller needing more falls back to a hashed random stream.
constexpr int halton_dimensions = 128;

/// Component `dimension` (< halton_dimensions) of point `index`, in [0, 1).
float halton(int dimension, uint64_t index);

}  // namespace steadylight
