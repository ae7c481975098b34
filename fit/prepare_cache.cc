#include "fit/prepare_cache.h"

#include <algorithm>
#include <cstdint>
#include <exception>
#include <future>
#include <list>
#include <mutex>

namespace brdfit {

namespace {

struct RenderedKey {
  Grid grid;
  RenderedErrorOptions options;
  bool operator==(const RenderedKey&) const = default;
};

// The plans of one kind, least recently used first.
template <class Key, class Plan>
struct Shelf {
  struct Entry {
    Key key;
    std::shared_future<std::shared_ptr<const Plan>> plan;
  };
  std::list<Entry> entries;
};

}  // namespace

struct PrepareCache::State {
  std::size_t capacity;
  mutable std::mutex mu;
  Shelf<SamplePlanKey, SamplePlan> samples;
  Shelf<RenderedKey, RenderedPlan> rendered;
  std::size_t made = 0, reused = 0;

  // The plan of `key` from the shelf, or made by `make` outside the lock (other keys are
  // served meanwhile; a second request for this key waits for this one). A plan that fails to be
  // made is not kept: its error goes to every request waiting for it.
  template <class Key, class Plan, class Make>
  std::shared_ptr<const Plan> Get(Shelf<Key, Plan>& shelf, const Key& key, const Make& make) {
    std::promise<std::shared_ptr<const Plan>> promise;
    std::shared_future<std::shared_ptr<const Plan>> future;
    bool mine = false;
    {
      std::lock_guard<std::mutex> lock(mu);
      const auto it = std::find_if(shelf.entries.begin(), shelf.entries.end(),
                                   [&](const auto& e) { return e.key == key; });
      if (it != shelf.entries.end()) {
        shelf.entries.splice(shelf.entries.end(), shelf.entries, it);  // most recently used
        future = it->plan;
        ++reused;
      } else {
        future = promise.get_future().share();
        shelf.entries.push_back({key, future});
        mine = true;
        ++made;
      }
    }
    if (mine) {
      std::shared_ptr<const Plan> plan;
      try {
        plan = std::make_shared<const Plan>(make());
      } catch (...) {
        promise.set_exception(std::current_exception());
        std::lock_guard<std::mutex> lock(mu);
        shelf.entries.remove_if([&](const auto& e) { return e.key == key; });
      }
      if (plan) {
        promise.set_value(plan);
        // Made: the least recently used plans beyond the capacity go (a failed one evicts none).
        std::lock_guard<std::mutex> lock(mu);
        while (shelf.entries.size() > capacity) shelf.entries.pop_front();
      }
    }
    return future.get();
  }
};

PrepareCache::PrepareCache(std::size_t capacity) : state_(std::make_unique<State>()) {
  state_->capacity = std::max<std::size_t>(capacity, 1);
}

PrepareCache::~PrepareCache() = default;

std::shared_ptr<const SamplePlan> PrepareCache::Samples(const Grid& grid,
                                                        const SampleOptions& options) {
  return state_->Get(state_->samples, SamplePlanKey::Of(grid, options),
                     [&] { return MakeSamplePlan(grid, options); });
}

std::shared_ptr<const RenderedPlan> PrepareCache::Rendered(const Grid& grid,
                                                           const RenderedErrorOptions& options) {
  return state_->Get(state_->rendered, RenderedKey{grid, options},
                     [&] { return MakeRenderedPlan(grid, options); });
}

PrepareCache::Stats PrepareCache::GetStats() const {
  std::lock_guard<std::mutex> lock(state_->mu);
  return {state_->made, state_->reused,
          state_->samples.entries.size() + state_->rendered.entries.size()};
}

}  // namespace brdfit
