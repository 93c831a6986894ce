#pragma once
// Small helpers shared by the tests: deterministic random numbers and tolerances named after
// what they compare.

#include <plyfit/kernel/types.hpp>

#include <cstdint>
#include <random>

namespace plyfit::test {

/// Deterministic generator so that every run draws the same cases.
struct Rng {
  std::mt19937_64 gen;
  explicit Rng(uint64_t seed = 12345) : gen(seed) {}
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(gen); }
  int integer(int a, int b) { return std::uniform_int_distribution<int>(a, b)(gen); }
};

/// Round-off level for exact constructions: a few hundred ulps of the quantities compared.
constexpr double kRoundoffRel = 1e-13;

}  // namespace plyfit::test
