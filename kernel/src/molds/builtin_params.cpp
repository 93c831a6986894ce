// The parameters of the built-in molds and shells: resolving them, checking their values, and
// parsing a built-in's spec "NAME[:key=value,...]".
#include "molds/builtin.hpp"

#include <cmath>
#include <sstream>

namespace plyfit {

namespace detail {

namespace {

// "a, b, c" of the names.
template <class Range, class Name>
std::string joined(const Range& items, Name name) {
  std::string out;
  for (const auto& x : items) out += (out.empty() ? "" : ", ") + name(x);
  return out;
}

}  // namespace

Result<BuiltinParams> BuiltinParams::resolve(const std::vector<BuiltinInfo>& list,
                                             const std::string& what, const std::string& name,
                                             const std::map<std::string, double>& given) {
  const BuiltinInfo* info = nullptr;
  for (const auto& b : list)
    if (b.name == name) info = &b;
  if (!info)
    return Error{ErrorCode::kUnknownBuiltin,
                 {},
                 {what, name, joined(list, [](const BuiltinInfo& b) { return b.name; })}};
  BuiltinParams p;
  p.name_ = name;
  for (const auto& q : info->params) p.values_[q.key] = q.value;
  for (const auto& [k, x] : given) {
    if (!p.values_.count(k))
      return Error{
          ErrorCode::kBuiltinNoParameter,
          {},
          {what, name, k, joined(info->params, [](const BuiltinParam& q) { return q.key; })}};
    if (!std::isfinite(x)) return Error{ErrorCode::kBuiltinParameterNotFinite, {}, {k, name}};
    p.values_[k] = x;
  }
  return p;
}

double BuiltinParams::radians(const char* k) const {
  return detail::radians((*this)[k]);
}

Status BuiltinParams::positive(std::initializer_list<const char*> keys) const {
  for (const char* k : keys)
    if (!((*this)[k] > 0.0))
      return Error{ErrorCode::kBuiltinParameterNotPositive, {}, {std::string(k), name_}};
  return ok_status();
}

Status BuiltinParams::angle(const char* k) const {
  const double x = (*this)[k];
  if (!(x > 0.0 && x <= 360.0))
    return Error{ErrorCode::kBuiltinAngleRange, {}, {std::string(k), name_}};
  return ok_status();
}

Status BuiltinParams::within(const char* k, double lo, double hi) const {
  const double x = (*this)[k];
  if (!(x >= lo && x <= hi))
    return Error{ErrorCode::kBuiltinParameterRange, {}, {std::string(k), name_, lo, hi}};
  return ok_status();
}

Status BuiltinParams::integer(const char* k, int lo, int hi) const {
  const double x = (*this)[k];
  if (!(x >= lo && x <= hi && x == std::floor(x)))
    return Error{ErrorCode::kBuiltinIntegerRange,
                 {},
                 {std::string(k), name_, std::int64_t{lo}, std::int64_t{hi}}};
  return ok_status();
}

std::array<Vec2, 4> domain_corners(const NurbsSurfaceData& s) {
  const double u0 = s.knots_u[static_cast<std::size_t>(s.degree_u)];
  const double u1 = s.knots_u[static_cast<std::size_t>(s.count_u)];
  const double v0 = s.knots_v[static_cast<std::size_t>(s.degree_v)];
  const double v1 = s.knots_v[static_cast<std::size_t>(s.count_v)];
  return {Vec2(u0, v0), Vec2(u1, v0), Vec2(u1, v1), Vec2(u0, v1)};
}

}  // namespace detail

Result<std::pair<std::string, std::map<std::string, double>>> parse_builtin_spec(
    const std::string& spec) {
  const auto colon = spec.find(':');
  std::pair<std::string, std::map<std::string, double>> out;
  out.first = spec.substr(0, colon);
  if (out.first.empty()) return Error{ErrorCode::kBuiltinNameMissing, {}, {spec}};
  if (colon == std::string::npos) return out;
  std::stringstream ss(spec.substr(colon + 1));
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      return Error{ErrorCode::kBuiltinParameterSyntax, {}, {item}};
    const std::string key = item.substr(0, eq), val = item.substr(eq + 1);
    try {
      std::size_t used = 0;
      const double x = std::stod(val, &used);
      if (used != val.size() || !std::isfinite(x)) throw std::invalid_argument(val);
      out.second[key] = x;
    } catch (const std::exception&) {
      return Error{ErrorCode::kBuiltinParameterValue, {}, {key, val}};
    }
  }
  return out;
}

}  // namespace plyfit
