// One plan of every output of a command, built and checked before any input is read:
// each path resolved once, refused when it is an input file or named twice (by any spelling or
// link), its format known and its folder writable; then every output written to a temporary
// file beside its target and renamed only when all of them succeeded (io::OutputBatch).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sfit/io/file_names.h"

namespace sfit::cli {

/// What an output holds; decides which extensions it accepts.
enum class OutputTarget {
  kSurface,  ///< -o: any surface format of the registry (include/sfit/io/formats.h); '-' is JSON
  kReport,   ///< --report: the fit report as JSON; '-' is standard output
  kPicture,  ///< --png, render -o: .png
  kRows,     ///< pack -o: .srows
};

struct PlannedOutput {
  std::string path;    ///< as given
  std::string option;  ///< the option that named it, for messages
  OutputTarget target;
  bool to_stdout = false;  ///< path "-": JSON on standard output
};

class OutputPlan {
 public:
  /// An input this command reads: no output may be the same file. "-" is standard input
  /// (protected when it is redirected from a file).
  void add_input(const std::string& path);
  /// Adds and checks one output now. Throws Error(kUsage) naming `option` for an unknown or
  /// unavailable format, an empty name, an input file, or a file named twice;
  /// Error(kOutputWrite) naming the file when its folder is missing or not writable.
  void add(const std::string& path, const std::string& option, OutputTarget target);
  void add(const std::vector<std::string>& paths, const std::string& option, OutputTarget target) {
    for (const auto& p : paths) add(p, option, target);
  }

  bool empty() const { return outputs_.empty(); }
  const std::vector<PlannedOutput>& outputs() const { return outputs_; }

  /// Writes every output through `write(output, text)`: a file output is written to its path
  /// (the writers' atomic writes are held back by an io::OutputBatch); a standard-output one
  /// fills `*text` instead. Standard output is written, then every file renamed onto its
  /// target, only when every writer succeeded; then "wrote PATH" is said for each, followed by
  /// what its writer returned (a few words on what was written; empty: nothing more).
  /// On any error nothing is left: every existing file as it was, no new file.
  using Writer = std::function<std::string(const PlannedOutput&, std::string* text)>;
  void write_all(const Writer& write) const;

 private:
  struct Input {
    std::string path;
    io::FileIdentity id;
  };
  std::vector<Input> inputs_;
  std::vector<PlannedOutput> outputs_;
  std::vector<io::FileIdentity> ids_;
};

}  // namespace sfit::cli
