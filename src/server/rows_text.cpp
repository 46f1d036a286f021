#include "rows_text.h"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "sfit/error.h"
#include "sfit/io/atomic_file.h"

namespace sfit::server {

void save_rows(const std::string& path, const Rows& rows, bool first_save) {
  std::string original;
  {
    std::ifstream in(path, std::ios::binary);
    if (in) {
      std::ostringstream s;
      s << in.rdbuf();
      original = s.str();
    }
  }
  std::string header;
  std::istringstream lines(original);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind('#', 0) != 0) break;
    header += line + "\n";
  }
  if (first_save)
    io::write_file_atomically(path + ".bak", [&](std::ostream& out) { out << original; });
  io::write_file_atomically(path, [&](std::ostream& out) {
    out << header;
    fmt::memory_buffer b;
    for (std::size_t j = 0; j < rows.size(); ++j) {
      if (j > 0) b.push_back('\n');
      for (const Point& p : rows[j])
        fmt::format_to(std::back_inserter(b), "{} {} {}\n", p.x(), p.y(), p.z());
      out.write(b.data(), static_cast<std::streamsize>(b.size()));
      b.clear();
    }
  });
}

}  // namespace sfit::server
