// The ply book: plybook.json and plybook.csv for pipelines, plybook.html for people. The page
// is self-contained: its style inline, each ply's pictures (the SVGs the svg writer made in the
// ply's folder) inline with their ids prefixed by the ply's place so that one page holds them
// all, no script; its only links are to the plies' own files, relative.

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/laminate.hpp>
#include <plyfit/exporters/messages.hpp>
#include <plyfit/exporters/warnings_json.hpp>

#include "render/text.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace plyfit::exporters {

namespace {

using render::fixed_text;
using render::xml_escape;

bool drawn(const PlySheet& p) {
  return p.status == "ok" || p.status == "partial";
}

std::string warning_codes(const PlySheet& p) {
  std::string s;
  for (const auto& w : p.warnings) {
    if (!s.empty()) s += ' ';
    s += to_string(w.code);
  }
  return s;
}

// An SVG file's element, its ids (and the references to them) prefixed; empty when missing.
std::string inline_svg(const fs::path& file, const std::string& prefix) {
  const std::string svg = read_file(file.string()).value_or("");
  const auto start = svg.find("<svg");
  if (start == std::string::npos) return {};
  // Each marker's next place, found again only once passed (one pass over the text).
  const char* markers[] = {"id=\"", "url(#", "href=\"#"};
  std::size_t next[3];
  for (int m = 0; m < 3; ++m) next[m] = svg.find(markers[m], start);
  std::string out;
  out.reserve(svg.size() + svg.size() / 64);
  std::size_t k = start;
  for (;;) {
    const int m = static_cast<int>(std::min_element(next, next + 3) - next);
    if (next[m] == std::string::npos) break;
    const std::size_t end = next[m] + std::char_traits<char>::length(markers[m]);
    out.append(svg, k, end - k);
    out += prefix;
    k = end;
    next[m] = svg.find(markers[m], k);
  }
  out.append(svg, k, std::string::npos);
  return out;
}

const char* kStyle =
    "body{font-family:DejaVu Sans,Verdana,Arial,sans-serif;margin:24px;color:#222}"
    "table{border-collapse:collapse;margin:12px 0}"
    "th,td{border:1px solid #bbb;padding:3px 8px;text-align:left;font-size:13px}"
    "th{background:#eee}td.num{text-align:right}"
    ".status-error,.status-cancelled{color:#b00}.status-partial{color:#a60}"
    "section.ply{border-top:2px solid #888;margin-top:24px}"
    ".pictures{display:flex;flex-wrap:wrap;gap:16px}"
    "figure{margin:0;flex:1 1 420px;max-width:640px}"
    "figure svg{width:100%;height:auto;max-height:640px;border:1px solid #ddd}"
    "figcaption{font-size:12px;color:#555}";

std::string table_row(const PlySheet& p) {
  std::ostringstream o;
  o << "<tr><td class=\"num\">" << p.sequence << "</td><td><a href=\"#ply-" << xml_escape(p.name)
    << "\">" << xml_escape(p.name) << "</a></td><td class=\"num\">"
    << render::degrees_text(p.angle_deg, 2) << "</td><td>" << xml_escape(p.material)
    << "</td><td class=\"status-" << xml_escape(p.status) << "\">" << xml_escape(p.status)
    << (p.error.empty() ? "" : ": " + xml_escape(p.error) + " [" + p.error_code + "]")
    << "</td><td class=\"num\">" << (drawn(p) ? fixed_text(p.flat_area, 1) : "")
    << "</td><td class=\"num\">" << (drawn(p) ? render::degrees_text(p.shear_max_deg, 2) : "")
    << "</td><td>" << xml_escape(warning_codes(p)) << "</td><td>";
  for (const auto& f : p.files)
    o << "<a href=\"" << xml_escape(p.name + "/" + f) << "\">" << xml_escape(f) << "</a> ";
  o << "</td></tr>\n";
  return o.str();
}

// A ply's section: its pictures (flat pattern, shear map, and the 3D view when its folder
// has view.svg) and its warnings.
std::string ply_section(const PlySheet& p, std::size_t k, const std::string& dir) {
  std::ostringstream o;
  o << "<section class=\"ply\" id=\"ply-" << xml_escape(p.name) << "\">\n<h2>" << p.sequence
    << " &#8212; " << xml_escape(p.name) << " (" << render::degrees_text(p.angle_deg, 2) << ", "
    << xml_escape(p.material) << ")</h2>\n<div class=\"pictures\">\n";
  const fs::path folder = fs::path(dir) / p.name;
  bool any = false;
  for (const auto& [file, cls, caption] : {std::tuple{"flat.svg", "flat", "Flat pattern"},
                                           {"shear.svg", "shear", "Shear map"},
                                           {"view.svg", "view3d", "3D view"}}) {
    const std::string svg =
        inline_svg(folder / file, std::string("p").append(std::to_string(k)).append("-"));
    if (svg.empty()) continue;
    any = true;
    o << "<figure class=\"picture " << cls << "\">\n"
      << svg << "<figcaption>" << caption << "</figcaption></figure>\n";
  }
  if (!any)
    o << "<p class=\"no-picture\">No picture: the ply was not draped, or its outputs leave out "
         "svg.</p>\n";
  o << "</div>\n";
  if (!p.pieces.empty()) {
    o << "<p class=\"pieces\">" << p.pieces.size() << " pieces for the roll:";
    for (const auto& q : p.pieces)
      o << " " << xml_escape(q.name) << " (" << fixed_text(q.width, 1) << " mm wide, "
        << fixed_text(q.area, 1) << " mm&#178;)";
    o << "</p>\n";
  }
  for (const auto& w : p.warnings)
    o << "<p class=\"warning\">" << xml_escape(message(w)) << " [" << to_string(w.code)
      << "]</p>\n";
  o << "</section>\n";
  return o.str();
}

// A ply split for its roll: its pieces and its seams with the distances they keep.
void add_pieces(nlohmann::json& j, const PlySheet& p) {
  nlohmann::json pieces = nlohmann::json::array(), seams = nlohmann::json::array();
  for (const auto& q : p.pieces)
    pieces.push_back({{"name", q.name}, {"area_mm2", q.area}, {"width_mm", q.width}});
  for (const auto& s : p.seams)
    seams.push_back(
        {{"x", s.x},
         {"stagger_distance_mm",
          s.stagger_distance < 0 ? nlohmann::json(nullptr) : nlohmann::json(s.stagger_distance)}});
  j["pieces"] = pieces;
  j["seams"] = seams;
  j["splice_stagger_mm"] = p.splice_stagger;
  j["stagger_met"] = p.stagger_met;
}

// The names of a ply's pieces, space-separated (empty: one piece).
std::string piece_names(const PlySheet& p) {
  std::string s;
  for (const auto& q : p.pieces) s += (s.empty() ? "" : " ") + q.name;
  return s;
}

}  // namespace

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string plybook_json(const Plybook& book) {
  nlohmann::json plies = nlohmann::json::array();
  for (const auto& p : book.plies) {
    nlohmann::json files = nlohmann::json::array();
    for (const auto& f : p.files) files.push_back(p.name + "/" + f);
    nlohmann::json ply = {{"sequence", p.sequence},
                          {"name", p.name},
                          {"angle_deg", p.angle_deg},
                          {"material", p.material},
                          {"status", p.status},
                          {"error", p.error},
                          {"error_code", p.error_code},
                          {"flat_area_mm2", p.flat_area},
                          {"shear_max_deg", p.shear_max_deg},
                          {"warnings", warnings_json(p.warnings)},
                          {"files", files}};
    if (!p.pieces.empty()) add_pieces(ply, p);
    plies.push_back(std::move(ply));
  }
  const nlohmann::json j = {{"laminate", book.laminate},
                            {"roll_width_mm", book.roll_width},
                            {"cut_drawing", "cut.dxf"},
                            {"plies", plies}};
  return j.dump(2) + "\n";
}

