// libFuzzer target: the .rows reader (parse_rows) on arbitrary bytes. It must return rows of
// finite points with a first line per row, or throw Error(kInputSyntax / kInputData) with
// one line; nothing else (no crash, no other exception, no sanitizer report).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_common.h"
#include "sfit/io/rows_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sfit;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const io::RowsFile f = io::parse_rows(text, "fuzz.rows");
    if (f.rows.empty() || f.rows.total_points() == 0) fuzz::finding("rows returned without points");
    if (f.first_line.size() != f.rows.size()) fuzz::finding("first_line does not match the rows");
    long previous = 0;
    for (std::size_t j = 0; j < f.rows.size(); ++j) {
      if (f.rows[j].empty()) fuzz::finding("an empty row returned");
      if (f.first_line[j] <= previous) fuzz::finding("first lines not increasing");
      previous = f.first_line[j];
      for (const Point& p : f.rows[j])
        if (!p.allFinite()) fuzz::finding("a non-finite coordinate returned");
    }
  } catch (const Error& e) {
    fuzz::check_error(e, ErrorCode::kInputSyntax, ErrorCode::kInputData);
  }
  return 0;
}
