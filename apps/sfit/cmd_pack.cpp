// sfit pack: rows to the binary .srows form, for big inputs read many times.
#include <memory>

#include "cli_common.h"
#include "commands.h"
#include "output_plan.h"
#include "sfit/error.h"
#include "sfit/io/atomic_file.h"
#include "sfit/io/rows_binary.h"

namespace sfit::cli {
namespace {

struct PackArgs {
  std::string input, output;
  bool quiet = false;
};

int run_pack(const PackArgs& a) {
  verbose = !a.quiet;
  OutputPlan plan;
  plan.add_input(a.input);
  plan.add(a.output, "-o", OutputTarget::kRows);
  const Input in = read_input(a.input);
  say(in.name + ": " + std::to_string(in.rows.size()) + " rows, " +
      std::to_string(in.rows.total_points()) + " points");
  plan.write_all([&](const PlannedOutput& out, std::string*) {
    io::write_rows_binary(out.path, in.rows);
    return std::string();
  });
  return 0;
}

}  // namespace

void add_pack_command(CLI::App& app, Runner& run) {
  auto args = std::make_shared<PackArgs>();
  CLI::App* c = app.add_subcommand("pack", "write rows in the binary .srows form (fast to read)");
  c->add_option("INPUT", args->input, "rows of points (any input sfit fit reads)")->required();
  c->add_option("-o,--output", args->output, "output file, ending in .srows")->required();
  c->add_flag("-q,--quiet", args->quiet, "print errors only");
  c->footer("Example:\n  sfit pack scan.rows -o scan.srows && sfit fit scan.srows -o scan.json");
  c->callback([args, &run] { run = [args] { return run_pack(*args); }; });
}

}  // namespace sfit::cli