std::string plybook_csv(const Plybook& book) {
  std::ostringstream o;
  o << "sequence,name,angle_deg,material,status,flat_area_mm2,shear_max_deg,warnings,files,"
       "error,error_code,pieces\n";
  for (const auto& p : book.plies) {
    std::string files;
    for (const auto& f : p.files) {
      if (!files.empty()) files += ' ';
      files += p.name + "/" + f;
    }
    o << p.sequence << "," << csv_field(p.name) << "," << render::exact_text(p.angle_deg) << ","
      << csv_field(p.material) << "," << p.status << ","
      << (drawn(p) ? render::exact_text(p.flat_area) : "") << ","
      << (drawn(p) ? render::exact_text(p.shear_max_deg) : "") << "," << csv_field(warning_codes(p))
      << "," << csv_field(files) << "," << csv_field(p.error) << "," << p.error_code << ","
      << csv_field(piece_names(p)) << "\n";
  }
  return o.str();
}

std::string plybook_html(const Plybook& book, const std::string& dir) {
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>Ply book: "
    << xml_escape(book.laminate) << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n"
    << "<h1>Ply book: " << xml_escape(book.laminate) << "</h1>\n<p>" << book.plies.size()
    << " plies in stacking order; roll width " << fixed_text(book.roll_width, 1)
    << " mm; cut drawing <a href=\"cut.dxf\">cut.dxf</a>; data <a href=\"plybook.json\">"
       "plybook.json</a>, <a href=\"plybook.csv\">plybook.csv</a>.</p>\n"
    << "<table class=\"plies\">\n<thead><tr><th>Seq</th><th>Ply</th><th>Angle</th>"
       "<th>Material</th><th>Status</th><th>Flat area (mm&#178;)</th><th>Max shear</th>"
       "<th>Warnings</th><th>Files</th></tr></thead>\n<tbody>\n";
  for (const auto& p : book.plies) o << table_row(p);
  o << "</tbody>\n</table>\n";
  for (std::size_t k = 0; k < book.plies.size(); ++k) o << ply_section(book.plies[k], k, dir);
  o << "</body>\n</html>\n";
  return o.str();
}

}  // namespace plyfit::exporters
