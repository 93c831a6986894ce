// Errors and warnings as text (messages.hpp): each code's own text function (message_text.hpp).
#include <plyfit/exporters/messages.hpp>

#include "render/message_text.hpp"

#include <sstream>

namespace plyfit::exporters {

namespace render {

std::int64_t Values::count(std::size_t k) const {
  if (k < v.size())
    if (const auto* x = std::get_if<std::int64_t>(&v[k])) return *x;
  return -1;
}

double Values::number(std::size_t k) const {
  if (k < v.size()) {
    if (const auto* x = std::get_if<double>(&v[k])) return *x;
    if (const auto* i = std::get_if<std::int64_t>(&v[k])) return static_cast<double>(*i);
  }
  return 0.0;
}

std::string Values::text(std::size_t k) const {
  if (k < v.size())
    if (const auto* x = std::get_if<std::string>(&v[k])) return *x;
  return "?";
}

std::string Values::brief(std::size_t k) const {
  std::ostringstream os;
  os.precision(3);
  os << number(k);
  return os.str();
}

}  // namespace render

namespace {

// Each code's text function, in the order of its enumeration.
using TextFn = std::string (*)(const render::Values&);
#define PLYFIT_TEXT_ENTRY(name, snake) &render::text_##snake,
constexpr TextFn kErrorTexts[] = {PLYFIT_ERROR_CODES(PLYFIT_TEXT_ENTRY)};
#undef PLYFIT_TEXT_ENTRY
#define PLYFIT_TEXT_ENTRY(name, snake) &render::warning_##snake,
constexpr TextFn kWarningTexts[] = {PLYFIT_WARNING_CODES(PLYFIT_TEXT_ENTRY)};
#undef PLYFIT_TEXT_ENTRY

// The text of `code` with `values` by its function in `texts` (the code's name when it has
// none: a code out of range).
template <typename Code, std::size_t N>
std::string text_of(const TextFn (&texts)[N], Code code, const std::vector<MessageValue>& values) {
  const auto k = static_cast<std::size_t>(code);
  return k < N ? texts[k](render::Values{values}) : std::string(to_string(code));
}

}  // namespace

std::string message(const Error& e) {
  return text_of(kErrorTexts, e.code, e.values);
}

std::string describe(const Error& e, const InputNamer& name_input) {
  std::string s;
  if (!e.input.empty()) s += (name_input ? name_input(e.input) : e.input) + ": ";
  if (e.face >= 0) s += "face " + std::to_string(e.face) + ": ";
  if (!e.where.empty()) s += e.where + ": ";
  s += message(e);
  if (e.cause) s += ": " + describe(*e.cause, name_input);
  return s;
}

std::string message(const Warning& w) {
  return text_of(kWarningTexts, w.code, w.values);
}

std::string messages(const std::vector<Warning>& warnings, const std::string& separator) {
  std::string s;
  for (std::size_t k = 0; k < warnings.size(); ++k)
    s += (k ? separator : std::string()) + message(warnings[k]);
  return s;
}

}  // namespace plyfit::exporters
