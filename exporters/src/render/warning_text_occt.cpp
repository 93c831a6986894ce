// The text of the OpenCASCADE module's warnings (occt/src): the reader's messages, faces whose
// area falls short of its accuracy, the listing's summary of such faces and what sewing faces
// into a shell found. A face is named with the file's entity that made it, when known.
#include "render/message_text.hpp"

#include <algorithm>
#include <cstdio>
#include <iterator>

namespace plyfit::exporters::render {

namespace {

// Faces in a list of a warning's values, at most this many named.
constexpr std::size_t kListedFaces = 12;

// "face 3 (#120)": face values[k] and the entity values[k + 1] (when not empty).
std::string face_named(const Values& x, std::size_t k) {
  const std::string entity = x.text(k + 1);
  return "face " + x.n(k) + (entity.empty() ? "" : " (" + entity + ")");
}

// "face 3", "faces 0-17", "faces 3, 4, 9-12, ...": the faces values[first..], in order; runs
// of three or more consecutive faces as a range.
std::string face_list(const Values& x, std::size_t first) {
  const std::size_t n = x.v.size();
  std::string s = n == first + 1 ? "face " : "faces ";
  std::size_t k = first;
  for (std::size_t shown = 0; k < n && shown < kListedFaces; ++shown) {
    std::size_t end = k + 1;
    while (end < n && x.count(end) == x.count(end - 1) + 1) ++end;
    if (shown > 0) s += ", ";
    s += x.n(k);
    if (end - k >= 3) s.append("-").append(x.n(end - 1));
    k = end - k >= 3 ? end : k + 1;
  }
  return k < n ? s + ", ..." : s;
}

// "3 edges", "1 edge".
std::string count_of(const Values& x, std::size_t k, const char* noun) {
  return x.n(k) + " " + noun + (x.count(k) == 1 ? "" : "s");
}

// The values from `first` on (a face's note inside a listing's summary).
std::vector<MessageValue> tail(const Values& x, std::size_t first) {
  return {x.v.begin() + static_cast<std::ptrdiff_t>(std::min(first, x.v.size())), x.v.end()};
}

// "12 fails (3x 'A', 1x 'B', ...)": one kind of reader message from values[k] on (its count,
// its kinds, the kinds shown, then (count, text) of each shown); `k` moves past them.
std::string reader_group(const Values& x, std::size_t& k, const char* word) {
  const std::int64_t total = x.count(k), kinds = x.count(k + 1), shown = x.count(k + 2);
  std::string s = x.n(k) + " " + word + (total == 1 ? "" : "s") + " (";
  k += 3;
  for (std::int64_t i = 0; i < shown; ++i, k += 2) {
    if (i > 0) s += ", ";
    s.append(x.n(k)).append("x '").append(x.text(k + 1)).append("'");
  }
  return s + (kinds > shown ? ", ...)" : ")");
}

}  // namespace

// Values: the stage ("load", "transfer"), then the fails and the warnings (reader_group()).
std::string warning_reader_messages(const Values& x) {
  std::size_t k = 1;
  const bool fails = x.count(k) > 0;
  std::string s = x.text(0) + ": ";
  if (fails)
    s += reader_group(x, k, "fail");
  else
    k += 3 + 2 * static_cast<std::size_t>(std::max<std::int64_t>(x.count(k + 2), 0));
  if (x.count(k) > 0) s.append(fails ? ", " : "").append(reader_group(x, k, "warning"));
  return s;
}

// Values: the face, its entity, the relative accuracy asked, the one reached (absent when
// OpenCASCADE's integration measured it: no estimate).
std::string warning_face_area_short(const Values& x) {
  char text[96];
  if (x.v.size() > 3)
    std::snprintf(text, sizeof text, "area to %.1e relative (estimated), not the %.0e asked",
                  x.number(3), x.number(2));
  else
    std::snprintf(text, sizeof text,
                  "area by OpenCASCADE's integration (no pcurves), accuracy unknown");
  return face_named(x, 0) + ": " + text;
}

// Values: the face, its entity, why its area could not be measured.
std::string warning_face_area_unmeasured(const Values& x) {
  return face_named(x, 0) + ": area not measured (" + x.text(2) + "): an invalid face";
}

// Values: the count, then the first face, its entity and why it could not be described (an
// error and its causes: error_chain_text()).
std::string warning_listing_failed_faces(const Values& x) {
  return "listing: " + x.n(0) + " faces could not be described (first: " + face_named(x, 1) + ": " +
         error_chain_text(x, 3) + ")";
}

// Values: the count, then the first face's (face_area_unmeasured).
std::string warning_unmeasured_faces(const Values& x) {
  return "listing: " + x.n(0) + " faces whose area could not be measured (first: " +
         warning_face_area_unmeasured(Values{tail(x, 1)}) + ")";
}

// Values: the count, then the first face's (face_area_short).
std::string warning_short_area_faces(const Values& x) {
  return "listing: " + x.n(0) + " face areas short of the accuracy asked (first: " +
         warning_face_area_short(Values{tail(x, 1)}) + ")";
}

PLYFIT_SENTENCE(warning_separate_shells,
                "sewing: the {n0} faces form {n1} separate shells that no shared edge joins; a "
                "drape stays on the one it starts on");

std::string warning_non_manifold_edges(const Values& x) {
  return "sewing: " + count_of(x, 0, "edge") + (x.count(0) == 1 ? " bounds" : " bound") +
         " more than two faces (non-manifold), treated as free";
}

// Values: the faces reversed.
std::string warning_faces_reoriented(const Values& x) {
  return "sewing: " + face_list(x, 0) + " reversed to orient the shell consistently";
}

std::string warning_shell_not_orientable(const Values& x) {
  return "sewing: " + count_of(x, 0, "shared edge") + (x.count(0) == 1 ? " joins" : " join") +
         " faces oriented against each other (a non-orientable shell)";
}

// Values: the face (-1: none made), the 144's entity (DE), loops dropped, loops it has, the
// widest gap of the dropped loops' model-space curves in mm (0: unknown).
std::string warning_trim_loops_dropped(const Values& x) {
  char gap[96] = "";
  if (x.number(4) > 0.0)
    std::snprintf(gap, sizeof gap, " (its model-space curves leave a gap of %.6g mm)", x.number(4));
  return "trims: " + (x.count(0) >= 0 ? "face " + x.n(0) : std::string("no face")) +
         " (trimmed surface DE " + x.n(1) + "): " + x.n(2) + " of its " + x.n(3) +
         " trim loop(s) could not be read and were dropped" + gap +
         "; the face is listed and draped as its whole surface, untrimmed";
}

}  // namespace plyfit::exporters::render
