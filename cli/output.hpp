// cli/output.hpp -- the one path from a command's answer to standard output.
//
// Every command writes its answer to std::cout; main() runs it with std::cout
// redirected into memory (StdoutCapture) and, only once the command has
// returned, writes the whole answer to file descriptor 1 in one go
// (write_stdout). So an error or a budget exceeded while the answer is being
// formatted leaves stdout empty, and a failed write (a full disk, a closed
// pipe, a closed descriptor) is an error with the system's reason, never a
// silent exit 0.
//
// A command whose answer can be too large to hold (sample with a million
// points) calls stream_stdout() once its result is certified: from then on
// std::cout writes through a fixed-size buffer straight to file descriptor 1,
// a failed write sets std::cout's badbit (the command checks it), and
// StdoutCapture::finish() flushes and closes.
#pragma once

#include <memory>
#include <ostream>
#include <sstream>
#include <streambuf>
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
  /// Forgets the text written so far (an error: nothing is printed). After
  /// stream_stdout() what was written is already out and stays out.
  void discard();

  /// Ends the command's output: the captured text is written to file
  /// descriptor 1 and the descriptor closed (write_and_close); in streaming
  /// mode the stream is flushed and the descriptor closed. Call once.
  /// \returns the empty string on success, otherwise the system's reason.
  std::string finish();

  /// Switches std::cout, from now on, to a bounded buffer written to file
  /// descriptor 1 (the text captured so far goes first). SIGPIPE is ignored
  /// from then on, so a closed pipe is a failed write (badbit), not a death
  /// by signal. Precondition: this capture is the one in effect.
  void stream();
  /// Whether stream() has switched std::cout to file descriptor 1.
  bool streaming() const { return direct_ != nullptr; }
  /// The first failed write's reason in streaming mode, else "".
  std::string stream_error() const;

 private:
  class FdBuf;
  std::ostringstream buffer_;
  std::streambuf* saved_;
  std::unique_ptr<FdBuf> direct_;
};

/// The stream a command writes its answer to: std::cout, or the stream a
/// ThreadOutput installed on this thread (`uniparam batch` runs commands on
/// several threads, each answer into its own buffer).
std::ostream& answer();
/// The stream of a command's warnings (std::cerr, or the ThreadOutput's).
std::ostream& warn();

/// Sends this thread's answer() and warn() to the given streams for its
/// lifetime (the previous ones are restored). While one is installed,
/// stream_stdout() does nothing: the answer stays in its buffer.
class ThreadOutput {
 public:
  ThreadOutput(std::ostream& answer, std::ostream& warn);
  ~ThreadOutput();
  ThreadOutput(const ThreadOutput&) = delete;
  ThreadOutput& operator=(const ThreadOutput&) = delete;

 private:
  std::ostream* saved_answer_;
  std::ostream* saved_warn_;
};

/// Calls stream() on the StdoutCapture in effect, if there is one (main
/// installs one around every command); otherwise std::cout is left as it is.
/// For a command whose answer is too large to hold in memory: call it after
/// everything that can fail before the first byte has succeeded.
void stream_stdout();

/// The system's reason for the first failed write since stream_stdout()
/// ("No space left on device", ...), or "" when none failed or nothing streams.
std::string stdout_stream_error();

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
