#include "cli_common.h"

#include <charconv>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "sfit/error.h"
#include "sfit/io/csv_reader.h"
#include "sfit/io/rows_binary.h"
#include "sfit/io/rows_reader.h"
#ifdef SFIT_HAVE_EXCHANGE
#include "sfit/exchange/readers.h"
#endif

namespace sfit::cli {

bool verbose = true;

void say(const std::string& line) {
  if (verbose) std::fprintf(stderr, "sfit: %s\n", line.c_str());
}

Point parse_tolerance(const std::string& text, const std::string& option) {
  std::vector<double> v;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string tok = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    double x = 0;
    const char* b = tok.data();
    const char* e = b + tok.size();
    if (b != e && *b == '+') ++b;
    const auto r = std::from_chars(b, e, x);
    if (tok.empty() || r.ec != std::errc() || r.ptr != e)
      throw Error(ErrorCode::kUsage, "'" + tok + "' is not a number (expected T or Tx,Ty,Tz)",
                  Place{.option = option});
    if (!std::isfinite(x) || x < 0)
      throw Error(ErrorCode::kUsage, "tolerance must be a finite number >= 0, got '" + tok + "'",
                  Place{.option = option}, {x});
    v.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (v.size() == 1) return Point::Constant(v[0]);
  if (v.size() == 3) return Point(v[0], v[1], v[2]);
  throw Error(ErrorCode::kUsage,
              "expected one tolerance or three (Tx,Ty,Tz), got " + std::to_string(v.size()),
              Place{.option = option});
}

Input read_input(const std::string& path) {
  const auto dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == "csv") {
    auto r = io::read_csv(path);
    return Input{std::move(r.rows), std::move(r.first_line), std::move(r.name)};
  }
#ifdef SFIT_HAVE_EXCHANGE
  if (exchange::is_exchange_input(path)) {
    auto r = exchange::read_sections(path);
    return Input{std::move(r.rows), std::move(r.first_line), path};
  }
#endif
  if (io::is_binary_rows_path(path)) {
    auto r = io::read_rows_binary(path);
    return Input{std::move(r.rows), std::move(r.first_line), std::move(r.name)};
  }
  auto r = io::read_rows(path);
  return Input{std::move(r.rows), std::move(r.first_line), std::move(r.name)};
}

}  // namespace sfit::cli
