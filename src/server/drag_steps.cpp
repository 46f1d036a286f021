#include "drag_steps.h"

#include "sfit/error.h"

namespace sfit::server {

std::uint64_t DragSteps::arrive(const std::string& key, std::uint64_t seq) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::uint64_t ticket = next_++;
  arrivals_.push_back(Arrival{key, ticket, seq});
  if (arrivals_.size() > kRemembered) arrivals_.pop_front();
  return ticket;
}

bool DragSteps::overtaken(const std::string& key, std::uint64_t ticket, std::uint64_t seq) const {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = arrivals_.rbegin(); it != arrivals_.rend() && it->ticket > ticket; ++it)
    if (it->seq > seq && it->key == key) return true;
  return false;
}

std::uint64_t seq_of(const nlohmann::json& seq) {
  if (!seq.is_number_unsigned())
    throw Error(ErrorCode::kUsage, "must be a whole number >= 0, got " + seq.dump(),
                Place{.option = "seq"});
  const std::uint64_t s = seq.get<std::uint64_t>();
  if (s > DragSteps::kMaxSeq)
    throw Error(ErrorCode::kUsage,
                "must be at most " + std::to_string(DragSteps::kMaxSeq) + ", got " + seq.dump(),
                Place{.option = "seq"});
  return s;
}

std::string client_key(nlohmann::json& edit) {
  std::string client;
  if (edit.contains("client")) {
    const nlohmann::json& c = edit["client"];
    if (!c.is_string() || c.get<std::string>().size() > 64)
      throw Error(ErrorCode::kUsage, "must be a string of at most 64 characters",
                  Place{.option = "client"});
    client = c.get<std::string>();
    edit.erase("client");
  }
  return client + "|" + edit.value("row", nlohmann::json()).dump() + "|" +
         edit.value("index", nlohmann::json()).dump();
}

}  // namespace sfit::server
