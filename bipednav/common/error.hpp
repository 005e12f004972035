#pragma once

#include <stdexcept>
#include <string>

namespace bipednav {

// Base of every error this project raises on bad input.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A parameter outside its valid range: names the struct field and what was expected.
class ParamError : public Error {
 public:
  ParamError(const std::string& field, const std::string& expected)
      : Error("invalid parameter '" + field + "': expected " + expected) {}
};

// A malformed or unreadable file: names the file, where in it, and what was expected.
class FileError : public Error {
 public:
  FileError(const std::string& file, const std::string& where, const std::string& what)
      : Error(file + (where.empty() ? "" : ":" + where) + ": " + what) {}
};

// Throws ParamError unless `ok`; used by the validate() of parameter structs.
inline void require(bool ok, const std::string& field, const std::string& expected) {
  if (!ok) throw ParamError(field, expected);
}

}  // namespace bipednav
