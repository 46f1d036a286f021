// Reading 10^6 points: the .rows text reader against the binary .srows reader.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "sfit/io/rows_binary.h"
#include "sfit/io/rows_reader.h"
#include "synthetic.h"

namespace sfit::bench {
namespace {

const std::string& text_file() {
  static const std::string path = [] {
    const std::string p = (std::filesystem::temp_directory_path() / "sfit-bench-1m.rows").string();
    const Rows rows = grid(1000, 1000);
    std::ofstream out(p);
    char buf[128];
    for (std::size_t j = 0; j < rows.size(); ++j) {
      for (const Point& q : rows[j]) {
        std::snprintf(buf, sizeof buf, "%.9g %.9g %.9g\n", q.x(), q.y(), q.z());
        out << buf;
      }
      out << '\n';
    }
    return p;
  }();
  return path;
}

const std::string& binary_file() {
  static const std::string path = [] {
    const std::string p = (std::filesystem::temp_directory_path() / "sfit-bench-1m.srows").string();
    io::write_rows_binary(p, io::read_rows(text_file()).rows);
    return p;
  }();
  return path;
}

void BM_ReadText(benchmark::State& state) {
  const std::string& p = text_file();
  for (auto _ : state) benchmark::DoNotOptimize(io::read_rows(p));
  state.SetItemsProcessed(state.iterations() * 1000000);
  state.SetBytesProcessed(state.iterations() * static_cast<long>(std::filesystem::file_size(p)));
}
BENCHMARK(BM_ReadText)->Unit(benchmark::kMillisecond);

void BM_ReadBinary(benchmark::State& state) {
  const std::string& p = binary_file();
  for (auto _ : state) benchmark::DoNotOptimize(io::read_rows_binary(p));
  state.SetItemsProcessed(state.iterations() * 1000000);
}
BENCHMARK(BM_ReadBinary)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sfit::bench

BENCHMARK_MAIN();
