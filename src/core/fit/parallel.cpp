#include "parallel.h"

#include <condition_variable>

namespace sfit::detail {
namespace {

// A pool thread, or a thread inside run(): a parallel loop nested in either runs serially
// (and never re-locks `use_`, which the calling thread may hold).
thread_local bool on_pool_thread = false;

// Threads made on first use and kept until exit; one parallel loop at a time.
class Pool {
 public:
  ~Pool() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    wake_.notify_all();
    for (auto& t : threads_) t.join();
  }

  bool run(int helpers, const std::function<void()>& work) {
    std::unique_lock<std::mutex> busy(use_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    {
      std::lock_guard<std::mutex> lock(m_);
      while (static_cast<int>(threads_.size()) < helpers) {
        const int index = static_cast<int>(threads_.size());
        threads_.emplace_back([this, index] { loop(index); });
      }
      work_ = &work;
      wanted_ = helpers;
      running_ = helpers;
      ++generation_;
    }
    wake_.notify_all();
    on_pool_thread = true;
    work();
    on_pool_thread = false;
    std::unique_lock<std::mutex> lock(m_);
    done_.wait(lock, [&] { return running_ == 0; });
    work_ = nullptr;
    return true;
  }

 private:
  void loop(int index) {
    on_pool_thread = true;
    std::uint64_t seen = 0;
    std::unique_lock<std::mutex> lock(m_);
    while (true) {
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      if (index >= wanted_) continue;
      const std::function<void()>* work = work_;
      lock.unlock();
      (*work)();  // parallel_for's worker catches everything f throws
      lock.lock();
      if (--running_ == 0) done_.notify_all();
    }
  }

  std::mutex use_;  // held for a whole run(): one parallel loop at a time
  std::mutex m_;
  std::condition_variable wake_, done_;
  std::vector<std::thread> threads_;
  const std::function<void()>* work_ = nullptr;
  int wanted_ = 0, running_ = 0;
  std::uint64_t generation_ = 0;
  bool stop_ = false;
};

}  // namespace

bool run_on_pool(int helpers, const std::function<void()>& work) {
  if (helpers <= 0 || on_pool_thread) return false;
  static Pool pool;
  return pool.run(helpers, work);
}

}  // namespace sfit::detail
