// cli/input.hpp -- a curve argument's text from the command line, standard
// input ("-") or a file ("@FILE").
#pragma once

#include <cstddef>
#include <string>

namespace uniparam::cli {

/// The text of the argument `what` ("--svg", "CURVE") given as `value`: all
/// of standard input for "-", the file's contents for "@FILE", else `value`.
/// \throws InvalidArgument naming `what` and the system's reason when the
///         file cannot be read, and when the text is longer than max_bytes.
std::string read_argument_text(const std::string& what, const std::string& value, std::size_t max_bytes);

}  // namespace uniparam::cli
