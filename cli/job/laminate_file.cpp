// read_laminate: a laminate file's sections into one scene (raw values) per ply, in stacking
// order. The scene keys are read by the scene files' own reader (add_scene_key); the laminate
// adds splice-stagger, sequence and angle, and sets each ply's name, angle and output folder.

#include "job/laminate_file.hpp"

#include "job/drape_job.hpp"
#include "job/ini.hpp"
#include "job/scene_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace plyfit::cli {

namespace {

constexpr const char* kLaminateSection = "laminate";
constexpr const char* kPlyPrefix = "ply ";
// The scene keys a laminate sets itself: each ply's output folder and name come from the
// section, its angle from `angle`.
constexpr const char* kSetByLaminate[] = {"output", "ply-name", "ply-angle"};
// Keys that stand for one another: a ply section giving one of a group drops the laminate's
// others (a ply's `faces` replaces the laminate's `face`, its start keys the laminate's seed).
const std::vector<std::vector<std::string>> kAlternatives = {
    {"face", "faces", "faces-at"},
    {"seed", "start3d", "base2d", "sweep2d", "base-normal", "sweep3d"},
    {"spacing", "spacing-weft", "spacing-warp"}};
// Largest sequence number.
constexpr long kMaxSequence = 1L << 30;

// A section of the file being read: its origin in messages and its keys.
struct Section {
  std::string name;       ///< empty for [laminate]
  std::string origin;     ///< "FILE [laminate]" or "FILE [ply NAME]"
  RawOptions scene, own;  ///< scene keys; laminate keys (laminate_keys())
  int line = 0;
};

bool is_laminate_key(const std::string& key) {
  const auto& t = laminate_keys();
  return std::any_of(t.begin(), t.end(), [&](const OptionSpec& s) { return s.key == key; });
}

// Ply names become folder and DXF layer names: letters, digits, '-', '_' and '.', not first.
bool valid_ply_name(const std::string& name) {
  if (name.empty() || name.front() == '.' || name.size() > 64) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
  });
}

Error placed(Error e, const std::string& path, int line) {
  e.where = ini_place(path, line);
  return e;
}

// An error of a laminate key, blaming it as its section's key.
Error in_section(Error e, const std::string& origin) {
  if (!e.input.empty()) e.input = origin + ": key '" + e.input + "'";
  return e;
}

// A [section] line: [laminate] once, then [ply NAME] with a new valid name.
Result<Section> open_section(const IniLine& l, const std::string& path,
                             const std::vector<Section>& plies, bool laminate_seen) {
  Section s;
  s.line = l.line;
  if (l.section == kLaminateSection && !laminate_seen && plies.empty()) {
    s.origin = path + " [laminate]";
    return s;
  }
  if (l.section.rfind(kPlyPrefix, 0) != 0)
    return placed(Error{ErrorCode::kLaminateSection, "", {l.section}}, path, l.line);
  s.name = l.section.substr(std::string(kPlyPrefix).size());
  s.name.erase(0, s.name.find_first_not_of(' '));
  if (!valid_ply_name(s.name))
    return placed(Error{ErrorCode::kPlyNameInvalid, "", {s.name}}, path, l.line);
  for (const auto& p : plies)
    if (p.name == s.name)
      return placed(Error{ErrorCode::kPlyRepeated, "", {s.name, static_cast<std::int64_t>(p.line)}},
                    path, l.line);
  s.origin = ply_origin(path, s.name);
  return s;
}

// A key = value line into its section: a laminate key where it belongs, or a scene key.
Status add_line(const IniLine& l, const std::string& path, const std::string& dir, Section& s) {
  const bool in_ply = !s.name.empty();
  for (const char* k : kSetByLaminate)
    if (l.key == k) return placed(Error{ErrorCode::kKeyNotInLaminate, "", {l.key}}, path, l.line);
  if (is_laminate_key(l.key)) {
    const bool ply_key = l.key == "sequence";
    const bool both = l.key == "angle";
    if (!both && ply_key != in_ply)
      return placed(Error{ErrorCode::kKeyNotInLaminate, "", {l.key}}, path, l.line);
    auto& vals = s.own.values[l.key];
    if (!vals.empty()) return in_section(Error{ErrorCode::kOptionRepeated, l.key}, s.origin);
    vals.push_back(l.value);
    s.own.origins[l.key] = s.origin;
    return ok_status();
  }
  IniLine key_only = l;
  key_only.section.clear();
  return add_scene_key(key_only, path, dir, s.scene, s.origin);
}

