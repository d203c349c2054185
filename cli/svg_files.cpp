// Output files of the plots: writing a file with its removal on a fatal
// signal, and PNG output through an rsvg-convert child, killed and reaped
// on a signal or when the time budget runs out.
#include "svg.hpp"

#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "uniparam/core/budget.hpp"

extern char** environ;

namespace uniparam::cli::svg {

// ---- Output files and the rsvg-convert child ----------------------------
//
// While a file is written or rsvg-convert runs, SIGINT, SIGTERM, SIGHUP and
// SIGQUIT are caught: the handler kills and reaps the child, removes a file
// this process created but did not finish, and re-raises the signal with its
// default action (so the exit status still tells the signal). It uses only
// async-signal-safe calls and the three variables below.

namespace {

volatile sig_atomic_t g_child = 0;         // pid of the running rsvg-convert, or 0
volatile sig_atomic_t g_remove_armed = 0;  // g_remove_path names a file to remove
char g_remove_path[PATH_MAX];

const int kCaught[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

extern "C" void on_ending_signal(int sig) {
  const pid_t child = g_child;
  if (child > 0) {
    kill(child, SIGKILL);
    while (waitpid(child, nullptr, 0) < 0 && errno == EINTR) {
    }
  }
  if (g_remove_armed) unlink(g_remove_path);
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(sig, &dfl, nullptr);
  raise(sig);  // pending until the handler returns, then the default action
}

// Catches the ending signals for its lifetime (signals the process ignores,
// as under nohup, stay ignored); restores the previous actions after.
class CatchEndingSignals {
 public:
  CatchEndingSignals() {
    for (std::size_t i = 0; i < std::size(kCaught); ++i) {
      sigaction(kCaught[i], nullptr, &old_[i]);
      if (old_[i].sa_handler == SIG_IGN) continue;
      struct sigaction sa {};
      sa.sa_handler = on_ending_signal;
      sigfillset(&sa.sa_mask);
      sigaction(kCaught[i], &sa, nullptr);
    }
  }
  ~CatchEndingSignals() {
    for (std::size_t i = 0; i < std::size(kCaught); ++i) sigaction(kCaught[i], &old_[i], nullptr);
  }
  CatchEndingSignals(const CatchEndingSignals&) = delete;
  CatchEndingSignals& operator=(const CatchEndingSignals&) = delete;

 private:
  struct sigaction old_[std::size(kCaught)];
};

// Blocks every signal in the calling thread for its lifetime (so that the
// handler never sees half-updated state).
class BlockSignals {
 public:
  BlockSignals() {
    sigset_t all;
    sigfillset(&all);
    pthread_sigmask(SIG_BLOCK, &all, &old_);
  }
  ~BlockSignals() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  BlockSignals(const BlockSignals&) = delete;
  BlockSignals& operator=(const BlockSignals&) = delete;
  const sigset_t& old() const { return old_; }

 private:
  sigset_t old_;
};

// Ignores SIGPIPE for its lifetime: a child that stops reading its input
// gives EPIPE, not the end of this process.
class IgnoreSigpipe {
 public:
  IgnoreSigpipe() {
    struct sigaction sa {};
    sa.sa_handler = SIG_IGN;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGPIPE, &sa, &old_);
  }
  ~IgnoreSigpipe() { sigaction(SIGPIPE, &old_, nullptr); }
  IgnoreSigpipe(const IgnoreSigpipe&) = delete;
  IgnoreSigpipe& operator=(const IgnoreSigpipe&) = delete;

 private:
  struct sigaction old_;
};

std::string cannot_write(const std::string& path, int err) {
  return "cannot write " + path + ": " + std::strerror(err);
}

class Fd {
 public:
  Fd() = default;
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() { reset(); }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  bool open() const { return fd_ >= 0; }
  void reset(int fd = -1) {
    if (fd_ >= 0) close(fd_);
    fd_ = fd;
  }

