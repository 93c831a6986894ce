// Errors and warnings as text (messages.hpp): each code's own text function (message_text.hpp).
#include <plyfit/exporters/messages.hpp>

#include "render/message_text.hpp"

#include <algorithm>
#include <iterator>
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

namespace {

// The text of a sentence's slot {KIND K} (fill()).
std::string slot_text(char kind, std::size_t k, const Values& x) {
  if (kind == 'n') return x.n(k);
  if (kind == 'b') return x.brief(k);
  if (kind == 'f') return x.fixed(k);
  if (kind == 'q') return '\'' + x.text(k) + '\'';
  return x.text(k);
}

}  // namespace

std::string fill(std::string_view sentence, const Values& x) {
  std::string out;
  std::size_t i = 0;
  for (auto open = sentence.find('{'); open != std::string_view::npos;
       open = sentence.find('{', i)) {
    out.append(sentence, i, open - i);
    const bool slot = open + 3 < sentence.size() && sentence[open + 3] == '}';
    const auto k =
        static_cast<std::size_t>(sentence[std::min(open + 2, sentence.size() - 1)] - '0');
    out += slot ? slot_text(sentence[open + 1], k, x) : std::string(1, '{');
    i = slot ? open + 4 : open + 1;
  }
  out.append(sentence, i);
  return out;
}

}  // namespace render

namespace {

// Each code's text function, in the order of its enumeration.
using TextFn = std::string (*)(const render::Values&);
#define PLYFIT_ERROR_TEXT(name, snake) &render::text_##snake,
#define PLYFIT_WARNING_TEXT(name, snake) &render::warning_##snake,
constexpr TextFn kErrorTexts[] = {PLYFIT_ERROR_CODES(PLYFIT_ERROR_TEXT)};
constexpr TextFn kWarningTexts[] = {PLYFIT_WARNING_CODES(PLYFIT_WARNING_TEXT)};
#undef PLYFIT_ERROR_TEXT
#undef PLYFIT_WARNING_TEXT

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

namespace render {

std::string error_chain_text(const Values& x, std::size_t first) {
  std::string out;
  for (std::size_t k = first; k + 1 < x.v.size();) {
    const std::string name = x.text(k);
    const auto n = static_cast<std::size_t>(std::max<std::int64_t>(x.count(k + 1), 0));
    const std::size_t end = std::min(k + 2 + n, x.v.size());
    Error e{ErrorCode::kInternal,
            {},
            std::vector<MessageValue>(x.v.begin() + static_cast<std::ptrdiff_t>(k + 2),
                                      x.v.begin() + static_cast<std::ptrdiff_t>(end))};
    bool known = false;
    for (std::size_t c = 0; c < std::size(kErrorTexts) && !known; ++c)
      if (name == to_string(static_cast<ErrorCode>(c))) {
        e.code = static_cast<ErrorCode>(c);
        known = true;
      }
    out += (out.empty() ? "" : ": ") + (known ? message(e) : name);
    k = end;
  }
  return out;
}

}  // namespace render

}  // namespace plyfit::exporters
