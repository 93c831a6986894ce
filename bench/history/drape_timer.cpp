// drape_timer: one line of drape figures for bench/history/compare-commits: the bicubic wave
// and the rational sphere octant of `plyfit-bench throughput` at about 1000^2 nodes, default
// options, built against any commit's kernel (public API only). Prints, per face: ns per
// mapped node (median of RUNS drapes), Newton iterations per solve, and peak heap bytes per
// mapped node (bench/src/memory.cpp's counter, first run). The tests' problem builder is of
// the working tree, as this file is; it uses the public DrapeProblem only.

#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/drape.hpp>
#if __has_include(<plyfit/kernel/face.hpp>)
#include <plyfit/kernel/face.hpp>
#endif

#include "../../tests/support/problems.hpp"
#include "../src/memory.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

using namespace plyfit;
using support::problem;

namespace {

constexpr int kSide = 1000;  // about kSide^2 nodes

// What drape() takes: a MoldSurface since the layout of 0fb5562; before it, the Face itself
// (public then, in face.hpp).
#if __has_include(<plyfit/kernel/face.hpp>)
using Surface = Face;
Surface surface_of(FaceData data) {
  return Face::create(std::move(data)).value();
}
#else
using Surface = MoldSurface;
Surface surface_of(FaceData data) {
  return MoldSurface::from_face(std::move(data)).value();
}
#endif

void measure(const char* name, const Surface& f, const DrapeProblem& pb, int runs) {
  std::vector<double> ns;
  double its = 0, heap = 0;
  for (int k = 0; k < runs; ++k) {
    bench::memory::reset_peak();
    const std::size_t h0 = bench::memory::live_bytes();
    const auto t0 = std::chrono::steady_clock::now();
    auto r = drape(f, pb, {});
    const auto t1 = std::chrono::steady_clock::now();
    if (!r) std::exit(1);
    const double n = static_cast<double>(r->metrics.nodes.mapped + r->metrics.nodes.auxiliary);
    ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / n);
    if (k == 0) {
      its = static_cast<double>(r->metrics.iterations) / static_cast<double>(r->metrics.solves);
      heap = static_cast<double>(bench::memory::peak_bytes() - h0) / n;
    }
  }
  std::nth_element(ns.begin(), ns.begin() + ns.size() / 2, ns.end());
  std::printf("%s %.1f %.3f %.1f ", name, ns[ns.size() / 2], its, heap);
}

}  // namespace

int main(int argc, char** argv) {
  bench::memory::stable_malloc();
  const int runs = argc > 1 ? std::atoi(argv[1]) : 1;
  const Surface wave = surface_of(builtin_mold("wave", {}).value());
  const double dw = std::sqrt(wave.area()) / kSide;
  // The wave's middle sample is its centre (50, 50): the base path along Su = +X there.
  measure("wave", wave,
          problem(dw, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)}, Vec3(50, 50, 0),
                  Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)}),
          runs);
  const double R = 20;
  const Surface octant = surface_of(builtin_mold("sphere-octant", {{"R", R}}).value());
  measure("octant", octant,
          problem(std::sqrt(octant.area()) / kSide, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1)},
                  Vec3(R / 2, 0, R / 2), Vec3(0, 1, 0), {Vec3(0, 1, 0)}),
          runs);
  std::printf("\n");
  return 0;
}
