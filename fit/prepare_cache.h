// The per-grid work of PrepareTable (fit/fitter.h), done once for all the tables of a batch
// (the per-grid work once): the sample plan (fit/sample_plan.h) and the rendered
// metric's plan (fit/rendered_error.h RenderedPlan), keyed by the grid and the options they
// depend on. Every MERL table has one grid, so `brdfit fit nbrdf:all` makes each plan once.
//
// Thread-safe: the workers of pipeline/batch_fit.cc share one cache; a plan asked for by two
// workers at once is made by one while the other waits for it. Bounded: at most `capacity`
// plans of each kind (the least recently used is dropped; a table being prepared keeps the
// plan it holds alive), so a batch over many grids does not grow (a MERL plan is ~17 MB).
#pragma once

#include <cstddef>
#include <memory>

#include "core/table.h"
#include "fit/rendered_error.h"
#include "fit/sample_plan.h"
#include "fit/samples.h"

namespace brdfit {

class PrepareCache {
 public:
  explicit PrepareCache(std::size_t capacity = 2);
  ~PrepareCache();
  PrepareCache(const PrepareCache&) = delete;
  PrepareCache& operator=(const PrepareCache&) = delete;

  // The plan of the grid and options (budget and seed play no part); made on first use.
  // Throws what MakeSamplePlan / MakeRenderedPlan throw (a bad cut-off: InputError).
  std::shared_ptr<const SamplePlan> Samples(const Grid& grid, const SampleOptions& options);
  std::shared_ptr<const RenderedPlan> Rendered(const Grid& grid,
                                               const RenderedErrorOptions& options = {});

  struct Stats {
    std::size_t made = 0, reused = 0;  // plans made, and asked for again (both kinds)
    std::size_t entries = 0;           // plans held now (both kinds)
  };
  Stats GetStats() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace brdfit
