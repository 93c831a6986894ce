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

std::string message(const Error& e) {
  const render::Values x{e.values};
  switch (e.code) {
#define PLYFIT_TEXT_CASE(name, snake) \
  case ErrorCode::k##name:            \
    return render::text_##snake(x);
    PLYFIT_ERROR_CODES(PLYFIT_TEXT_CASE)
#undef PLYFIT_TEXT_CASE
  }
  return to_string(e.code);
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
  const render::Values x{w.values};
  switch (w.code) {
#define PLYFIT_TEXT_CASE(name, snake) \
  case WarningCode::k##name:          \
    return render::warning_##snake(x);
    PLYFIT_WARNING_CODES(PLYFIT_TEXT_CASE)
#undef PLYFIT_TEXT_CASE
  }
  return to_string(w.code);
}

}  // namespace plyfit::exporters
