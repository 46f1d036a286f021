#include "save_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "rows_text.h"
#include "sfit/error.h"

namespace sfit::server {
namespace {

[[noreturn]] void refuse(const std::string& input, const std::string& why) {
  throw Error(ErrorCode::kOutputWrite, "cannot save: " + why + "; nothing written",
              Place{.file = input});
}

std::string octal(mode_t m) {
  char b[8];
  std::snprintf(b, sizeof b, "%04o", static_cast<unsigned>(m & 07777));
  return b;
}

// Writes `text` to a fresh temporary file beside `path` with the mode and owner of `like`;
// returns its name. Throws through refuse().
std::string write_temporary(const std::string& input, const std::string& path,
                            const std::string& text, const struct stat& like) {
  std::string tmp = path + ".sfit-XXXXXX";
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) refuse(input, "cannot create a file beside '" + path + "': " + std::strerror(errno));
  auto fail = [&](const std::string& what) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    ::unlink(tmp.c_str());
    refuse(input, what + " '" + tmp + "': " + why);
  };
  // The owner first: chown clears the set-id bits that fchmod then restores.
  if (::fchown(fd, like.st_uid, like.st_gid) != 0 && errno != EPERM)
    fail("cannot set the owner of");
  if (::fchmod(fd, like.st_mode & 07777) != 0) fail("cannot set the mode of");
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("cannot write");
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) fail("cannot write");
  if (::close(fd) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    refuse(input, "cannot write '" + tmp + "': " + why);
  }
  return tmp;
}

}  // namespace

SaveResult save_rows(const std::string& input, const Rows& rows) {
  SaveResult r;
  r.backup = input + ".bak";
  struct stat link {};
  if (::lstat(input.c_str(), &link) != 0)
    refuse(input, std::string("the file is gone: ") + std::strerror(errno));
  r.target = input;
  if (S_ISLNK(link.st_mode)) {  // write where the link points; the link stays
    char* real = ::realpath(input.c_str(), nullptr);
    if (!real) refuse(input, std::string("its link leads nowhere: ") + std::strerror(errno));
    r.target = real;
    std::free(real);
  }
  struct stat st {};
  if (::stat(r.target.c_str(), &st) != 0)
    refuse(input, "cannot read '" + r.target + "': " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) refuse(input, "'" + r.target + "' is not a regular file");
  if ((st.st_mode & 0222) == 0 || ::access(r.target.c_str(), W_OK) != 0)
    refuse(input, "'" + r.target + "' is read-only (mode " + octal(st.st_mode) + ")");
  if (st.st_nlink > 1)
    refuse(input, "'" + r.target + "' has " + std::to_string(st.st_nlink) +
                      " hard links and saving (a new file renamed over it) would break them; "
                      "copy it to a file of its own to edit it");
  std::string original;
  {
    std::ifstream in(r.target, std::ios::binary);
    if (!in) refuse(input, "cannot read '" + r.target + "'");
    std::ostringstream s;
    s << in.rdbuf();  // an empty file sets s's failbit: nothing to copy
    original = s.str();
  }
  const std::string text = rows_text(rows, original);

  // The backup: created once (link() never replaces), kept from then on.
  struct stat b {};
  if (::lstat(r.backup.c_str(), &b) != 0) {
    const std::string tmp = write_temporary(input, r.backup, original, st);
    if (::link(tmp.c_str(), r.backup.c_str()) == 0) {
      r.backup_written = true;
    } else if (errno != EEXIST) {
      const std::string why = std::strerror(errno);
      ::unlink(tmp.c_str());
      refuse(input, "cannot write the backup '" + r.backup + "': " + why);
    }
    ::unlink(tmp.c_str());
  }

  const std::string tmp = write_temporary(input, r.target, text, st);
  if (std::rename(tmp.c_str(), r.target.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    refuse(input, "cannot replace '" + r.target + "': " + why);
  }
  return r;
}

}  // namespace sfit::server
