// A per-thread memo of data-independent geometry (parameters, basis values, factorisations)
// keyed by the sizes that determine it. Results never depend on whether a value came from
// the cache, so no locking is needed and threads stay deterministic. Bounded in bytes:
// cleared when full.
#pragma once

#include <cstddef>
#include <map>
#include <memory>

namespace sfit::detail {

template <class Key, class Value>
class ThreadCache {
 public:
  explicit ThreadCache(std::size_t max_bytes) : max_bytes_(max_bytes) {}

  /// The value for `key`, made by make() (returning std::unique_ptr<Value>) on a miss.
  /// Value must have bytes(). The reference is valid until the next get().
  template <class Make>
  const Value& get(const Key& key, Make&& make) {
    auto it = entries_.find(key);
    if (it != entries_.end()) return *it->second;
    std::unique_ptr<Value> v = make();
    const std::size_t b = v->bytes();
    if (bytes_ + b > max_bytes_) {
      entries_.clear();
      bytes_ = 0;
    }
    bytes_ += b;
    return *entries_.emplace(key, std::move(v)).first->second;
  }

 private:
  std::size_t max_bytes_;
  std::size_t bytes_ = 0;
  std::map<Key, std::unique_ptr<Value>> entries_;
};

}  // namespace sfit::detail
