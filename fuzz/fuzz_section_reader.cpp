// libFuzzer target: the STEP/IGES section reader (exchange::read_sections) on arbitrary bytes,
// the first byte choosing STEP or IGES. Whatever OpenCASCADE does with the file (it crashes
// on many hostile files), sfit must answer with rows of finite points in range, one closed
// flag per row and a unit, or throw Error(kInputUnreadable / kInputSyntax / kInputData) with
// one line; nothing else. OpenCASCADE runs in a child process, so libFuzzer's coverage is
// that of sfit's side (the answer's decoding and checks); the seeds (make_section_seeds)
// and the mutations carry the CAD kernel's paths.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "fuzz_common.h"
#include "sfit/exchange/readers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sfit;
  if (size < 1) return 0;
  static const std::string base = "/tmp/sfit-fuzz-section-" + std::to_string(::getpid());
  const std::string path = base + ((data[0] & 1) ? ".igs" : ".step");
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return 0;
    std::fwrite(data + 1, 1, size - 1, f);
    std::fclose(f);
  }
  try {
    exchange::SectionReadOptions o;
    o.timeout_seconds = 5;
    const exchange::SectionsFile s = exchange::read_sections(path, o);
    if (s.rows.empty()) fuzz::finding("sections returned without rows");
    if (s.closed.size() != s.rows.size()) fuzz::finding("closed flags do not match the rows");
    if (s.units.empty()) fuzz::finding("no unit returned");
    for (std::size_t j = 0; j < s.rows.size(); ++j) {
      if (s.rows[j].empty()) fuzz::finding("an empty row returned");
      for (const Point& p : s.rows[j])
        if (!p.allFinite() || p.cwiseAbs().maxCoeff() > 1e150)
          fuzz::finding("a coordinate out of range returned");
    }
  } catch (const Error& e) {
    fuzz::check_error(e, ErrorCode::kInputUnreadable, ErrorCode::kInputSyntax,
                      ErrorCode::kInputData);
  }
  std::remove(path.c_str());
  return 0;
}
