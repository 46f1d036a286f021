#include "input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "sfit/error.h"

namespace sfit::io::detail {

InputFile open_input(const std::string& path, std::uint64_t* size) {
  if (size) *size = 0;
  if (path == "-") return InputFile(stdin);
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw Error(ErrorCode::kInputUnreadable,
                std::string("cannot open input: ") + std::strerror(errno), Place{.file = path});
  if (S_ISDIR(st.st_mode))
    throw Error(ErrorCode::kInputUnreadable, "cannot read input: it is a directory",
                Place{.file = path});
  InputFile f(std::fopen(path.c_str(), "rb"));
  if (!f)
    throw Error(ErrorCode::kInputUnreadable,
                std::string("cannot open input: ") + std::strerror(errno), Place{.file = path});
  if (size) *size = static_cast<std::uint64_t>(st.st_size);
  return f;
}

}  // namespace sfit::io::detail
