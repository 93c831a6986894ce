#include "report/compare_report.hpp"

#include "commands/commands.hpp"
#include "report/text_format.hpp"

#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/optimize.hpp>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace plyfit::cli {

const std::vector<Criterion>& criteria() {
  static const std::vector<Criterion> list = {
      {"area", "area (mesh points)", Mark::kSmaller, true, 0},
      {"flat_area", "flat area", Mark::kSmaller, false, 2},
      {"gamma_min_deg", "gamma min (deg)", Mark::kLarger, false, 3},
      {"gamma_max_deg", "gamma max (deg)", Mark::kSmaller, false, 3},
      {"shear_max_deg", "max shear (deg)", Mark::kSmaller, false, 3},
      {"energy", "energy sum cos^2", Mark::kSmaller, false, 3},
      {"paper_gamma_min_deg", "paper gamma min (deg)", Mark::kLarger, false, 3},
      {"paper_gamma_max_deg", "paper gamma max (deg)", Mark::kSmaller, false, 3},
      {"paper_shear_max_deg", "paper max shear (deg)", Mark::kSmaller, false, 3},
      {"paper_energy", "paper energy", Mark::kSmaller, false, 3},
      {"coverage_pct", "cell coverage (%)", Mark::kNone, false, 2},
      {"outline_coverage_pct", "outline coverage (%)", Mark::kCovers, false, 2},
      {"shear_limit", "shear-limit stops", Mark::kSmaller, true, 0},
  };
  return list;
}

/// Index of the column `key` in criteria().
std::size_t column(const std::string& key) {
  for (std::size_t c = 0; c < criteria().size(); ++c)
    if (criteria()[c].key == key) return c;
  throw std::logic_error("no compare column " + key);
}

namespace {

/// Two figures closer than this (relative to the larger) tie: both are marked best. Counts
/// tie only when equal.
constexpr double kTieRel = 1e-9;

bool ties(double a, double b, bool count) {
  if (count) return a == b;
  return std::abs(a - b) <= kTieRel * std::max(std::abs(a), std::abs(b));
}

/// The marking rule, as the legends state it.
const char* const kRule =
    "best in its column among the compared scenes: those whose drape is ok (not partial) and "
    "whose flat pattern's outline covers the face as well as the best, within 0.5% (all marked "
    "in the outline coverage column); smallest area, flat area, gamma max, max shear, energy "
    "(ours and the paper's) and shear-limit stops; largest gamma min (ours and the paper's); "
    "ties within 1e-9 relative are all marked; the cell coverage is shown, not compared";

std::string cell(const Row& r, std::size_t c) {
  return fixed(r.values[c], criteria()[c].digits);
}

// The scenes that failed, the partial ones with their warnings, and those that cover less.
void print_notes(const std::vector<Row>& rows, std::ostream& os) {
  for (const auto& r : rows) {
    if (!r.ok) {
      os << r.name << ": error: " << error_line(r.error, r.error_code) << "\n";
    } else if (r.partial) {
      os << r.name << ": partial, not compared";
      if (!r.warnings.empty()) os << ": " << exporters::messages(r.warnings);
      os << "\n";
    } else if (!r.compared) {
      os << r.name << ": not compared: its outline covers "
         << fixed(r.values[column("outline_coverage_pct")], 2)
         << "% of the face, more than 0.5% less than the best\n";
    }
  }
}

}  // namespace

