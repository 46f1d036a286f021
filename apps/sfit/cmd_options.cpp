// sfit options: the library's option table (include/sfit/options.h), as text, Markdown
// (docs/options.md) or JSON (what the editor reads).
#include <cstdio>
#include <memory>
#include <string>

#include "commands.h"
#include "sfit/io/options_json.h"
#include "sfit/options.h"

namespace sfit::cli {

void add_options_command(CLI::App& app, Runner& run) {
  auto format = std::make_shared<std::string>("text");
  CLI::App* c = app.add_subcommand(
      "options", "list every fit option: flag, Python keyword, type, default, allowed values");
  c->add_option("--format", *format, "text (default), markdown (docs/options.md) or json")
      ->check(CLI::IsMember({"text", "markdown", "json"}));
  c->footer("Example:\n  sfit options --format json");
  c->callback([format, &run] {
    run = [format] {
      if (*format == "markdown") {
        std::fputs(option_table_markdown().c_str(), stdout);
      } else if (*format == "json") {
        std::puts(io::option_table_json().dump(2).c_str());
      } else {
        for (const OptionSpec& s : option_table())
          std::printf(
              "%-16s %-14s %-6s %-9s %s\n", std::string(s.flag).c_str(),
              std::string(s.name).c_str(), std::string(to_string(s.group)).c_str(),
              std::string(to_string(s.type)).c_str(),
              (full_help(s) + (s.choices.empty() ? "" : "; one of " + choice_list(s))).c_str());
      }
      return 0;
    };
  });
}

}  // namespace sfit::cli
