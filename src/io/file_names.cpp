#include "sfit/io/file_names.h"

#include <sys/stat.h>

#include <cctype>
#include <filesystem>

namespace sfit::io {

std::string extension_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

FileIdentity identify_file(const std::string& path) {
  FileIdentity id;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id.known = id.exists = true;
    id.device = st.st_dev;
    id.inode = st.st_ino;
    return id;
  }
  const std::filesystem::path p(path);
  std::string dir = p.parent_path().string();
  if (dir.empty()) dir = ".";
  if (::stat(dir.c_str(), &st) != 0) return id;
  id.known = true;
  id.device = st.st_dev;
  id.inode = st.st_ino;
  id.leaf = p.filename().string();
  return id;
}

FileIdentity identify_descriptor(int fd) {
  FileIdentity id;
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) return id;
  id.known = id.exists = true;
  id.device = st.st_dev;
  id.inode = st.st_ino;
  return id;
}

}  // namespace sfit::io