 private:
  int fd_ = -1;
};

void make_pipe(Fd& read_end, Fd& write_end) {
  int p[2];
  if (pipe2(p, O_CLOEXEC) != 0) throw std::runtime_error(std::string("cannot create a pipe: ") + std::strerror(errno));
  read_end.reset(p[0]);
  write_end.reset(p[1]);
}

// The running rsvg-convert: killed and reaped at destruction unless reaped
// before (so that every way out of write_png, an exception included, ends it).
class Child {
 public:
  Child() = default;
  ~Child() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      wait_blocking();
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  void set(pid_t pid) { pid_ = pid; }
  pid_t pid() const { return pid_; }
  /// Reaps the child if it has exited; true then (status in status()).
  bool try_reap() {
    BlockSignals b;
    const pid_t r = waitpid(pid_, &status_, WNOHANG);
    if (r == pid_ || (r < 0 && errno == ECHILD)) {
      pid_ = 0;
      g_child = 0;
      return true;
    }
    return false;
  }
  int status() const { return status_; }

 private:
  void wait_blocking() {
    BlockSignals b;
    while (waitpid(pid_, &status_, 0) < 0 && errno == EINTR) {
    }
    pid_ = 0;
    g_child = 0;
  }
  pid_t pid_ = 0;
  int status_ = 0;
};

const char* kNoRsvg =
    "PNG output needs the program rsvg-convert, which is not installed: install the Debian "
    "package librsvg2-bin (apt-get install librsvg2-bin), or write SVG with -o FILE.svg";

// Milliseconds to the calling thread's deadline (at least 0), capped at `cap`.
int poll_timeout_ms(int cap) {
  const Deadline d = current_deadline();
  if (!d.active) return cap;
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(d.at - std::chrono::steady_clock::now());
  return static_cast<int>(std::max<long long>(0, std::min<long long>(cap, left.count() + 1)));
}

}  // namespace

void check_writable(const std::string& path) {
  int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd >= 0) {
    close(fd);
    unlink(path.c_str());
    return;
  }
  if (errno == EEXIST) {
    // an existing file: opened for writing without truncating it
    fd = open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd >= 0) {
      close(fd);
      return;
    }
  }
  throw std::runtime_error(cannot_write(path, errno));
}

void write_file(const std::string& path, const std::string& bytes) {
  const CatchEndingSignals catching;
  struct stat st;
  const bool existed = stat(path.c_str(), &st) == 0;
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) throw std::runtime_error(cannot_write(path, errno));
  if (!existed && path.size() < sizeof g_remove_path) {
    const BlockSignals blocked;
    std::memcpy(g_remove_path, path.c_str(), path.size() + 1);
    g_remove_armed = 1;
  }
  std::size_t off = 0;
  int err = 0;
  while (off < bytes.size()) {
    const ssize_t n = write(fd, bytes.data() + off, bytes.size() - off);
    if (n < 0) {
      if (errno == EINTR) continue;
      err = errno;
      break;
    }
    off += static_cast<std::size_t>(n);
  }
  if (close(fd) != 0 && err == 0) err = errno;
  const BlockSignals blocked;
  if (err != 0 && !existed) unlink(path.c_str());
  g_remove_armed = 0;
  if (err != 0) throw std::runtime_error(cannot_write(path, err));
}

std::string find_rsvg_convert() {
  const char* env = std::getenv("PATH");
  const std::string path = env && *env ? env : "/usr/local/bin:/usr/bin:/bin";
  for (std::size_t i = 0; i <= path.size();) {
    std::size_t j = path.find(':', i);
    if (j == std::string::npos) j = path.size();
    const std::string dir = j == i ? "." : path.substr(i, j - i);
    const std::string candidate = dir + "/rsvg-convert";
    struct stat st;
    if (stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(candidate.c_str(), X_OK) == 0)
      return candidate;
    i = j + 1;
  }
  throw std::runtime_error(kNoRsvg);
}

