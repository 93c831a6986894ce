// The private basis routines (kernel/src/bspline_basis.hpp): the fixed-degree kernels must give
// the same bits as the run-time-degree one, and the branch-free span search the same span as
// a plain scan.

#include <catch2/catch.hpp>

#include "geometry/bspline_basis.hpp"
#include "test_util.hpp"

#include <cstring>
#include <vector>

using plyfit::test::Rng;
namespace detail = plyfit::detail;

namespace {

// Random knot vector with repeated knots (multiplicities 1..degree + 1).
std::vector<double> random_knots(Rng& rng, int count, int degree) {
  std::vector<double> k;
  double x = rng.uniform(-2.0, 2.0);
  while (static_cast<int>(k.size()) < count + degree + 1) {
    const int mult = rng.integer(1, degree + 1);
    for (int m = 0; m < mult && static_cast<int>(k.size()) < count + degree + 1; ++m)
      k.push_back(x);
    x += rng.uniform(0.01, 2.0);
  }
  return k;
}

// The span by definition: the last span of positive length in [first, last] with U[s] <= u,
// clamped to [first, last].
int span_by_scan(const double* U, int first, int last, double u) {
  int s = first;
  for (int i = first; i <= last; ++i)
    if (U[i] < U[i + 1] && U[i] <= u) s = i;
  return s;
}

template <int ND, int P>
void check_same_bits(Rng& rng) {
  for (int trial = 0; trial < 50; ++trial) {
    const int count = P + 1 + rng.integer(0, 8);
    const auto k = random_knots(rng, count, P);
    int first = 0, last = 0;
    detail::span_range(k.data(), count - 1, P, first, last);
    if (!(k[first] < k[last + 1])) continue;  // empty domain
    for (int s = 0; s < 20; ++s) {
      const double u = rng.uniform(k[first] - 0.5, k[last + 1] + 0.5);
      const int span = detail::find_span(k.data(), first, last, u);
      REQUIRE(span == span_by_scan(k.data(), first, last, u));
      double fixed[ND + 1][detail::kMaxBasis] = {}, generic[ND + 1][detail::kMaxBasis] = {};
      detail::ders_basis<ND, P>(k.data(), span, P, u, fixed);
      detail::ders_basis<ND>(k.data(), span, P, u, generic);
      for (int d = 0; d <= ND; ++d)
        CHECK(std::memcmp(fixed[d], generic[d], sizeof(double) * (P + 1)) == 0);
    }
  }
}

// check_same_bits at degree P for the derivative orders the kernels call it with (the point
// alone only up to cubic).
template <int P>
void check_degree(Rng& rng) {
  if constexpr (P <= 3) check_same_bits<0, P>(rng);
  check_same_bits<1, P>(rng);
  check_same_bits<2, P>(rng);
}

}  // namespace

TEST_CASE("kernel: fixed-degree basis routines give the same bits as the generic one") {
  Rng rng(31);
  check_degree<1>(rng);
  check_degree<2>(rng);
  check_degree<3>(rng);
  check_degree<4>(rng);
  check_degree<5>(rng);
}

TEST_CASE("kernel: the first-derivative basis matches the general A2.3 recurrence") {
  // ders_basis<1> has its own first-derivative loop; it must agree with the first row of
  // ders_basis<2>, which runs the general A2.3 recurrence, to the last bit.
  Rng rng(32);
  for (int trial = 0; trial < 200; ++trial) {
    const int p = rng.integer(1, 25);
    const int count = p + 1 + rng.integer(0, 6);
    const auto k = random_knots(rng, count, p);
    int first = 0, last = 0;
    detail::span_range(k.data(), count - 1, p, first, last);
    if (!(k[first] < k[last + 1])) continue;
    const double u = rng.uniform(k[first], k[last + 1]);
    const int span = detail::find_span(k.data(), first, last, u);
    double d1[2][detail::kMaxBasis] = {}, d2[3][detail::kMaxBasis] = {};
    detail::ders_basis<1>(k.data(), span, p, u, d1);
    detail::ders_basis<2>(k.data(), span, p, u, d2);
    INFO("degree " << p);
    CHECK(std::memcmp(d1[0], d2[0], sizeof(double) * (p + 1)) == 0);
    CHECK(std::memcmp(d1[1], d2[1], sizeof(double) * (p + 1)) == 0);
  }
}
