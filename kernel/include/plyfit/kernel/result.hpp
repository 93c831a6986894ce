#pragma once
/// \file Result<T>: a value or an error message, for expected failures of user input.
///
/// Exceptions are kept for broken internal invariants; everything a user can get wrong
/// (a bad file, a bad option, an invalid NURBS definition) comes back as an Error.

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

namespace plyfit {

/// An expected failure: a one-line, user-facing message.
struct Error {
  std::string message;
};

/// Either a T or an Error (a minimal `tl::expected`).
template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  Result(Error e) : v_(std::move(e)) {}      // NOLINT(google-explicit-constructor)

  /// True when a value is held.
  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }

  /// The value; throws std::logic_error when called on an error (an internal bug).
  T& value() & {
    check();
    return std::get<0>(v_);
  }
  const T& value() const& {
    check();
    return std::get<0>(v_);
  }
  T&& value() && {
    check();
    return std::get<0>(std::move(v_));
  }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

  /// The error; only valid when !ok().
  const Error& error() const { return std::get<1>(v_); }

 private:
  void check() const {
    if (!ok()) throw std::logic_error("Result::value() on an error: " + std::get<1>(v_).message);
  }
  std::variant<T, Error> v_;
};

/// Result of an operation with no value.
struct Unit {};
using Status = Result<Unit>;
inline Status ok_status() {
  return Unit{};
}

}  // namespace plyfit
