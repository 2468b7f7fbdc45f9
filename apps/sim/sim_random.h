// The simulator's random numbers: std::mt19937 for the raw 32-bit stream (its output is fixed by
// the C++ standard) and our own uniform and Gaussian on top of it, so a seed gives the same scene
// and the same noise with every standard library (std::*_distribution is implementation-defined).
#pragma once
#include <cmath>
#include <cstdint>
#include <random>

namespace lpir {

class SimRandom {
 public:
  explicit SimRandom(uint32_t seed) : engine_(seed) {}

  // Uniform in the open interval (0, 1): (k + 0.5) / 2^32 for a raw draw k.
  double Uniform() { return (static_cast<double>(engine_()) + 0.5) * (1.0 / 4294967296.0); }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  bool Chance(double p) { return Uniform() < p; }
  // Standard normal by Box-Muller from two uniforms (the second variate is discarded, so every
  // call consumes exactly two raw draws).
  double Normal() {
    const double u1 = Uniform();
    const double u2 = Uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

 private:
  std::mt19937 engine_;
};

}  // namespace lpir
