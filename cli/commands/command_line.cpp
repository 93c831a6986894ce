#include "commands/command_line.hpp"

#include <boost/program_options.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <ostream>
#include <sstream>
#include <thread>

namespace po = boost::program_options;
namespace fs = std::filesystem;

namespace plyfit::cli {

namespace {

/// Help lines put the text in this column.
constexpr std::size_t kHelpColumn = 34;

const OptionSpec* find_spec(const OptionTable& table, const std::string& key) {
  for (const auto& s : table)
    if (s.key == key) return &s;
  return nullptr;
}

// The spec a flag as Boost names it in an error ("--key" or "-k") stands for.
const OptionSpec* spec_of_flag(const OptionTable& table, std::string flag) {
  if (flag.rfind("--", 0) == 0) return find_spec(table, flag.substr(2));
  for (const auto& s : table)
    if (s.short_name && flag == std::string("-") + s.short_name) return &s;
  return nullptr;
}

po::options_description boost_options(const OptionTable& table) {
  po::options_description desc;
  for (const auto& s : table) {
    const std::string name = s.short_name ? s.key + "," + s.short_name : s.key;
    if (s.value.empty())
      desc.add_options()(name.c_str(), po::value<std::vector<std::string>>()->zero_tokens());
    else
      desc.add_options()(name.c_str(), po::value<std::vector<std::string>>()->composing());
  }
  return desc;
}

// Boost's parse errors as codes: the option it names when it is one of the table's.
Error from_boost(const po::error& e, const OptionTable& table) {
  if (const auto* u = dynamic_cast<const po::unknown_option*>(&e))
    return Error{ErrorCode::kUnknownOption, "", {u->get_option_name()}};
  if (const auto* s = dynamic_cast<const po::invalid_command_line_syntax*>(&e))
    if (s->kind() == po::invalid_syntax::missing_parameter)
      if (const OptionSpec* spec = spec_of_flag(table, s->get_option_name()))
        return Error{ErrorCode::kOptionNeedsValue, spec->key, {spec->value}};
  return Error{ErrorCode::kBadCommandLine, "", {std::string(e.what())}};
}

std::string trimmed(const std::string& text) {
  const auto b = text.find_first_not_of(" \t\r\n\f\v");
  if (b == std::string::npos) return {};
  return text.substr(b, text.find_last_not_of(" \t\r\n\f\v") - b + 1);
}

template <int N>
Result<Eigen::Matrix<double, N, 1>> parse_vec(const std::string& text, const std::string& key) {
  Eigen::Matrix<double, N, 1> v;
  std::stringstream ss(text);
  std::string part;
  int k = 0;
  while (std::getline(ss, part, ',')) {
    if (k >= N) return Error{ErrorCode::kVectorSize, key, {text, std::int64_t{N}}};
    auto x = parse_number(part, key);
    if (!x) return x.error();
    v[k++] = *x;
  }
  if (k != N) return Error{ErrorCode::kVectorSize, key, {text, std::int64_t{N}}};
  return v;
}

}  // namespace

Result<RawOptions> parse_command_line(const std::vector<std::string>& args,
                                      const OptionTable& table, const std::string& positional,
                                      const std::string& bare_note) {
  po::positional_options_description pos;
  if (!positional.empty()) pos.add(positional.c_str(), -1);
  po::options_description desc = boost_options(table);
  if (!positional.empty() && !find_spec(table, positional))
    desc.add_options()(positional.c_str(), po::value<std::vector<std::string>>()->composing());
  RawOptions raw;
  raw.origin = kCommandLine;
  const std::string cwd = fs::current_path().string();
  try {
    po::command_line_parser parser(args);
    parser.options(desc);
    if (!positional.empty()) parser.positional(pos);
    const po::parsed_options parsed = parser.run();
    for (const auto& o : parsed.options) {
      if (o.string_key.empty())
        return Error{ErrorCode::kUnexpectedArgument, "", {o.value.front(), bare_note}};
      const OptionSpec* s = find_spec(table, o.string_key);
      auto& vals = raw.values[o.string_key];
      raw.dirs[o.string_key] = cwd;
      raw.origins[o.string_key] = raw.origin;
      const bool repeatable = !s || s->repeatable || o.string_key == positional;
      if (!repeatable && !vals.empty()) return Error{ErrorCode::kOptionRepeated, o.string_key};
      if (s && s->value.empty())
        vals.push_back("true");
      else
        vals.insert(vals.end(), o.value.begin(), o.value.end());
    }
  } catch (const po::error& e) {
    return from_boost(e, table);
  }
  return raw;
}

bool wants_help(const std::vector<std::string>& args) {
  return std::find(args.begin(), args.end(), "--help") != args.end() ||
         std::find(args.begin(), args.end(), "-h") != args.end();
}

RawOptions merge(const RawOptions& base, const RawOptions& over) {
  RawOptions out = base;
  for (const auto& [k, v] : over.values) {
    out.values[k] = v;
    const auto d = over.dirs.find(k);
    if (d != over.dirs.end()) out.dirs[k] = d->second;
    const auto o = over.origins.find(k);
    out.origins[k] = o != over.origins.end() ? o->second : over.origin;
  }
  return out;
}

std::string origin_of(const RawOptions& raw, const std::string& key) {
  const auto o = raw.origins.find(key);
  return o != raw.origins.end() ? o->second : raw.origin;
}

exporters::InputNamer input_namer(const RawOptions& raw, const OptionTable& table) {
  std::map<std::string, std::string> names;
  for (const auto& s : table) {
    const std::string from = origin_of(raw, s.key);
    names[s.key] =
        from == kCommandLine || from.empty() ? "--" + s.key : from + ": key '" + s.key + "'";
  }
  return [names](const std::string& input) {
    const auto n = names.find(input);
    return n != names.end() ? n->second : input;
  };
}

exporters::InputNamer flag_namer(const OptionTable& table) {
  RawOptions flags;
  flags.origin = kCommandLine;
  return input_namer(flags, table);
}

OptionSpec help_option() {
  return {"help", "", "", "show this help", false, "", 'h'};
}

Result<long> jobs_value(const Options& o) {
  constexpr long kMaxJobs = 1024;  // most jobs run at a time
  if (o.given("jobs")) return o.integer("jobs", 1, kMaxJobs);
  return static_cast<long>(std::max(1u, std::thread::hardware_concurrency()));
}

OptionSpec quiet_option() {
  return {"quiet", "", "", "no progress line"};
}

OptionSpec jobs_option(const std::string& what) {
  return {"jobs", "N", "", what + " run at a time (default: the number of cores)", false, "", 'j'};
}

OptionSpec output_option(const std::string& value, const std::string& help,
                         const std::string& def) {
  return {"output", value, def, help, false, "", 'o'};
}

OptionSpec scenes_option() {
  return {"scene", "SCENE", "", "scene files", true};
}

void print_options(std::ostream& os, const OptionTable& table) {
  for (const auto& s : table) {
    std::string flag = "  --" + s.key + (s.short_name ? std::string(", -") + s.short_name : "") +
                       (s.value.empty() ? "" : " " + s.value);
    if (flag.size() < kHelpColumn)
      flag += std::string(kHelpColumn - flag.size(), ' ');
    else
      flag += "\n" + std::string(kHelpColumn, ' ');
    os << flag << s.help << (s.def.empty() ? "" : " [" + s.def + "]")
       << (s.repeatable ? " (repeatable)" : "") << "\n";
  }
}

Result<double> parse_number(const std::string& text, const std::string& key) {
  const std::string t = trimmed(text);
  if (t.empty()) return Error{ErrorCode::kEmptyValue, key};
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size()) return Error{ErrorCode::kNotANumber, key, {text}};
  if (!std::isfinite(x) || errno == ERANGE) return Error{ErrorCode::kNotFinite, key, {text}};
  return x;
}

