// texproc/error.h: the one exception type libtexproc throws for bad data.
//
// A caller's bug (a null pointer, a view whose stride is too small) is an
// assert. Bad data (a file that cannot be read, a header that lies, an option
// out of range) throws texproc::Error, whose message names the file or the
// option and, where there is a fixed set, lists the valid values.
#pragma once

#include <stdexcept>
#include <string>

namespace texproc {

// Exit codes of the texproc CLI, the same table KTX-Software's `ktx` tool
// uses, so scripts can tell failures apart. Error carries one of them.
enum class ErrorCode : int {
  success = 0,
  bad_arguments = 1,    // an option or argument is invalid
  io = 2,               // a file could not be opened, read or written
  invalid_file = 3,     // a file was read but its contents are invalid
  runtime = 4,          // anything else that went wrong while working
  unsupported = 5,      // valid, but texproc does not support it
  difference_found = 7  // `compare`: the inputs differ beyond the tolerance
};

class Error : public std::runtime_error {
 public:
  Error(ErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ErrorCode code() const noexcept { return code_; }

 private:
  ErrorCode code_;
};

}  // namespace texproc
