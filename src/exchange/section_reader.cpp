// Section curves from STEP/IGES files, read by OpenCASCADE in a child process (section_child.h)
// so that nothing the CAD kernel does with a bad file can take the caller down.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>

#include "cad_module.h"
#include "section_child.h"
#include "sfit/error.h"
#include "sfit/exchange/readers.h"
#include "sfit/io/file_names.h"

namespace sfit::exchange {

namespace {

[[noreturn]] void fail(ErrorCode code, const std::string& path, const std::string& msg,
                       long row = -1) {
  throw Error(code, msg, Place{.file = path, .row = row});
}

// --- the child's answer on the pipe ----------------------------------------------------------
// 'R' units rows { closed n x y z ... }  or  'E' code row message.
void put(std::string& b, const void* p, std::size_t n) {
  b.append(static_cast<const char*>(p), n);
}
template <class T>
void put(std::string& b, T v) {
  put(b, &v, sizeof v);
}
void put_text(std::string& b, const std::string& s) {
  put<std::uint32_t>(b, static_cast<std::uint32_t>(s.size()));
  b += s;
}

struct Cursor {
  const std::string& b;
  std::size_t at = 0;
  bool ok = true;
  template <class T>
  T get() {
    T v{};
    if (at + sizeof v > b.size()) {
      ok = false;
      return v;
    }
    std::memcpy(&v, b.data() + at, sizeof v);
    at += sizeof v;
    return v;
  }
  std::string text() {
    const auto n = get<std::uint32_t>();
    if (!ok || at + n > b.size()) {
      ok = false;
      return {};
    }
    std::string s = b.substr(at, n);
    at += n;
    return s;
  }
};

std::string encode(const SectionsFile& f) {
  std::string b = "R";
  put_text(b, f.units);
  put<std::uint64_t>(b, f.rows.size());
  for (std::size_t j = 0; j < f.rows.size(); ++j) {
    const auto row = f.rows[j];
    put<std::uint8_t>(b, j < f.closed.size() && f.closed[j] ? 1 : 0);
    put<std::uint64_t>(b, row.size());
    put(b, row.data(), row.size() * sizeof(Point));
  }
  return b;
}

std::string encode(const Error& e) {
  std::string b = "E";
  put<std::int32_t>(b, static_cast<std::int32_t>(e.code()));
  put<std::int64_t>(b, e.place().row);
  put_text(b, e.message());
  return b;
}

// Decodes the child's answer; false if it is not a whole one.
bool decode(const std::string& b, const std::string& path, SectionsFile& out) {
  if (b.empty()) return false;
  Cursor c{b, 1};
  if (b[0] == 'E') {
    const auto code = c.get<std::int32_t>();
    const auto row = c.get<std::int64_t>();
    const std::string msg = c.text();
    if (!c.ok || code < 0 || code > static_cast<int>(ErrorCode::kInternal)) return false;
    fail(static_cast<ErrorCode>(code), path, msg, static_cast<long>(row));
  }
  if (b[0] != 'R') return false;
  out.units = c.text();
  const auto rows = c.get<std::uint64_t>();
  if (!c.ok || rows > b.size()) return false;
  std::vector<Point> pts;
  for (std::uint64_t j = 0; j < rows; ++j) {
    out.closed.push_back(c.get<std::uint8_t>() != 0);
    const auto n = c.get<std::uint64_t>();
    if (!c.ok || n > (b.size() - c.at) / sizeof(Point)) return false;
    pts.resize(n);
    std::memcpy(static_cast<void*>(pts.data()), b.data() + c.at, n * sizeof(Point));
    c.at += n * sizeof(Point);
    out.rows.add_row(pts);
  }
  return c.ok && c.at == b.size();
}

// Reads `fd` to its end onto `b`, waiting for it at most `timeout_seconds`; false where the
// time ran out first.
bool read_all(int fd, double timeout_seconds, std::string& b) {
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_seconds);
  char buf[1 << 16];
  while (true) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - std::chrono::steady_clock::now())
                          .count();
    if (left <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    const int r = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1000)));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) continue;
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return true;
    b.append(buf, static_cast<std::size_t>(n));
  }
}