void write_png(const std::string& svg_text, const std::string& png_path, double zoom) {
  check_time_budget();
  const std::string program = find_rsvg_convert();
  const std::string z = num(zoom);
  std::vector<std::string> args = {"rsvg-convert", "--format", "png", "--zoom", z};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  const CatchEndingSignals catching;
  const IgnoreSigpipe no_sigpipe;
  Fd in_r, in_w, out_r, out_w, err_r, err_w, exec_r, exec_w;
  make_pipe(in_r, in_w);
  make_pipe(out_r, out_w);
  make_pipe(err_r, err_w);
  make_pipe(exec_r, exec_w);  // carries errno if exec fails; closed by a successful exec
  Child child;
  {
    const BlockSignals blocked;
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid == 0) {
      // The child: only async-signal-safe calls until exec.
#ifdef __linux__
      prctl(PR_SET_PDEATHSIG, SIGKILL);
#endif
      if (getppid() != parent) _exit(127);
      struct sigaction dfl {};
      dfl.sa_handler = SIG_DFL;
      sigemptyset(&dfl.sa_mask);
      sigaction(SIGPIPE, &dfl, nullptr);
      auto move = [](int from, int to) {
        if (from == to) return fcntl(to, F_SETFD, 0) == 0;
        return dup2(from, to) == to;
      };
      if (move(in_r.get(), 0) && move(out_w.get(), 1) && move(err_w.get(), 2)) {
        sigset_t none;
        sigemptyset(&none);
        pthread_sigmask(SIG_SETMASK, &none, nullptr);
        execve(program.c_str(), argv.data(), environ);
      }
      const int e = errno;
      ssize_t ignored = write(exec_w.get(), &e, sizeof e);
      (void)ignored;
      _exit(127);
    }
    if (pid < 0) throw std::runtime_error(std::string("cannot run rsvg-convert: ") + std::strerror(errno));
    child.set(pid);
    g_child = pid;
  }
  in_r.reset();
  out_w.reset();
  err_w.reset();
  exec_w.reset();
  int exec_errno = 0;
  for (;;) {
    const ssize_t n = read(exec_r.get(), &exec_errno, sizeof exec_errno);
    if (n < 0 && errno == EINTR) continue;
    if (n != static_cast<ssize_t>(sizeof exec_errno)) exec_errno = 0;
    break;
  }
  if (exec_errno != 0) {
    if (exec_errno == ENOENT) throw std::runtime_error(kNoRsvg);
    throw std::runtime_error("cannot run " + program + ": " + std::strerror(exec_errno));
  }

  // Feed the SVG, collect the PNG and the messages, until the child closes
  // its output or the time budget runs out (then ~Child kills it).
  fcntl(in_w.get(), F_SETFL, fcntl(in_w.get(), F_GETFL) | O_NONBLOCK);
  std::string png, err;
  std::size_t sent = 0;
  if (svg_text.empty()) in_w.reset();
  char buf[65536];
  while (out_r.open() || err_r.open()) {
    check_time_budget();
    pollfd fds[3];
    int n = 0, iin = -1, iout = -1, ierr = -1;
    if (in_w.open()) { fds[n] = {in_w.get(), POLLOUT, 0}; iin = n++; }
    if (out_r.open()) { fds[n] = {out_r.get(), POLLIN, 0}; iout = n++; }
    if (err_r.open()) { fds[n] = {err_r.get(), POLLIN, 0}; ierr = n++; }
    const int r = poll(fds, static_cast<nfds_t>(n), poll_timeout_ms(250));
    if (r < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("waiting for rsvg-convert: ") + std::strerror(errno));
    }
    if (iin >= 0 && fds[iin].revents) {
      const ssize_t w = write(in_w.get(), svg_text.data() + sent, std::min<std::size_t>(svg_text.size() - sent, 65536));
      if (w > 0) sent += static_cast<std::size_t>(w);
      if ((w < 0 && errno != EINTR && errno != EAGAIN) || sent == svg_text.size()) in_w.reset();
    }
    auto drain = [&](int i, Fd& fd, std::string& to, std::size_t cap) {
      if (i < 0 || !fds[i].revents) return;
      const ssize_t k = read(fd.get(), buf, sizeof buf);
      if (k > 0) {
        if (to.size() < cap) to.append(buf, static_cast<std::size_t>(std::min<std::size_t>(k, cap - to.size())));
      } else if (k == 0 || (errno != EINTR && errno != EAGAIN)) {
        fd.reset();
      }
    };
    drain(iout, out_r, png, static_cast<std::size_t>(-1));
    drain(ierr, err_r, err, 65536);
  }
  in_w.reset();
  while (!child.try_reap()) {
    check_time_budget();
    poll(nullptr, 0, std::min(20, poll_timeout_ms(20)));
  }
  const int status = child.status();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
    throw std::runtime_error("rsvg-convert failed writing " + png_path + (err.empty() ? "" : ": " + err));
  }
  write_file(png_path, png);
}

}  // namespace uniparam::cli::svg
