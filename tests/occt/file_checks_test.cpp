// Numbers a reader would take in silently and choke on later (occt/src/file_checks.hpp):
// non-finite or absurd numbers in a geometric entity and STEP lists nested too deep are errors
// naming the file and the entity (STEP #id, IGES DE number) when the file is read. The files
// are plyfit's sample molds with one value changed.

#include <plyfit/importers/importers.hpp>

#include <catch2/catch.hpp>

#include "occt/error_checks.hpp"

#include <array>
#include <regex>

using namespace plyfit;
using namespace plyfit::test;

namespace {

// The text of STEP entity `id` ("#78"): from its name to its closing ';'.
std::pair<size_t, size_t> step_entity(const std::string& s, const std::string& id) {
  const std::regex name("(^|\\n)" + id + "\\s*=");
  std::smatch m;
  REQUIRE(std::regex_search(s, m, name));
  const size_t a = static_cast<size_t>(m.position(0)) + m.length(1);
  return {a, s.find(';', a)};
}

// `s` with the k-th number (0-based) of STEP entity `id` replaced by `value` (or, with
// `wrap`, by `wrap` times '(' + the number + ')').
std::string step_with(std::string s, const std::string& id, int k, const std::string& value,
                      int wrap = 0) {
  const auto [a, b] = step_entity(s, id);
  const std::regex number("[(,\\s]([-+]?[0-9]+\\.?[0-9]*(E[-+]?[0-9]+)?)(?=[,)\\s])");
  auto it = std::sregex_iterator(s.begin() + static_cast<long>(s.find('=', a)),
                                 s.begin() + static_cast<long>(b), number);
  for (int i = 0; i < k; ++i) ++it;
  REQUIRE(it != std::sregex_iterator());
  const size_t at = static_cast<size_t>(it->position(1)) + s.find('=', a);
  const size_t len = static_cast<size_t>(it->length(1));
  const std::string old = s.substr(at, len);
  s.replace(at, len,
            wrap ? std::string(static_cast<size_t>(wrap), '(') + old +
                       std::string(static_cast<size_t>(wrap), ')')
                 : value);
  return s;
}

// `s` with field k of the parameters of IGES directory entry `de` (field 0: the entity type)
// replaced by `value`, the 80-column records kept.
std::string iges_with(std::string s, int de, int k, const std::string& value) {
  size_t pos = 0;
  int field = 0;
  while (pos < s.size()) {
    const size_t eol = s.find('\n', pos);
    REQUIRE(eol != std::string::npos);
    if (eol - pos >= 73 && s[pos + 72] == 'P' && std::stoi(s.substr(pos + 64, 8)) == de) {
      std::string data = s.substr(pos, 64);
      size_t start = 0;
      for (size_t i = 0; i < data.size(); ++i) {
        if (data[i] != ',' && data[i] != ';') continue;
        if (field++ == k) {
          data.replace(start, i - start, value);
          while (!data.empty() && data.back() == ' ') data.pop_back();
          REQUIRE(data.size() <= 64);
          s.replace(pos, 64, data + std::string(64 - data.size(), ' '));
          return s;
        }
        start = i + 1;
      }
    }
    pos = eol + 1;
  }
  FAIL("no field " << k << " in DE " << de);
  return s;
}

// Field index of the first pole's x of an IGES 128 entity (K1, K2, M1, M2 its fields 1-4).
int first_pole_field(int k1, int k2, int m1, int m2) {
  const int knots_u = (1 + k1 - m1) + 2 * m1 + 1, knots_v = (1 + k2 - m2) + 2 * m2 + 1;
  return 10 + knots_u + knots_v + (k1 + 1) * (k2 + 1);
}

// Opening `path` fails with one line naming the file and, as the error's place, `entity`;
// its code is one of the number checks' (a STEP reader takes INF for a word, not a number).
void rejected(const std::string& path, const std::string& entity) {
  auto r = importers::open_mold(path);
  REQUIRE_FALSE(r.ok());
  check_error(r.error(), path);
  INFO(exporters::describe(r.error()));
  const ErrorCode c = r.error().code;
  CHECK((c == ErrorCode::kFileNumberNotFinite || c == ErrorCode::kFileNumberTooLarge ||
         c == ErrorCode::kStepWordForNumber));
  CHECK(r.error().input == path);
  CHECK((r.error().where == entity || r.error().where.rfind(entity + " ", 0) == 0));
}

// plyfit info on `path` exits 1 with one line naming the file and `entity`.
void binary_refuses(const std::string& path, const std::string& entity, const TempDir& dir) {
  const Run r = run_plyfit("info '" + path + "'", dir);
  INFO("exit " << r.code << ", stderr: " << r.err);
  CHECK(r.code == 1);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.find(path) != std::string::npos);
  CHECK(r.err.find(entity) != std::string::npos);
}

