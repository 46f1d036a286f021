#include "sfit/io/rows_binary.h"
#include "sfit/weights.h"

#include <sys/stat.h>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>

#include "input_file.h"
#include "sfit/error.h"
#include "sfit/io/atomic_file.h"

namespace sfit::io {
namespace {

static_assert(std::endian::native == std::endian::little, ".srows is little-endian; add swaps");
constexpr char kMagic[8] = {'S', 'F', 'I', 'T', 'R', 'O', 'W', 'S'};
constexpr std::uint32_t kVersion = 1;
constexpr std::uint64_t kHeaderBytes = 32;
constexpr std::uint32_t kWeighted = 1;

[[noreturn]] void syntax(const std::string& path, const std::string& what) {
  throw Error(ErrorCode::kInputSyntax, "not an sfit binary rows file: " + what,
              Place{.file = path});
}

}  // namespace

bool is_binary_rows_path(const std::string& path) {
  return path.size() > 6 && path.compare(path.size() - 6, 6, ".srows") == 0;
}

RowsFile read_rows_binary(const std::string& path) {
  if (path == "-")
    throw Error(ErrorCode::kUsage, "binary rows are read from a file, not standard input",
                Place{.file = path});
  std::uint64_t size = 0;
  detail::InputFile f = detail::open_input(path, &size);
  unsigned char header[kHeaderBytes];
  if (size < kHeaderBytes || std::fread(header, 1, kHeaderBytes, f.get()) != kHeaderBytes)
    syntax(path, "shorter than its 32-byte header");
  if (std::memcmp(header, kMagic, 8) != 0) syntax(path, "it does not start with SFITROWS");
  std::uint32_t version, flags;
  std::uint64_t M, P;
  std::memcpy(&version, header + 8, 4);
  std::memcpy(&flags, header + 12, 4);
  std::memcpy(&M, header + 16, 8);
  std::memcpy(&P, header + 24, 8);
  if (version != kVersion)
    syntax(path, "version " + std::to_string(version) + " (this sfit reads 1)");
  // Check the sizes before allocating anything: 8 M + 24 P must be exactly what follows.
  // [seams] flags bit 0: P float64 weights follow the points (docs/seams.md).
  if (flags & ~kWeighted) syntax(path, "unknown flags " + std::to_string(flags));
  const std::uint64_t per_point = flags & kWeighted ? 32 : 24;
  if (M > size / 8 || P > size / per_point || kHeaderBytes + 8 * M + per_point * P != size)
    syntax(path, "its size " + std::to_string(size) + " bytes does not match " + std::to_string(M) +
                     " rows and " + std::to_string(P) + " points");
  std::vector<std::uint64_t> lengths(M);
  if (M && std::fread(lengths.data(), 8, M, f.get()) != M) syntax(path, "truncated row lengths");
  std::uint64_t sum = 0;
  for (std::uint64_t j = 0; j < M; ++j) {
    if (lengths[j] == 0)
      throw Error(ErrorCode::kInputData, "row has no points",
                  Place{.file = path, .row = static_cast<long>(j)});
    if (lengths[j] > P - sum)  // never sum += first: crafted lengths could wrap around
      syntax(path, "row lengths add up to more than the " + std::to_string(P) + " points");
    sum += lengths[j];
  }
  if (sum != P)
    syntax(path, "row lengths add up to " + std::to_string(sum) + ", not " + std::to_string(P));
  RowsFile out;
  out.name = path;
  out.rows.reserve(P, M);
  std::vector<Point> block;
  for (std::uint64_t j = 0; j < M; ++j) {
    block.resize(lengths[j]);
    static_assert(sizeof(Point) == 24, "Point must be three packed doubles");
    if (std::fread(block.data(), 24, lengths[j], f.get()) != lengths[j])
      syntax(path, "truncated points");
    for (std::uint64_t k = 0; k < lengths[j]; ++k)
      if (!block[k].allFinite())
        throw Error(ErrorCode::kInputData, "coordinate is not a finite number",
                    Place{.file = path, .row = static_cast<long>(j), .point = static_cast<long>(k)},
                    {block[k].x(), block[k].y(), block[k].z()});
    out.rows.add_row(block);
  }
  if (flags & kWeighted) {
    std::vector<double> w(P);
    if (P && std::fread(w.data(), 8, P, f.get()) != P) syntax(path, "truncated weights");
    for (std::uint64_t j = 0, i = 0; j < M; ++j)
      for (std::uint64_t k = 0; k < lengths[j]; ++k, ++i)
        if (const std::string why = weight_error(w[i]); !why.empty())
          throw Error(
              ErrorCode::kInputData, why,
              Place{.file = path, .row = static_cast<long>(j), .point = static_cast<long>(k)},
              {w[i]});
    out.rows.set_weights(std::move(w));
  }
  out.first_line.clear();  // no lines in a binary file
  return out;
}

void write_rows_binary(const std::string& path, const Rows& rows) {
  write_file_atomically(path, [&](std::ostream& o) {
    char header[kHeaderBytes];
    std::memcpy(header, kMagic, 8);
    const std::uint32_t flags = rows.weighted() ? kWeighted : 0;
    const std::uint64_t M = rows.size(), P = rows.total_points();
    std::memcpy(header + 8, &kVersion, 4);
    std::memcpy(header + 12, &flags, 4);
    std::memcpy(header + 16, &M, 8);
    std::memcpy(header + 24, &P, 8);
    o.write(header, kHeaderBytes);
    for (std::size_t j = 0; j < rows.size(); ++j) {
      const std::uint64_t n = rows[j].size();
      o.write(reinterpret_cast<const char*>(&n), 8);
    }
    o.write(reinterpret_cast<const char*>(rows.points().data()),
            static_cast<std::streamsize>(24 * P));
    if (rows.weighted())
      o.write(reinterpret_cast<const char*>(rows.weights().data()),
              static_cast<std::streamsize>(8 * P));
  });
}

}  // namespace sfit::io
