// sfit: rows of 3D points to one B-spline surface within tolerance.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <new>

#include "cli_common.h"
#include "commands.h"
#include "sfit/error.h"
#include "sfit/version.h"

int main(int argc, char** argv) {
  CLI::App app{
      "sfit: fits one smooth B-spline surface to rows of 3D points, within a per-axis\n"
      "tolerance, with as few control points as possible, on uniform knots\n"
      "(Vergeest 1989, SFIT01), and checks every data point on the result.",
      "sfit"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("sfit ") + sfit::kVersion);
  app.footer(
      "Run 'sfit COMMAND --help' for the options of a command.\n"
      "Exit codes: 0 ok, 2 usage, 3 input unreadable (also: a STEP/IGES file the CAD kernel\n"
      "crashed on), 4 input syntax, 5 input data, 6 output not written, 7 tolerance not met,\n"
      "8 internal error (a bug: please report it). See docs/errors.md.");
  sfit::cli::Runner run;
  sfit::cli::add_fit_command(app, run);
  sfit::cli::add_convert_command(app, run);
  sfit::cli::add_pack_command(app, run);
  sfit::cli::add_formats_command(app, run);
  sfit::cli::add_options_command(app, run);
#ifdef SFIT_HAVE_RENDER
  sfit::cli::add_render_commands(app, run);
#endif
  sfit::cli::harden_options(app);  // empty values refused, whole numbers read in decimal
#ifdef SFIT_HAVE_SERVER
  sfit::cli::add_edit_command(app, run);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", app.help().c_str());
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::printf("%s", app.help("", CLI::AppFormatMode::All).c_str());
    return 0;
  } catch (const CLI::CallForVersion&) {
    std::printf("sfit %s\n", sfit::kVersion);
    return 0;
  } catch (const CLI::ParseError& e) {
    std::string msg = e.what();
    for (char& c : msg)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "sfit: error: %s (see 'sfit --help')\n", msg.c_str());
    return sfit::exit_code(sfit::ErrorCode::kUsage);
  }
  try {
    return run ? run() : 0;
  } catch (const sfit::Error& e) {
    std::fprintf(stderr, "sfit: error: %s\n", e.what());
    return e.exit_code();
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "sfit: error: out of memory\n");
    return sfit::exit_code(sfit::ErrorCode::kInternal);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sfit: error: internal: %s\n", e.what());
    return sfit::exit_code(sfit::ErrorCode::kInternal);
  }
}
