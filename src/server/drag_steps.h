// Which drag steps a newer one has overtaken (latest wins). A step is skipped only when a
// step of the same client, for the same point, with a greater `seq` arrived AFTER it (while it
// waited for the session): a page that reloads or a second tab starts its own `seq` from 1 and
// is never held back by an older page's numbers, and a huge `seq` holds back only the steps
// that were already waiting when it came.
#pragma once

#include <cstdint>
#include <deque>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

namespace sfit::server {

class DragSteps {
 public:
  /// The largest `seq` taken (JSON's exact integers, 2^53 - 1).
  static constexpr std::uint64_t kMaxSeq = (std::uint64_t{1} << 53) - 1;
  /// Arrivals remembered; an older step is refitted whatever came after it.
  static constexpr std::size_t kRemembered = 256;

  /// Records the arrival of step `seq` of `key` (client and point); returns its ticket.
  std::uint64_t arrive(const std::string& key, std::uint64_t seq);
  /// True when a step of `key` with a greater seq arrived after the step of `ticket`.
  bool overtaken(const std::string& key, std::uint64_t ticket, std::uint64_t seq) const;

 private:
  struct Arrival {
    std::string key;
    std::uint64_t ticket, seq;
  };
  mutable std::mutex mutex_;
  std::deque<Arrival> arrivals_;
  std::uint64_t next_ = 0;
};

/// The `seq` of an edit: a whole number 0 ... DragSteps::kMaxSeq (Error kUsage, field "seq").
std::uint64_t seq_of(const nlohmann::json& seq);

/// The key of a move's drag steps: its optional "client" (a string of at most 64 characters
/// the page draws once per load; Error kUsage, field "client", otherwise), which it removes
/// from `edit`, and the point moved.
std::string client_key(nlohmann::json& edit);

}  // namespace sfit::server