// The dish's surface (#77) and its first pole (#78); in IGES the 128 entity is DE 3, degree 2
// with 3 x 3 poles.
const std::string kStepSurface = "#77", kStepPole = "#78";
constexpr int kIgesSurface = 3;
const int kIgesPole = first_pole_field(2, 2, 2, 2);

// The dish with `value` as number k of STEP entity `step_id`, and as field `iges_field` of the
// IGES surface: opening either is an error naming that entity.
void rejects_value(const TempDir& dir, const std::string& value, const std::string& step_id, int k,
                   int iges_field) {
  INFO(value);
  const std::string s = dir.file("changed.step"), i = dir.file("changed.igs");
  write_bytes(s, step_with(read_bytes(sample_mold("dish.step")), step_id, k, value));
  rejected(s, step_id);
  write_bytes(i, iges_with(read_bytes(sample_mold("dish.igs")), kIgesSurface, iges_field, value));
  rejected(i, "DE " + std::to_string(kIgesSurface));
}

}  // namespace

TEST_CASE("importers: an INF or NaN pole is an error naming the file and the entity") {
  TempDir dir("file_checks_inf");
  for (const std::string v : {"INF", "NaN"}) rejects_value(dir, v, kStepPole, 0, kIgesPole + 1);
}

TEST_CASE("importers: a coordinate of 1.0E+999 or 1.E308 is an error naming the entity") {
  TempDir dir("file_checks_big");
  for (const std::string v : {"1.0E+999", "-1.0E+999", "1.E308", "-1.E308"})
    rejects_value(dir, v, kStepPole, 2, kIgesPole + 2);
}

TEST_CASE(
    "importers: a coordinate past 1e8 written without an exponent is an error naming the entity") {
  TempDir dir("file_checks_plain");
  // Plain decimals of up to 8 digits before the point are not read (they cannot be past 1e8).
  for (const std::string v : {"123456789.5", "-100000000.1"})
    rejects_value(dir, v, kStepPole, 2, kIgesPole + 2);
}

TEST_CASE("importers: a huge integer count is an error naming the entity") {
  TempDir dir("file_checks_count");
  // STEP: the surface's degree in u; IGES: K1, its poles in u less one.
  for (const std::string v : {"2147483648", "9223372036854775808"})
    rejects_value(dir, v, kStepSurface, 0, 1);
  // The pointer to a trim curve in an IGES loop (type 508, DE 7 of the split cylinder; its
  // record has room for one character more).
  const std::string path = dir.file("loop_pointer.igs");
  write_bytes(path, iges_with(read_bytes(sample_mold("cylinder-split.igs")), 7, 8, "1E9"));
  rejected(path, "DE 7");
}

TEST_CASE("importers: a STEP number nested 200,000 parentheses deep is an error, not a crash") {
  TempDir dir("file_checks_nest");
  const std::string path = dir.file("nested.step");
  write_bytes(path, step_with(read_bytes(sample_mold("dish.step")), kStepPole, 1, "", 200000));
  binary_refuses(path, kStepPole, dir);
}

TEST_CASE("importers: STEP references swapped into a cycle are an error naming the entity") {
  TempDir dir("file_checks_cycle");
  const std::string step = read_bytes(sample_mold("dish.step"));
  // An oriented edge and a surface curve that refer to themselves (OpenCASCADE's reader recursed
  // on them until the stack overflowed), and the face's vertex referring back to the face.
  const std::vector<std::array<std::string, 3>> cycles = {
      {"#20 = ORIENTED_EDGE('',*,*,#21,.T.);", "#20 = ORIENTED_EDGE('',*,*,#20,.T.);", "#20"},
      {"#24 = SURFACE_CURVE('',#25,", "#24 = SURFACE_CURVE('',#24,", "#24"},
      {"#22 = VERTEX_POINT('',#23);", "#22 = VERTEX_POINT('',#17);", "#17"}};
  for (const auto& [from, to, entity] : cycles) {
    INFO(to);
    std::string s = step;
    const size_t at = s.find(from);
    REQUIRE(at != std::string::npos);
    s.replace(at, from.size(), to);
    const std::string path = dir.file("cycle.step");
    write_bytes(path, s);
    binary_refuses(path, entity, dir);
  }
}
