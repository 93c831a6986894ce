// The keys of a drape job: each is a flag of plyfit drape (--key) and a scene-file key, listed
// under its section by --dump-scene.

#include "job/drape_job.hpp"
#include "job/materials.hpp"

namespace plyfit::cli {

const OptionTable& drape_options() {
  static const OptionTable list = {
      {"mold", "FILE|builtin:NAME[:k=v,...]", "", "mold file (STEP, IGES) or a built-in mold",
       false, "mold"},
      {"face", "N", "0", "face index in the mold file (see plyfit info)", false, "mold"},
      {"faces", "LIST|all|connected", "",
       "faces to drape as one shell (comma-separated indices, all, or connected: those reached "
       "from the seed's face across edges no sharper than --max-crease), sewn along their shared "
       "edges; instead of --face",
       false, "mold"},
      {"max-crease", "DEG", "60",
       "--faces connected stops at shared edges whose faces' normals turn by more than this, in "
       "(0, 180]",
       false, "mold"},
      {"faces-at", "X,Y,Z", "",
       "drape the face under this point: the face of the mold file nearest to it; instead of "
       "--face",
       false, "mold"},
      {"format", "KEY", "", "importer to use instead of the file extension (step, iges)", false,
       "mold"},
      {"flip-normal", "", "false", "drape on the other side of the surface", false, "mold"},
      {"spacing", "D", "", "thread spacing d (both directions), model units", false, "ply"},
      {"spacing-weft", "D", "", "weft link length (spacing of the warp threads, along x)", false,
       "ply"},
      {"spacing-warp", "D", "", "warp link length (spacing of the weft threads, along y)", false,
       "ply"},
      {"ply", "W,H", "", "cloth rectangle [0,W] x [0,H] (default: unbounded)", false, "ply"},
      {"start2d", "X,Y", "", "start point of the base path in ply coordinates", false, "start"},
      {"base2d", "DX,DY", "", "base path direction in ply coordinates", false, "start"},
      {"sweep2d", "DX,DY", "", "sweep direction in ply coordinates (one per half-plane)", true,
       "start"},
      {"start3d", "X,Y,Z", "", "start point on the mold (projected onto the face)", false, "start"},
      {"base-normal", "NX,NY,NZ", "", "normal of the base plane (through the 3D start)", false,
       "start"},
      {"sweep3d", "DX,DY,DZ", "", "3D sweep direction, paired in order with --sweep2d", true,
       "start"},
      {"seed", "X,Y,Z", "",
       "seed point (projected onto the mold): the ply's origin; the start, base path and sweeps "
       "follow from it, --rosette and --ply-angle (instead of the start keys)",
       false, "start"},
      {"rosette", "DX,DY,DZ", "1,0,0",
       "the 0 deg direction (a translational rosette), projected onto the surface at the seed",
       false, "start"},
      {"seed-curve", "plane|geodesic|FILE[:PICK]", "plane",
       "what the base path follows from the start: the base plane's section, the geodesic "
       "leaving the start along it, or a curve of a file (CSV, STEP, IGES; one curve)",
       false, "start"},
      {"boundary", "FILE[:PICK]", "",
       "the ply's boundary: a CSV of 3D points (one closed loop per block, blank lines "
       "between loops), PICK the loops to use (indices from 0, comma list); the region "
       "holding the seed is draped, inner loops are cut-outs",
       false, "start"},
      {"dart", "FILE[:PICK]", "",
       "a dart: a cut in the ply along a curve on the part (CSV of 3D points or a STEP/IGES "
       "file's curves, each an open curve); links that cross it are not enforced, so the cloth "
       "on its two sides drapes independently (repeatable)",
       true, "start"},
      {"darts", "auto|none", "none",
       "auto: seams cut where fronts of cloth meet and disagree, and where the drape ends at the "
       "shear limit darts from the face's edge into those zones, the ply draped again with them "
       "(at most 3 drapes in all)",
       false, "start"},
      {"boundary-offset", "MM", "0",
       "grow (> 0) or shrink (< 0) the boundary's region along the surface (trim allowance)", false,
       "start"},
      {"material", "NAME", kDefaultMaterial,
       "material from the materials table: its label, warning and limit angles", false, "material"},
      {"materials", "FILE", "", "materials table to use instead of plyfit's (data/materials.ini)",
       false, "material"},
      {"lock-angle", "DEG", "",
       "largest shear (90 - thread angle) the cloth takes (default: the material's limit); 90 = "
       "no limit",
       false, "material"},
      {"warn-angle", "DEG", "",
       "shear above which cells are flagged (default: the material's warning angle, at most "
       "lock angle - 5)",
       false, "material"},
      {"ply-name", "TEXT", "ply", "ply name for labels", false, "material"},
      {"roll-width", "MM", "",
       "split a flat pattern wider than this across the warp into pieces along warp threads "
       "(splices), each no wider (default: the material's roll-width; none: no splices)",
       false, "material"},
      {"splice-overlap", "MM", "0",
       "with --roll-width: each piece left of a seam laps this far over its neighbour (0: a "
       "butt joint)",
       false, "material"},
      {"ply-angle", "DEG", "0",
       "ply angle: the warp turned from the rosette's 0 deg about the outward normal, "
       "counter-clockwise seen from outside (with the start keys, their drape turned by it)",
       false, "material"},
      {"tolerance", "T", "1e-14", "Newton tolerance relative to the spacing (eq. 9)", false,
       "numerics"},
      {"max-iterations", "N", "40", "Newton iteration cap per node", false, "numerics"},
      {"guess", "extrapolated|paper|parallelogram", "extrapolated",
       "initial guess of the two-sphere solver (paper: eqs. 10-11)", false, "numerics"},
      {"max-nodes", "N", "50000000", "stop after reaching this many nodes", false, "numerics"},
      {"output", "DIR", "", "output folder (-o)", false, "output", 'o'},
      {"outputs", "LIST", "", "outputs to write, comma-separated (default: all)", false, "output"},
      {"curve-degree", "1|3", "1", "degree of the thread curves in net.step", false, "output"},
      {"view", "X,Y,Z", "1,1,1", "view direction of drape.svg (towards the viewer)", false,
       "output"},
      {"dxf-threads", "true|false", "false",
       "THREADS layer (thread grid) in flat.dxf (a cutter would cut it)", false, "output"},
      {"min-width", "W", "",
       "cut outline: slivers of cloth and notches narrower than W are cut off or closed, "
       "model units (default: half the spacing; 0: the exact outline)",
       false, "output"},
  };
  return list;
}

}  // namespace plyfit::cli
