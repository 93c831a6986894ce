#pragma once
// The option parser every subcommand shares: a command declares its options as a table
// (OptionSpec), parse_command_line() reads its arguments into raw values by key (scene files
// give the same raw values: job/scene_file.hpp), and Options converts them (numbers, integers,
// switches, vectors, ranges) with errors that blame the key. input_namer() names a key in
// messages as the flag or the scene file's key its value came from.

#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/result.hpp>
#include <plyfit/kernel/types.hpp>

#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace plyfit::cli {

/// One option: flag --key (and -short_name), value form, default (empty: none) and help.
struct OptionSpec {
  std::string key;
  std::string value;  ///< e.g. "X,Y"; empty for a switch
  std::string def;    ///< default as text, empty if none
  std::string help;
  bool repeatable = false;
  std::string section;  ///< scene-file section a drape key is listed under by --dump-scene
  char short_name = 0;  ///< e.g. 'o' for -o; 0: none

  OptionSpec(std::string key_, std::string value_, std::string def_, std::string help_,
             bool repeatable_ = false, std::string section_ = {}, char short_name_ = 0)
      : key(std::move(key_)),
        value(std::move(value_)),
        def(std::move(def_)),
        help(std::move(help_)),
        repeatable(repeatable_),
        section(std::move(section_)),
        short_name(short_name_) {}
};

/// A command's options, in help order.
using OptionTable = std::vector<OptionSpec>;

/// The options several commands take, one definition each: --help/-h, --quiet (no progress
/// line), --jobs/-j N (`what` run at a time, default the number of cores), --output/-o VALUE,
/// and the scene files a command takes as operands (key "scene", repeatable).
OptionSpec help_option();
OptionSpec quiet_option();
OptionSpec jobs_option(const std::string& what);
OptionSpec output_option(const std::string& value, const std::string& help,
                         const std::string& def = {});
OptionSpec scenes_option();

/// Where values given as flags come from (RawOptions::origin, ::origins).
inline constexpr const char* kCommandLine = "command line";

/// Raw values by key, before conversion (switches have the value "true").
struct RawOptions {
  std::map<std::string, std::vector<std::string>> values;
  /// Folder that relative paths in each key's value are relative to (the scene file's
  /// folder, or the working directory for flags).
  std::map<std::string, std::string> dirs;
  /// Where each key's value came from (kCommandLine or a scene file), for messages: a flag
  /// that overrides a scene key is named as the flag.
  std::map<std::string, std::string> origins;
  std::string origin;  ///< where they came from: kCommandLine or a scene file's path
};

/// Parses a command's arguments against its table. Bare arguments are values of `positional`
/// (a key, which need not be in the table); without one they are errors, saying `bare_note`.
/// Unknown options, a non-repeatable option given twice and a missing value are errors.
Result<RawOptions> parse_command_line(const std::vector<std::string>& args,
                                      const OptionTable& table, const std::string& positional = {},
                                      const std::string& bare_note = {});

/// True when the arguments ask for help (--help or -h anywhere).
bool wants_help(const std::vector<std::string>& args);

/// Values of `over` replace those of `base` key by key.
RawOptions merge(const RawOptions& base, const RawOptions& over);

/// Where the value of `key` came from: kCommandLine or a scene file (a default: the origin of
/// the whole).
std::string origin_of(const RawOptions& raw, const std::string& key);

/// Names an error's input for messages: a key of `table` as "--key", or "FILE: key 'key'" when
/// its value came from a scene file; any other input (a file) as it is.
exporters::InputNamer input_namer(const RawOptions& raw, const OptionTable& table);

/// Names a command's own options (all given as flags) in messages: "--key".
exporters::InputNamer flag_namer(const OptionTable& table);

/// The options of a table as help lines: "  --key, -k VALUE   help [default] (repeatable)".
void print_options(std::ostream& os, const OptionTable& table);

/// A number's allowed interval, for Options::number_in (hi may be infinite).
struct Range {
  double lo = 0.0, hi = 0.0;
  bool lo_open = false, hi_open = false;
  const char* unit = "";  ///< "degrees", "percent" or ""
};

/// Parses a finite number; errors blame `key`.
Result<double> parse_number(const std::string& text, const std::string& key);
/// Parses an integer in [lo, hi]; errors blame `key`.
Result<long> parse_integer(const std::string& text, const std::string& key, long lo, long hi);
/// Parses true/false (1/0, yes/no, on/off); errors blame `key`.
Result<bool> parse_bool(const std::string& text, const std::string& key);
/// Parses N comma-separated numbers; errors blame `key`.
Result<Vec2> parse_vec2(const std::string& text, const std::string& key);
Result<Vec3> parse_vec3(const std::string& text, const std::string& key);
/// Splits a comma-separated list (empty items dropped).
std::vector<std::string> split_list(const std::string& text);

/// A command's raw values read through its table: the values given, else the defaults,
/// converted with errors that blame the key.
class Options {
 public:
  Options(const RawOptions& raw, const OptionTable& table) : raw_(raw), table_(table) {}

  /// The values given for `key` (empty when none).
  const std::vector<std::string>& all(const std::string& key) const;
  bool given(const std::string& key) const { return !all(key).empty(); }
  /// The first value given, else the default, else none.
  std::optional<std::string> text(const std::string& key) const;
  /// The value (given or default) of `key` as a number, integer, switch or vector; a key with
  /// neither is a missing option.
  Result<double> number(const std::string& key) const;
  Result<double> number_in(const std::string& key, const Range& range) const;
  Result<long> integer(const std::string& key, long lo, long hi) const;
  Result<bool> flag(const std::string& key) const;
  Result<Vec2> vec2(const std::string& key) const;
  Result<Vec3> vec3(const std::string& key) const;

  /// The missing-option error for `key`, as the raw values' origin says it.
  Error missing(const std::string& key) const;
  const RawOptions& raw() const { return raw_; }
  /// Names the keys in messages as the flags or scene keys their values came from.
  exporters::InputNamer namer() const { return input_namer(raw_, table_); }

 private:
  Result<std::string> required(const std::string& key) const;
  const RawOptions& raw_;
  const OptionTable& table_;
};

/// The value of --jobs/-j (jobs_option): 1 to 1024, default the number of cores.
Result<long> jobs_value(const Options& o);

}  // namespace plyfit::cli
