// cli/output.hpp -- the one path from a command's answer to standard output.
//
// Every command writes its answer to std::cout; main() runs it with std::cout
// redirected into memory (StdoutCapture) and, only once the command has
// returned, writes the whole answer to file descriptor 1 in one go
// (write_stdout). So an error or a budget exceeded while the answer is being
// formatted leaves stdout empty, and a failed write (a full disk, a closed
// pipe, a closed descriptor) is an error with the system's reason, never a
// silent exit 0.
#pragma once

#include <sstream>
#include <string>

namespace uniparam::cli {

/// Redirects std::cout into an in-memory buffer for its lifetime; the
/// previous stream buffer is restored at destruction (the text not taken is
/// discarded).
class StdoutCapture {
 public:
  StdoutCapture();
  ~StdoutCapture();
  StdoutCapture(const StdoutCapture&) = delete;
  StdoutCapture& operator=(const StdoutCapture&) = delete;

  /// The text written to std::cout so far; the buffer is emptied.
  std::string take();
  /// Forgets the text written so far (an error: nothing is printed).
  void discard();

 private:
  std::ostringstream buffer_;
  std::streambuf* saved_;
};

/// Writes all of `text` to file descriptor `fd` (retrying short writes and
/// EINTR) and closes `fd`, reporting the errors of the write and of the close
/// (a file system may report a full disk only at close). SIGPIPE is held
/// back during the write, so a closed pipe is the error EPIPE rather than a
/// silent death by signal. An empty `text` is not written and `fd` is left
/// open (a command that printed nothing does not need stdout).
/// \returns the empty string on success, otherwise the reason
///          ("No space left on device", "Broken pipe", "Bad file descriptor").
std::string write_and_close(int fd, const std::string& text);

}  // namespace uniparam::cli
