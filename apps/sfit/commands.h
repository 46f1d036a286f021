// The sfit subcommands and output formats; optional parts add theirs here.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace sfit::cli {

/// Each command registers its subcommand and sets `run` to what executes it (returns the
/// process exit code; errors are thrown as sfit::Error).
using Runner = std::function<int()>;

void add_fit_command(CLI::App& app, Runner& run);
void add_convert_command(CLI::App& app, Runner& run);
void add_pack_command(CLI::App& app, Runner& run);
void add_formats_command(CLI::App& app, Runner& run);
void add_options_command(CLI::App& app, Runner& run);
#ifdef SFIT_HAVE_RENDER
void add_render_commands(CLI::App& app, Runner& run);
#endif
#ifdef SFIT_HAVE_SERVER
void add_edit_command(CLI::App& app, Runner& run);
#endif

}  // namespace sfit::cli