// The rule: a scene competes for best only when its drape is ok (not partial) and its flat
// pattern's outline covers at least the largest such coverage among the ok scenes (at most the
// whole face) less kCoverageSlack: a fitting that covers less of the face never wins by the
// figures it leaves out (fewer nodes, less energy, less area).
void mark_best(std::vector<Row>& rows) {
  const std::size_t cov = column("outline_coverage_pct");
  double top = -1.0;  // percent
  for (const auto& r : rows)
    if (r.ok && !r.partial) top = std::max(top, r.values[cov]);
  const double floor = std::min(top, 100.0) - 100.0 * kCoverageSlack;
  for (auto& r : rows) {
    r.best.assign(criteria().size(), false);
    r.compared = r.ok && !r.partial && r.values[cov] >= floor;
  }
  for (std::size_t c = 0; c < criteria().size(); ++c) {
    const Criterion& k = criteria()[c];
    if (k.mark == Mark::kNone) continue;
    if (k.mark == Mark::kCovers) {
      for (auto& r : rows) r.best[c] = r.compared;
      continue;
    }
    bool any = false;
    double best = 0.0;
    for (const auto& r : rows) {
      if (!r.compared) continue;
      const double v = r.values[c];
      if (!any || (k.mark == Mark::kLarger ? v > best : v < best)) best = v;
      any = true;
    }
    for (auto& r : rows)
      if (r.compared && ties(r.values[c], best, k.count)) r.best[c] = true;
  }
}

void print_compare_text(const std::vector<Row>& rows, std::ostream& os) {
  std::vector<std::vector<std::string>> t;
  std::vector<std::string> head = {"scene"};
  for (const auto& k : criteria()) head.push_back(k.header);
  t.push_back(head);
  for (const auto& r : rows) {
    std::vector<std::string> line = {r.name};
    for (std::size_t c = 0; c < criteria().size(); ++c)
      line.push_back(r.ok ? cell(r, c) + (r.best[c] ? " *" : "  ") : "-");
    t.push_back(line);
  }
  std::vector<std::size_t> w(head.size(), 0);
  for (const auto& line : t)
    for (std::size_t c = 0; c < line.size(); ++c) w[c] = std::max(w[c], line[c].size());
  for (const auto& line : t) {
    std::string s;
    for (std::size_t c = 0; c < line.size(); ++c) {
      std::string v = line[c];
      // Scene names left-aligned, figures right-aligned.
      if (c == 0)
        v += std::string(w[c] - v.size(), ' ');
      else
        v = std::string(w[c] - v.size(), ' ') + v;
      s += (c ? "  " : "") + v;
    }
    os << s << "\n";
  }
  print_notes(rows, os);
  os << "* " << kRule << "\n";
}

void print_compare_markdown(const std::vector<Row>& rows, std::ostream& os) {
  os << "| scene |";
  for (const auto& k : criteria()) os << " " << k.header << " |";
  os << "\n|---|";
  for (std::size_t c = 0; c < criteria().size(); ++c) os << "---:|";
  os << "\n";
  for (const auto& r : rows) {
    os << "| " << r.name << " |";
    for (std::size_t c = 0; c < criteria().size(); ++c) {
      if (!r.ok)
        os << " error |";
      else if (r.best[c])
        os << " **" << cell(r, c) << "** |";
      else
        os << " " << cell(r, c) << " |";
    }
    os << "\n";
  }
  os << "\n";
  print_notes(rows, os);
  os << "\nIn bold: " << kRule << ".\n";
}

void print_compare_csv(const std::vector<Row>& rows, std::ostream& os) {
  os << "scene,status";
  for (const auto& k : criteria()) os << "," << k.key;
  os << ",best,note\n";
  for (const auto& r : rows) {
    os << r.name << "," << (!r.ok ? "error" : r.partial ? "partial" : "ok");
    std::string best;
    for (std::size_t c = 0; c < criteria().size(); ++c) {
      if (!r.ok) {
        os << ",";
        continue;
      }
      std::ostringstream v;
      v.precision(17);
      v << r.values[c];
      os << "," << v.str();
      if (r.best[c]) best += (best.empty() ? "" : ";") + criteria()[c].key;
    }
    // The note: the error, or a partial drape's warnings.
    std::string note = r.error.empty() ? "" : error_line(r.error, r.error_code);
    for (const auto& w : r.warnings)
      if (r.partial) note += (note.empty() ? "" : "; ") + exporters::message(w);
    for (char& ch : note)
      if (ch == '"') ch = '\'';
    os << "," << best << "," << (note.empty() ? "" : "\"" + note + "\"") << "\n";
  }
}

}  // namespace plyfit::cli
