// Deterministic shards of a batch (`brdfit fit --shard I/N`, docs/scale.md): the I-th of N
// slices of the work list (input × model run), balanced by expected cost, so that N machines
// given the same command (and I = 0..N-1) fit every item exactly once and finish together.
//
//  * The slicing depends only on the set of items (input strings, model names, options JSON)
//    and N: not on the order the inputs were given in (a shell glob sorts by locale), not on
//    the machine, its cores or --jobs.
//  * Cost of an item: ModelRunCost(model), the model's measured fit time (initializer +
//    Levenberg-Marquardt at the default budget, plus the metric pass every fit pays; shard.cc
//    has the table and how it was measured), in units of 10 ms. The parameter count does not
//    predict it (lambert+abc, 9 parameters, costs 4 times lambert+ggx, 7). Every table of a
//    batch is taken to cost the same (tables are on the MERL grid or one close to it).
//  * Unit of a slice: a whole input (all its model runs) when there are at least N inputs, so
//    that each table is loaded and prepared once over all shards and its fits' choice
//    (core/model_choice.h) is made in one shard; with fewer inputs than shards, single
//    (input, model run) items.
//  * Assignment: longest processing time first (Graham 1969, "Bounds on multiprocessing timing
//    anomalies"): units by decreasing cost, ties by (input, model, options), each to the shard
//    with the least cost so far (ties: the lowest index). The most loaded shard exceeds the
//    mean by at most one unit's cost.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace brdfit::pipeline {

struct Shard {
  int index = 0;  // I, in [0, count)
  int count = 1;  // N >= 1; 1 is the whole batch
  bool Whole() const { return count == 1; }
};

// "I/N" with 0 <= I < N <= 100000. Throws InputError naming --shard.
Shard ParseShard(const std::string& text);

// The expected cost of one fit of `model` (a registry name), in the units above: measured for
// every model of the catalog when it was calibrated; 10 + parameters for a model added since.
int ModelRunCost(const std::string& model);

// Whether `model` has a measured cost (tests: every fittable model should).
bool HasMeasuredRunCost(const std::string& model);

struct ShardRun {
  std::string model;    // registry name
  std::string options;  // OptionsJson of the run (fit/options.h)
};

// Whether each (input f, run k) item is in the shard: element f * runs.size() + k.
std::vector<bool> ShardMembership(const std::vector<std::string>& inputs,
                                  const std::vector<ShardRun>& runs, const Shard& shard);

}  // namespace brdfit::pipeline
