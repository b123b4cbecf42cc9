#include "steadylight/base/halton.h"

#include <algorithm>
#include <array>
#include <vector>

#include "steadylight/base/rng.h"

namespace steadylight {
namespace {

std::array<int, halton_dimensions> first_primes() {
    std::array<int, halton_dimensions> primes{};
    int count = 0;
    for (int n = 2; count < halton_dimensions; ++n) {
        bool prime = true;
        for (int d = 2; d * d <= n && prime; ++d) prime = n % d != 0;
        if (prime) primes[size_t(count++)] = n;
    }
    return primes;
}

/// One fixed digit permutation per dimension, from a fixed seed: the same in every run.
struct Tables {
    std::array<int, halton_dimensions> primes = first_primes();
    std::array<std::vector<uint16_t>, halton_dimensions> permutations;

    Tables() {
        Pcg32 rng(0x5eed'ba11);
        for (int d = 0; d < halton_dimensions; ++d) {
            std::vector<uint16_t>& perm = permutations[size_t(d)];
            perm.resize(size_t(primes[size_t(d)]));
            for (size_t i = 0; i < perm.size(); ++i) perm[i] = uint16_t(i);
            // Fisher-Yates with the deterministic generator.
            for (size_t i = perm.size() - 1; i > 0; --i) std::swap(perm[i], perm[rng.next_u32() % (i + 1)]);
        }
    }
};

const Tables& tables() {
    static const Tables t;
    return t;
}

}  // namespace

float halton(int dimension, uint64_t index) {
    const Tables& t = tables();
    const uint64_t base = uint64_t(t.primes[size_t(dimension)]);
    const std::vector<uint16_t>& perm = t.permutations[size_t(dimension)];
    const double inv_base = 1.0 / double(base);
    double inv_base_n = 1, value = 0;
    while (index > 0) {
        const uint64_t next = index / base;
        inv_base_n *= inv_base;
        value += perm[size_t(index - next * base)] * inv_base_n;
        index = next;
    }
    // The infinitely many leading zero digits map to perm[0] each: a geometric tail.
    value += perm[0] * inv_base_n * inv_base / (1 - inv_base);
    return std::min(float(value), 0x1.fffffep-1f);
}

}  // namespace steadylight
