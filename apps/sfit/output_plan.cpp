#include "output_plan.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "cli_common.h"
#include "outputs.h"
#include "sfit/error.h"
#include "sfit/io/atomic_file.h"
#include "sfit/io/formats.h"

namespace sfit::cli {
namespace {

[[noreturn]] void usage(const std::string& option, const std::string& message) {
  throw Error(ErrorCode::kUsage, message, Place{.option = option});
}

void check_extension(const std::string& path, const std::string& option, OutputTarget t) {
  const std::string e = io::extension_of(path);
  switch (t) {
    case OutputTarget::kSurface:
      check_output_extension(path, option);
      return;
    case OutputTarget::kReport:
      return;  // the report is JSON whatever the name
    case OutputTarget::kPicture:
      if (e != "png") usage(option, "'" + path + "': a picture is written as .png");
      check_output_extension(path, option, io::FormatKind::kPicture);
      return;
    case OutputTarget::kRows:
      if (e != "srows") usage(option, "the output of pack must end in .srows");
      return;
  }
}

}  // namespace

void OutputPlan::add_input(const std::string& path) {
  if (path.empty()) return;
  io::FileIdentity id = path == "-" ? io::identify_descriptor(0) : io::identify_file(path);
  if (id.known && id.exists) inputs_.push_back({path == "-" ? "standard input" : path, id});
}

void OutputPlan::add(const std::string& path, const std::string& option, OutputTarget target) {
  if (path.empty()) usage(option, "empty file name");
  PlannedOutput o{path, option, target, path == "-"};
  if (o.to_stdout) {
    if (target != OutputTarget::kSurface && target != OutputTarget::kReport)
      usage(option, "'-' (standard output) carries JSON only: give a file name");
    for (const auto& p : outputs_)
      if (p.to_stdout)
        usage(option, "standard output ('-') is already the output of " + p.option +
                          ": give each output once");
    outputs_.push_back(o);
    ids_.push_back({});
    return;
  }
  check_extension(path, option, target);
  io::check_writable(path);
  const io::FileIdentity id = io::identify_file(path);
  if (id.known) {
    for (const auto& in : inputs_)
      if (in.id == id)
        usage(option, "'" + path + "' is the input file" +
                          (in.path == path ? std::string() : " '" + in.path + "'") +
                          ": sfit never writes over an input");
    for (std::size_t k = 0; k < outputs_.size(); ++k)
      if (!outputs_[k].to_stdout && ids_[k] == id)
        usage(option,
              "'" + path + "' is already the output of " + outputs_[k].option +
                  (outputs_[k].path == path ? std::string() : " (as '" + outputs_[k].path + "')") +
                  ": give each output once");
  }
  outputs_.push_back(o);
  ids_.push_back(id);
}

void OutputPlan::write_all(const Writer& write) const {
  std::string text;
  std::vector<std::string> what;
  {
    io::OutputBatch batch;
    for (const auto& o : outputs_) what.push_back(write(o, o.to_stdout ? &text : nullptr));
    if (!text.empty()) {
      const bool ok = std::fwrite(text.data(), 1, text.size(), stdout) == text.size() &&
                      std::fflush(stdout) == 0;
      if (!ok)
        throw Error(ErrorCode::kOutputWrite,
                    std::string("cannot write output: ") + std::strerror(errno),
                    Place{.file = "standard output"});
    }
    batch.commit();
  }
  for (std::size_t i = 0; i < outputs_.size(); ++i)
    say((outputs_[i].to_stdout ? "wrote the JSON to standard output"
                               : "wrote " + outputs_[i].path) +
        (what[i].empty() ? "" : " (" + what[i] + ")"));
}

}  // namespace sfit::cli
