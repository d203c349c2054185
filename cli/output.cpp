// cli/output.cpp -- buffered standard output, written and checked once (see output.hpp).
#include "output.hpp"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <iostream>

namespace uniparam::cli {

namespace {
StdoutCapture* g_active = nullptr;  // the capture in effect (main's), if any

/// Writes all of [p, p + n) to fd, retrying short writes and EINTR.
/// \returns the empty string or the system's reason.
std::string write_all(int fd, const char* p, std::size_t n) {
  while (n > 0) {
    const ssize_t k = ::write(fd, p, n);
    if (k < 0) {
      if (errno == EINTR) continue;
      return std::strerror(errno);
    }
    if (k == 0) return "the output accepted no more bytes";
    p += k;
    n -= static_cast<std::size_t>(k);
  }
  return std::string();
}
}  // namespace

/// A stream buffer of 64 KiB on a file descriptor; the first failed write is
/// kept (error()) and every later output fails.
class StdoutCapture::FdBuf : public std::streambuf {
 public:
  explicit FdBuf(int fd) : fd_(fd) { setp(buf_, buf_ + sizeof buf_); }
  const std::string& error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (drain() != 0) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override { return drain(); }

 private:
  int drain() {
    if (!error_.empty()) return -1;
    const std::size_t n = static_cast<std::size_t>(pptr() - pbase());
    error_ = write_all(fd_, pbase(), n);
    setp(buf_, buf_ + sizeof buf_);
    return error_.empty() ? 0 : -1;
  }
  int fd_;
  char buf_[1 << 16];
  std::string error_;
};

StdoutCapture::StdoutCapture() : saved_(std::cout.rdbuf(buffer_.rdbuf())) { g_active = this; }

StdoutCapture::~StdoutCapture() {
  std::cout.rdbuf(saved_);
  if (g_active == this) g_active = nullptr;
}

void StdoutCapture::stream() {
  if (direct_) return;
  ::signal(SIGPIPE, SIG_IGN);
  direct_ = std::make_unique<FdBuf>(1);
  std::cout.rdbuf(direct_.get());
  const std::string early = buffer_.str();
  buffer_.str(std::string());
  std::cout << early;
}

std::string StdoutCapture::finish() {
  if (!direct_) return write_and_close(1, take());
  std::cout.flush();
  if (!direct_->error().empty()) return direct_->error();
  if (!std::cout) return "the output stream failed";
  if (::close(1) != 0 && errno != EINTR) return std::strerror(errno);
  return std::string();
}

std::string StdoutCapture::stream_error() const { return direct_ ? direct_->error() : std::string(); }

namespace {
thread_local std::ostream* t_answer = nullptr;
thread_local std::ostream* t_warn = nullptr;
}  // namespace

std::ostream& answer() { return t_answer ? *t_answer : std::cout; }
std::ostream& warn() { return t_warn ? *t_warn : std::cerr; }

ThreadOutput::ThreadOutput(std::ostream& a, std::ostream& w) : saved_answer_(t_answer), saved_warn_(t_warn) {
  t_answer = &a;
  t_warn = &w;
}

ThreadOutput::~ThreadOutput() {
  t_answer = saved_answer_;
  t_warn = saved_warn_;
}

void stream_stdout() {
  if (t_answer) return;
  if (g_active) g_active->stream();
}

std::string stdout_stream_error() { return g_active ? g_active->stream_error() : std::string(); }

std::string StdoutCapture::take() {
  std::string s = buffer_.str();
  discard();
  return s;
}

void StdoutCapture::discard() {
  buffer_.str(std::string());
  buffer_.clear();
  std::cout.clear();
}

namespace {

/// Blocks SIGPIPE in the calling thread for its lifetime; a SIGPIPE raised
/// meanwhile (by a write to a closed pipe, which then fails with EPIPE) is
/// consumed before the previous mask is restored.
class HoldSigpipe {
 public:
  HoldSigpipe() {
    sigemptyset(&pipe_);
    sigaddset(&pipe_, SIGPIPE);
    sigset_t pending;
    sigemptyset(&pending);
    sigpending(&pending);
    was_pending_ = sigismember(&pending, SIGPIPE) == 1;
    pthread_sigmask(SIG_BLOCK, &pipe_, &old_);
  }
  ~HoldSigpipe() {
    if (!was_pending_) {
      const timespec zero{0, 0};
      while (sigtimedwait(&pipe_, nullptr, &zero) == SIGPIPE) {
      }
    }
    pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  HoldSigpipe(const HoldSigpipe&) = delete;
  HoldSigpipe& operator=(const HoldSigpipe&) = delete;

 private:
  sigset_t pipe_, old_;
  bool was_pending_ = false;
};

}  // namespace

std::string write_and_close(int fd, const std::string& text) {
  if (text.empty()) return std::string();
  {
    const HoldSigpipe hold;
    const std::string error = write_all(fd, text.data(), text.size());
    if (!error.empty()) return error;
  }
  // Linux closes the descriptor even when close() reports EINTR.
  if (::close(fd) != 0 && errno != EINTR) return std::strerror(errno);
  return std::string();
}

}  // namespace uniparam::cli
