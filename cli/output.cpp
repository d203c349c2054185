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

StdoutCapture::StdoutCapture() : saved_(std::cout.rdbuf(buffer_.rdbuf())) {}

StdoutCapture::~StdoutCapture() { std::cout.rdbuf(saved_); }

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
    const char* p = text.data();
    std::size_t left = text.size();
    while (left > 0) {
      const ssize_t n = ::write(fd, p, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        return std::strerror(errno);
      }
      if (n == 0) return "the output accepted no more bytes";
      p += n;
      left -= static_cast<std::size_t>(n);
    }
  }
  // Linux closes the descriptor even when close() reports EINTR.
  if (::close(fd) != 0 && errno != EINTR) return std::strerror(errno);
  return std::string();
}

}  // namespace uniparam::cli