// The file's sections: [laminate] (optional, first) and the [ply NAME] sections in file order.
Result<std::pair<Section, std::vector<Section>>> read_sections(const std::string& path) {
  auto lines = read_scene_lines(path);
  if (!lines) return lines.error();
  const std::string dir = fs::absolute(fs::path(path)).parent_path().string();
  Section laminate;
  laminate.origin = path + " [laminate]";
  std::vector<Section> plies;
  Section* current = nullptr;
  bool laminate_seen = false;
  for (const IniLine& l : *lines) {
    if (l.is_section) {
      auto s = open_section(l, path, plies, laminate_seen);
      if (!s) return s.error();
      if (s->name.empty()) {
        laminate = std::move(s).value();
        laminate_seen = true;
        current = &laminate;
      } else {
        plies.push_back(std::move(s).value());
        current = &plies.back();
      }
    } else if (!current) {
      return placed(Error{ErrorCode::kLaminateSection, "", {std::string()}}, path, l.line);
    } else if (auto st = add_line(l, path, dir, *current); !st) {
      return st.error();
    }
  }
  if (plies.empty()) {
    Error e{ErrorCode::kLaminateNoPlies};
    e.where = path;
    return e;
  }
  return std::pair{std::move(laminate), std::move(plies)};
}

// A ply's scene: the laminate's keys overridden by its own; its name, angle and output folder.
LaminatePly make_ply(const Section& laminate, const Section& s, const std::string& outdir,
                     long sequence) {
  LaminatePly p;
  p.name = s.name;
  p.sequence = sequence;
  RawOptions over = s.scene;
  over.origin = s.origin;
  RawOptions base = laminate.scene;
  for (const auto& group : kAlternatives)
    for (const auto& key : group)
      if (over.values.count(key))
        for (const auto& other : group)
          if (!over.values.count(other)) base.values.erase(other);
  p.raw = merge(base, over);
  p.raw.origin = s.origin;
  const Section& angle_from = s.own.values.count("angle") ? s : laminate;
  if (const auto a = angle_from.own.values.find("angle"); a != angle_from.own.values.end()) {
    p.raw.values["ply-angle"] = a->second;
    p.raw.origins["ply-angle"] = angle_from.origin;
  }
  p.raw.values["ply-name"] = {s.name};
  p.raw.values["output"] = {(fs::path(outdir) / s.name).string()};
  for (const char* k : {"ply-name", "output"}) p.raw.origins[k] = kCommandLine;
  return p;
}

}  // namespace

const OptionTable& laminate_keys() {
  static const OptionTable table = {
      {"splice-stagger", "MM", "0",
       "[laminate]: seams of plies of one fibre direction (angle mod 180) keep at least this "
       "far apart on the part, mm (plies with roll-width)"},
      {"sequence", "N", "",
       "[ply NAME]: the ply's place in the stack (plies are stacked by it; default: the "
       "previous ply's plus 1, the first 1)"},
      {"angle", "DEG", "0",
       "the ply angle from the rosette, degrees (a ply's own, or in [laminate] the default)"},
  };
  return table;
}

std::string ply_origin(const std::string& path, const std::string& name) {
  return path + " [ply " + name + "]";
}

Result<Laminate> read_laminate(const std::string& path, const std::string& outdir) {
  auto sections = read_sections(path);
  if (!sections) return sections.error();
  const auto& [laminate, plies] = *sections;
  Laminate lam;
  lam.path = path;
  // The roll: the plies' roll-width scene key, given in [laminate], is also the cut drawing's.
  const Options ls(laminate.scene, drape_options());
  if (ls.given("roll-width")) {
    auto roll =
        ls.number_in("roll-width", Range{0.0, std::numeric_limits<double>::infinity(), true});
    if (!roll) return in_section(roll.error(), laminate.origin);
    lam.roll_width = *roll;
  }
  const Options lo(laminate.own, laminate_keys());
  auto stagger = lo.number("splice-stagger");
  if (!stagger) return in_section(stagger.error(), laminate.origin);
  if (!(*stagger >= 0.0))
    return in_section(Error{ErrorCode::kSpliceStaggerNegative, "splice-stagger", {*stagger}},
                      laminate.origin);
  lam.splice_stagger = *stagger;
  std::set<long> taken;
  long previous = 0;
  for (const Section& s : plies) {
    const Options po(s.own, laminate_keys());
    long seq = previous + 1;
    if (po.given("sequence")) {
      auto n = po.integer("sequence", 0, kMaxSequence);
      if (!n) return in_section(n.error(), s.origin);
      seq = *n;
    }
    if (!taken.insert(seq).second)
      return in_section(Error{ErrorCode::kSequenceRepeated, "sequence", {std::int64_t{seq}}},
                        s.origin);
    previous = seq;
    lam.plies.push_back(make_ply(laminate, s, outdir, seq));
  }
  std::stable_sort(
      lam.plies.begin(), lam.plies.end(),
      [](const LaminatePly& a, const LaminatePly& b) { return a.sequence < b.sequence; });
  return lam;
}

}  // namespace plyfit::cli
