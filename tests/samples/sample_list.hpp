#pragma once
// The sample molds under samples/molds: built-in mold spec and file stem. Kept in step with
// scripts/make-sample-molds (the test checking the committed files uses this list).

#include <string>
#include <vector>

namespace plyfit::test {

/// One sample mold: `plyfit sample SPEC -o samples/molds/FILE.{step,igs}`.
struct SampleMold {
  std::string spec;  ///< built-in mold or shell, NAME[:k=v,...]
  std::string file;  ///< file stem (also the face name)
};

/// Every sample mold of one face (a built-in mold).
inline const std::vector<SampleMold>& sample_molds() {
  static const std::vector<SampleMold> list = {
      {"sphere-octant:R=20", "sphere-octant"},
      {"revolution-third", "revolution-third"},
      {"cylinder", "cylinder-sector"},
      {"cone", "cone-sector"},
      {"saddle", "saddle"},
      {"hemisphere:R=1", "hemisphere"},
      {"wave", "wave"},
      {"plate:W=100,H=60,hole_r=10,hole_x=50,hole_y=30", "plate-hole"},
      {"dish:R=30,rho=40,hole_r=8", "dish"},
      {"cylinder:angle=360", "tube"},
      {"cylinder:angle=360,window_angle=60,window_height=8", "tube-window"},
  };
  return list;
}

/// Every sample mold of several faces (a built-in shell).
inline const std::vector<SampleMold>& sample_shells() {
  static const std::vector<SampleMold> list = {
      {"sphere-8", "sphere-8"},
      {"cylinder-split:angle=360", "cylinder-split"},
      {"flange-fillet-wall", "flange-fillet-wall"},
  };
  return list;
}

}  // namespace plyfit::test
