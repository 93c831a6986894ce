#pragma once
// What plyfit info --neighbours prints: each face of a mold file sewn into one shell, its
// neighbours across shared edges with the crease angle, and its free boundary.

#include <plyfit/kernel/mold.hpp>

#include <iosfwd>
#include <string>
#include <vector>

namespace plyfit::cli {

/// One face's links (indices are the file's).
struct FaceLinks {
  int index = 0;
  struct Neighbour {
    int face = 0;
    double crease_deg = 0.0;  ///< largest over the shared edges between the two faces
  };
  std::vector<Neighbour> neighbours;
  FreeBoundary free;
};

/// The faces' links of a sewn shell, in the shell's order of faces.
std::vector<FaceLinks> face_links(const MoldSurface& shell, const std::vector<int>& source_faces);

/// The links as a table, or (json) as JSON; `warnings` are the sewing's.
void print_links(const std::string& path, const std::vector<FaceLinks>& links,
                 const std::vector<Warning>& warnings, bool json, std::ostream& os);

}  // namespace plyfit::cli
