#pragma once
// The share of a face the cut ply covers: the flat pattern's outline carried onto the surface
// cell by cell. plyfit optimize's coverage constraint and plyfit compare's best rule.

#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/flat_pattern.hpp>

namespace plyfit::cli {

/// Surface area of the region the flat pattern's outline covers: the integral over the
/// outline of the ratio of surface to flat area, constant per cell of the ply (its four
/// corners' 3D quadrilateral, on the surface extended past the face for corners outside it);
/// the cells the outline cuts count only their part inside it, whatever the grid's position.
/// Over the face's (or shell's) area it is the outline's coverage.
double outline_surface_area(const DrapeResult& res, const FlatPattern& flat);

/// A drape's outline coverage may fall this far (fraction of the face) below the best coverage
/// (at most 1) and still count as covering as much: the 589 drapes of the three sphere-octant
/// samples' searches (d = R/20) that reach the whole face cover 99.70% to 100.21% of it by
/// this measure, at most 0.30% short, with the grid's position against the boundary (by the
/// mapped cells, report.json's coverage, 88.5% to 96.8%).
constexpr double kCoverageSlack = 0.005;

}  // namespace plyfit::cli