// Writes all of `b` to `fd` (as much as the reader takes: it may be gone).
void write_all(int fd, const std::string& b) {
  std::size_t done = 0;
  while (done < b.size()) {
    const ssize_t n = ::write(fd, b.data() + done, b.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

[[noreturn]] void child(const std::string& path, int fd, const detail::CadModule& cad) {
  // Die of a crash rather than handle it (a sanitizer's or test framework's handlers are
  // inherited); no core file; OpenCASCADE's console messages go nowhere.
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGALRM, SIGTERM})
    ::signal(sig, SIG_DFL);
  ::signal(SIGPIPE, SIG_IGN);
  rlimit core{0, 0};
  ::setrlimit(RLIMIT_CORE, &core);
  const int null = ::open("/dev/null", O_WRONLY);
  if (null >= 0) {
    ::dup2(null, 1);
    ::dup2(null, 2);
  }
  std::string answer;
  try {
    answer = encode(cad.read_sections_here(path));
  } catch (const Error& e) {
    answer = encode(e);
  } catch (const std::bad_alloc&) {
    answer = encode(Error(ErrorCode::kInputData, "cannot read the file: out of memory"));
  } catch (...) {
    answer = encode(
        Error(ErrorCode::kInputUnreadable, "cannot read the file: the CAD kernel failed on it"));
  }
  write_all(fd, answer);
  ::_exit(0);
}

std::string describe_status(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = ::strsignal(sig);
    return "OpenCASCADE crashed on it (signal " + std::to_string(sig) + ", " +
           (name ? name : "unknown") + ")";
  }
  if (WIFEXITED(status))
    return "the reader stopped (exit " + std::to_string(WEXITSTATUS(status)) + ")";
  return "the reader stopped";
}

}  // namespace

bool is_exchange_input(const std::string& path) {
  const std::string e = io::extension_of(path);
  return detail::is_step_extension(e) || detail::is_iges_extension(e);
}

SectionsFile read_sections(const std::string& path, const SectionReadOptions& options) {
  const std::string ext = io::extension_of(path);
  if (!is_exchange_input(path))
    fail(ErrorCode::kUsage, path, "not a STEP (.step, .stp) or IGES (.igs, .iges) file name");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    fail(ErrorCode::kInputUnreadable, path,
         std::string("cannot open input: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode))
    fail(ErrorCode::kInputUnreadable, path, "cannot read input: it is a directory");
  if (!std::ifstream(path, std::ios::binary))
    fail(ErrorCode::kInputUnreadable, path,
         std::string("cannot open input: ") + std::strerror(errno));
  if (st.st_size == 0) fail(ErrorCode::kInputSyntax, path, "empty file: not a STEP or IGES file");

  // Loaded here: the child only calls it (no loading, no lock after the fork).
  const detail::CadModule& cad = detail::cad_module(Place{.file = path});
  SectionsFile out;
  if (!options.isolate) {
    out = cad.read_sections_here(path);
  } else {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0)
      fail(ErrorCode::kInputUnreadable, path,
           std::string("cannot read the file: no pipe for the reader: ") + std::strerror(errno));
    std::fflush(nullptr);  // nothing buffered is written twice
    const pid_t pid = ::fork();
    if (pid < 0) {
      ::close(fds[0]);
      ::close(fds[1]);
      fail(ErrorCode::kInputUnreadable, path,
           std::string("cannot read the file: cannot start the reader: ") + std::strerror(errno));
    }
    if (pid == 0) {
      ::close(fds[0]);
      child(path, fds[1], cad);
    }
    ::close(fds[1]);
    std::string answer;
    const bool timed_out = !read_all(fds[0], options.timeout_seconds, answer);
    ::close(fds[0]);
    if (timed_out) ::kill(pid, SIGKILL);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (timed_out)
      fail(ErrorCode::kInputUnreadable, path,
           "cannot read the file: OpenCASCADE did not finish reading it in " +
               std::to_string(static_cast<int>(options.timeout_seconds)) + " s");
    const bool clean = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (!clean || !decode(answer, path, out))
      fail(ErrorCode::kInputUnreadable, path,
           "cannot read the file: " +
               (clean ? std::string("the reader gave no whole answer") : describe_status(status)));
  }
  out.name = path;
  out.first_line.clear();
  detail::check_sections(out, path);
  return out;
}

}  // namespace sfit::exchange
