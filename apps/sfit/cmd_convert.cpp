// sfit convert: re-export a saved surface.
#include <memory>

#include "cli_common.h"
#include "commands.h"
#include "output_plan.h"
#include "outputs.h"
#include "sfit/error.h"
#include "sfit/io/atomic_file.h"
#include "sfit/io/surface_json.h"

namespace sfit::cli {
namespace {

struct ConvertArgs {
  std::string input;
  std::vector<std::string> outputs;
  OutputShapeArgs shape{.units = "mm"};
  bool quiet = false;
};

int run_convert(const ConvertArgs& a) {
  verbose = !a.quiet;
  if (a.outputs.empty())
    throw Error(ErrorCode::kUsage, "nothing to write: give -o OUT.ext", Place{.option = "-o"});
  OutputPlan plan;
  plan.add_input(a.input);
  plan.add(a.outputs, "-o", OutputTarget::kSurface);
  check_output_options(a.shape.units, a.shape.mesh_density, a.shape.normals);
  const Surface s = io::read_surface_json(a.input);
  const OutputContext ctx = output_context(a.shape, s, nullptr, nullptr, a.input, a.shape.units);
  plan.write_all([&](const PlannedOutput& out, std::string* text) {
    return write_output(out.path, ctx, text);
  });
  return 0;
}

}  // namespace

void add_convert_command(CLI::App& app, Runner& run) {
  auto args = std::make_shared<ConvertArgs>();
  CLI::App* c = app.add_subcommand("convert", "re-export a saved surface (.json) to other formats");
  c->add_option("SURFACE", args->input, "surface file written by 'sfit fit' (.json)")->required();
  c->add_option("-o,--output", args->outputs, "output file(s); the extension picks the format");
  add_output_shape_options(c, args->shape);  // --mesh ... --units (docs/meshes.md)
  c->add_flag("-q,--quiet", args->quiet, "print errors only");
  c->footer("Example:\n  sfit convert hull.json -o hull.step -o hull.stl");
  c->callback([args, &run] { run = [args] { return run_convert(*args); }; });
}

}  // namespace sfit::cli