Result<long> parse_integer(const std::string& text, const std::string& key, long lo, long hi) {
  auto x = parse_number(text, key);
  if (!x) return x.error();
  if (*x != std::floor(*x) || *x < static_cast<double>(lo) || *x > static_cast<double>(hi))
    return Error{ErrorCode::kNotAnInteger,
                 key,
                 {text, static_cast<std::int64_t>(lo), static_cast<std::int64_t>(hi)}};
  return static_cast<long>(*x);
}

Result<bool> parse_bool(const std::string& text, const std::string& key) {
  if (text == "true" || text == "1" || text == "yes" || text == "on") return true;
  if (text == "false" || text == "0" || text == "no" || text == "off") return false;
  return Error{ErrorCode::kNotABool, key, {text}};
}

Result<Vec2> parse_vec2(const std::string& text, const std::string& key) {
  return parse_vec<2>(text, key);
}

Result<Vec3> parse_vec3(const std::string& text, const std::string& key) {
  return parse_vec<3>(text, key);
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) items.push_back(item);
  return items;
}

const std::vector<std::string>& Options::all(const std::string& key) const {
  static const std::vector<std::string> kNone;
  const auto it = raw_.values.find(key);
  return it == raw_.values.end() ? kNone : it->second;
}

std::optional<std::string> Options::text(const std::string& key) const {
  if (given(key)) return all(key).front();
  const OptionSpec* s = find_spec(table_, key);
  if (s && !s->def.empty()) return s->def;
  return std::nullopt;
}

Error Options::missing(const std::string& key) const {
  const bool in_scene = raw_.origin != kCommandLine && !raw_.origin.empty();
  Error e{ErrorCode::kMissingOption, "", {key, std::int64_t{in_scene}}};
  if (in_scene) e.where = raw_.origin;
  return e;
}

Result<std::string> Options::required(const std::string& key) const {
  if (auto t = text(key)) return *t;
  return missing(key);
}

Result<double> Options::number(const std::string& key) const {
  auto t = required(key);
  if (!t) return t.error();
  return parse_number(*t, key);
}

Result<double> Options::number_in(const std::string& key, const Range& r) const {
  auto x = number(key);
  if (!x) return x;
  const bool above = r.lo_open ? *x > r.lo : *x >= r.lo;
  const bool below = r.hi_open ? *x < r.hi : *x <= r.hi;
  if (above && below) return x;
  return Error{ErrorCode::kOutOfRange,
               key,
               {*text(key), r.lo, r.hi, std::int64_t{r.lo_open}, std::int64_t{r.hi_open},
                std::string(r.unit)}};
}

Result<long> Options::integer(const std::string& key, long lo, long hi) const {
  auto t = required(key);
  if (!t) return t.error();
  return parse_integer(*t, key, lo, hi);
}

Result<bool> Options::flag(const std::string& key) const {
  auto t = required(key);
  if (!t) return t.error();
  return parse_bool(*t, key);
}

Result<Vec2> Options::vec2(const std::string& key) const {
  auto t = required(key);
  if (!t) return t.error();
  return parse_vec2(*t, key);
}

Result<Vec3> Options::vec3(const std::string& key) const {
  auto t = required(key);
  if (!t) return t.error();
  return parse_vec3(*t, key);
}

}  // namespace plyfit::cli
