// The reader of sfit/files.h: every input format of the registry, chosen by the extension.
#include "sfit/error.h"
#include "sfit/files.h"
#include "sfit/io/csv_reader.h"
#include "sfit/io/rows_binary.h"
#include "sfit/io/rows_reader.h"
#ifdef SFIT_HAVE_EXCHANGE
#include "sfit/exchange/readers.h"
#endif

namespace sfit::files {

Input read_input(const std::string& path) {
  // Dispatch through the one format registry (sfit/io/formats.h); '-' and unknown
  // extensions are .rows text.
  const std::string ext = path == "-" ? "rows" : io::extension_of(path);
  const io::Format* f = io::find_format(ext);
  const bool rows_format =
      f && f->reads && (f->kind == io::FormatKind::kRows || f->part == io::FormatPart::kCad);
  if (rows_format && !f->available)
    throw Error(ErrorCode::kUsage,
                std::string(f->name) + " input needs " + std::string(io::part_name(f->part)) +
                    ", which this build of sfit lacks",
                Place{.file = path});
  const io::FormatId id = rows_format ? f->id : io::FormatId::kRows;
  if (id == io::FormatId::kCsv) {
    auto r = io::read_csv(path);
    return Input{std::move(r.rows), std::move(r.first_line), std::move(r.name)};
  }
#ifdef SFIT_HAVE_EXCHANGE
  if (id == io::FormatId::kStep || id == io::FormatId::kIges) {
    auto r = exchange::read_sections(path);
    return Input{std::move(r.rows), std::move(r.first_line), path, std::move(r.closed),
                 std::move(r.units)};
  }
#endif
  if (id == io::FormatId::kBinaryRows) {
    auto r = io::read_rows_binary(path);
    return Input{std::move(r.rows), std::move(r.first_line), std::move(r.name)};
  }
  auto r = io::read_rows(path);
  return Input{std::move(r.rows), std::move(r.first_line), std::move(r.name)};
}

}  // namespace sfit::files
