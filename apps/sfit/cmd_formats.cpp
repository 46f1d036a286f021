// sfit formats: the format registry (include/sfit/io/formats.h) as a table.
#include <fmt/format.h>

#include <cstdio>
#include <memory>

#include "commands.h"
#include "sfit/error.h"
#include "sfit/io/formats.h"
#ifdef SFIT_HAVE_EXCHANGE
#include "sfit/exchange/cad_writers.h"
#endif

namespace sfit::cli {

namespace {

// Whether this build has the format now: STEP and IGES also need their module to load
// (libsfit_cad.so, loaded on first use).
const char* available(const io::Format& f) {
  if (!f.available) return "no";
#ifdef SFIT_HAVE_EXCHANGE
  if (f.part == io::FormatPart::kCad) {
    try {
      exchange::require_cad("");
    } catch (const Error&) {
      return "no module";
    }
  }
#endif
  return "yes";
}

}  // namespace

void add_formats_command(CLI::App& app, Runner& run) {
  CLI::App* c = app.add_subcommand("formats", "list the file formats this build reads and writes");
  c->footer("Example:\n  sfit formats");
  c->callback([&run] {
    run = [] {
      std::printf("%-14s %-11s %-6s %-6s %-10s %s\n", "format", "extensions", "reads", "writes",
                  "this build", "what");
      for (const io::Format& f : io::formats()) {
        std::string ext;
        for (auto e : f.extensions) ext += (ext.empty() ? "." : " .") + std::string(e);
        std::printf("%-14s %-11s %-6s %-6s %-10s %s\n", std::string(f.name).c_str(), ext.c_str(),
                    f.reads ? "yes" : "-", f.writes ? "yes" : "-", available(f),
                    std::string(f.description).c_str());
      }
      return 0;
    };
  });
}

}  // namespace sfit::cli
