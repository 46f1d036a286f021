// sfit: rows of 3D points to one B-spline surface within tolerance.
#include <sys/stat.h>
#include <CLI/CLI.hpp>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>

#include "cli_common.h"
#include "commands.h"
#include "sfit/error.h"
#include "sfit/version.h"

namespace {

// std::bad_alloc is no sfit::Error (the library lets it through; Python makes it MemoryError):
// its own exit code, documented in docs/errors.md beside the library's 2 ... 8.
constexpr int kOutOfMemoryExit = 10;

// Standard output flushed and without error, or its error line and exit 6: '--help',
// '--version', 'formats' and '-o -' into a full disk or a closed pipe must not say "done".
int finish_stdout(int code) {
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return code;
  const int err = errno;
  std::fprintf(stderr, "sfit: error: standard output: cannot write output: %s\n",
               std::strerror(err ? err : EIO));
  return code != 0 ? code : sfit::exit_code(sfit::ErrorCode::kOutputWrite);
}

// Where an out-of-memory happened, for its one line: the command and the first of its
// arguments that names an existing file (its input), e.g. "fit big.rows".
std::string command_place(int argc, char** argv) {
  std::string out = argc > 1 ? argv[1] : "sfit";
  for (int i = 2; i < argc; ++i) {
    struct stat st {};
    if (argv[i][0] != '-' && ::stat(argv[i], &st) == 0) return out + " " + argv[i];
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  // A closed pipe on standard output is a write error with its line (exit 6), not a silent
  // death by SIGPIPE.
  std::signal(SIGPIPE, SIG_IGN);
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
      "8 internal error (a bug: please report it), 9 cancelled, 10 out of memory,\n"
      "130/143 interrupted by SIGINT/SIGTERM (nothing written). See docs/errors.md.");
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
    return finish_stdout(0);
  } catch (const CLI::CallForAllHelp&) {
    std::printf("%s", app.help("", CLI::AppFormatMode::All).c_str());
    return finish_stdout(0);
  } catch (const CLI::CallForVersion&) {
    std::printf("sfit %s\n", sfit::kVersion);
    return finish_stdout(0);
  } catch (const CLI::ParseError& e) {
    std::string msg = e.what();
    for (char& c : msg)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "sfit: error: %s (see 'sfit --help')\n", msg.c_str());
    return sfit::exit_code(sfit::ErrorCode::kUsage);
  }
  try {
    return finish_stdout(run ? run() : 0);
  } catch (const sfit::Error& e) {
    std::fprintf(stderr, "sfit: error: %s\n", e.what());
    return e.exit_code();
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr,
                 "sfit: error: %s: out of memory: the input or the options need more memory "
                 "than this process can have\n",
                 command_place(argc, argv).c_str());
    return kOutOfMemoryExit;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sfit: error: internal: %s\n", e.what());
    return sfit::exit_code(sfit::ErrorCode::kInternal);
  }
}
