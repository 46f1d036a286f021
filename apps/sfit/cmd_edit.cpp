// sfit edit: the browser editor (src/server, editor/; docs/editor.md).
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "cli_common.h"
#include "commands.h"
#include "outputs.h"
#include "sfit/error.h"
#include "sfit/server/editor.h"

extern char** environ;

namespace sfit::cli {
namespace {

struct EditArgs : FitOptionArgs {
  std::string input;
  int port = 0;
  bool no_browser = false;
  bool quiet = false;
  std::string units = "mm";
};

// Opens `url` in the user's browser (xdg-open), without waiting for it or failing if absent.
void open_browser(const std::string& url) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  std::string prog = "xdg-open";
  char* argv[] = {prog.data(), const_cast<char*>(url.c_str()), nullptr};
  pid_t pid = 0;
  if (posix_spawnp(&pid, prog.c_str(), &fa, nullptr, argv, environ) != 0)
    say("could not start xdg-open: open the address above yourself");
  posix_spawn_file_actions_destroy(&fa);
}

int run_edit(const EditArgs& a) {
  if (a.input == "-")
    throw Error(ErrorCode::kUsage, "edit needs a file (its rows are saved back to it)",
                Place{.option = "INPUT"});
  verbose = !a.quiet;
  const CheckedFitOptions checked = check_fit_options(a);
  check_output_options(a.units, 0);
  Input in = read_input(a.input);
  server::EditorConfig config;
  config.input = a.input;
  config.options = checked.options;
  note_closed_rows(in, config.options.closed_u, !a.closed().empty(), &config.closed_note);
  config.units = in.units.empty() ? a.units : in.units;
  config.options.tolerance = checked.tolerance(in.rows);
  const std::vector<long> first_line = in.first_line;
  config.rows = std::move(in.rows);
  config.port = a.port;
  const std::string units = a.units, name = in.name;
  config.write = [units, name](const std::string& path, const FitResult& fit, const Rows& rows) {
    OutputContext ctx{fit.surface, &fit, &rows, name, false, 0, false, units};
    write_output(path, ctx);  // atomic: a temporary file renamed
  };
  config.export_formats = output_extensions();
  say("fitting " + a.input + " ...");
  std::unique_ptr<server::EditorServer> server;
  try {
    server = std::make_unique<server::EditorServer>(std::move(config));
  } catch (const Error& e) {
    // The first fit's errors name rows and points: say in which file, at which line (as
    // sfit fit does).
    if (!e.place().file.empty() || !e.place().option.empty()) throw;
    Place p = e.place();
    p.file = name;
    if (p.row >= 0 && p.row < static_cast<long>(first_line.size()))
      p.line = first_line[static_cast<std::size_t>(p.row)] + std::max(0L, p.point);
    throw Error(e.code(), e.message(), p, e.values());
  }
  if (const std::string why = server->best_effort(); !why.empty())
    say("warning: no surface within T (" + why + "); the editor shows the best found");
  const bool clean = server::serve_until_signal(*server, [&] {
    std::fprintf(stderr, "sfit: editing %s at %s\n", a.input.c_str(), server->url().c_str());
    std::fflush(stderr);
    if (!a.no_browser) open_browser(server->url());
  });
  if (!clean) {
    // A refit still runs (the signal came during a long one): it is abandoned, not awaited;
    // it writes nothing, and a save or an export is a rename of a finished file.
    say("stopped (the refit under way was abandoned)");
    std::fflush(stderr);
    std::_Exit(0);
  }
  say("stopped");
  return 0;
}

}  // namespace

void add_edit_command(CLI::App& app, Runner& run) {
  auto args = std::make_shared<EditArgs>();
  CLI::App* c = app.add_subcommand(
      "edit", "edit the rows in the browser; the surface follows (docs/editor.md)");
  c->add_option("INPUT", args->input,
                "rows of points: .rows (saved back to it) or .csv, .step, .iges (exported only)")
      ->required();
  add_fit_option_flags(c, *args);
  c->add_option("--port", args->port, "port on 127.0.0.1 (0, the default: a free one)")
      ->check(CLI::Range(0, 65535));
  c->add_flag("--no-browser", args->no_browser, "do not open the browser; print the address only");
  c->add_option("--units", args->units,
                "length unit that exported STEP/IGES files state (mm, cm, m, ...)")
      ->default_val("mm");
  c->add_flag("-q,--quiet", args->quiet, "print the address and errors only");
  c->footer(
      "Prints 'sfit: editing INPUT at http://127.0.0.1:PORT/?token=TOKEN' and serves the\n"
      "editor there until Ctrl-C. Example:\n"
      "  sfit edit examples/ship_px121_stations.rows --tol 0.05 --no-browser");
  c->callback([args, &run] { run = [args] { return run_edit(*args); }; });
}

}  // namespace sfit::cli
