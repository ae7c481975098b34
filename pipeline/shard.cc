#include "pipeline/shard.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <map>
#include <numeric>
#include <queue>
#include <tuple>
#include <utility>

#include "core/error.h"
#include "models/registry.h"

namespace brdfit::pipeline {
namespace {

constexpr int kMaxShards = 100000;

// The measured cost of one fit of each catalog model, in units of 10 ms of one core: the mean
// initializer + Levenberg-Marquardt time of `brdfit bench` at the default budget, plus the
// metric pass every fit pays. docs/scale.md "Cost of a fit" has the command, the machine and
// the times each number comes from; only the ratios matter.
const std::map<std::string, int>& MeasuredRunCost() {
  static const std::map<std::string, int> costs = {
      {"lambert", 11},
      {"burley", 12},
      {"oren-nayar", 12},
      {"ggx", 14},
      {"ggx-hc", 14},
      {"lambert+ggx-hc", 14},
      {"blinn-phong", 15},
      {"lambert+ggx", 15},
      {"lambert+ward", 15},
      {"lambert+blinn-phong", 16},
      {"lambert+phong", 16},
      {"phong", 16},
      {"ward", 16},
      {"ggx-f0", 20},
      {"lambert+beckmann", 20},
      {"lambert+ggx-f0", 20},
      {"oren-nayar+ggx", 20},
      {"ward-duer", 22},
      {"ue4", 23},
      {"burley+ggx", 26},
      {"lafortune", 26},
      {"lambert+lafortune", 28},
      {"beckmann", 29},
      {"lambert+ggx+ggx", 29},
      {"cook-torrance", 31},
      {"lambert+cook-torrance", 32},
      {"sgd", 44},
      {"abc", 45},
      {"lambert+sgd", 52},
      {"lambert+abc", 58},
      {"lambert+lafortune+lafortune", 109},
      {"lambert+lafortune+lafortune+lafortune", 289},
      // The sheen models, measured later and scaled to the others by lambert+ggx's ratio.
      {"sheen", 12},
      {"lambert+sheen", 12},
      {"lambert+ggx+sheen", 20},
      {"burley+ggx+sheen", 40},
      // The bodies Blender Cycles evaluates, measured later in one run with their twins
      // (oren-nayar, burley and their +ggx sums) and scaled by each twin's ratio.
      {"oren-nayar-fujii", 12},
      {"burley-2012", 12},
      {"oren-nayar-fujii+ggx", 19},
      {"burley-2012+ggx", 23},
      // The factorization candidate (pipeline/factor_candidate.h: four forms, their scores and
      // files): 2.9 times lambert+ggx+ggx.
      {"factorization", 85},
  };
  return costs;
}

// A model without a measurement (added to the catalog since): the metric pass plus one unit
// per parameter, a rough guess of the same scale.
constexpr int kUnmeasuredBase = 10;

// A non-negative decimal number of at most 6 digits, or -1.
int ParseCount(const std::string& s) {
  if (s.empty() || s.size() > 6 || !std::all_of(s.begin(), s.end(), ::isdigit)) return -1;
  return std::stoi(s);
}

}  // namespace

Shard ParseShard(const std::string& text) {
  const auto slash = text.find('/');
  const int i = slash == std::string::npos ? -1 : ParseCount(text.substr(0, slash));
  const int n = slash == std::string::npos ? -1 : ParseCount(text.substr(slash + 1));
  if (i < 0 || n < 1 || n > kMaxShards || i >= n) {
    throw InputError("--shard '" + text + "': expected I/N with 0 <= I < N <= " +
                     std::to_string(kMaxShards) + ", e.g. 0/4");
  }
  return {i, n};
}

int ModelRunCost(const std::string& model) {
  if (const auto it = MeasuredRunCost().find(model); it != MeasuredRunCost().end()) {
    return it->second;
  }
  const ModelInfo* m = FindModel(model);
  return kUnmeasuredBase + (m ? static_cast<int>(m->params.size()) : 0);
}

bool HasMeasuredRunCost(const std::string& model) {
  return MeasuredRunCost().count(model) > 0;
}

std::vector<bool> ShardMembership(const std::vector<std::string>& inputs,
                                  const std::vector<ShardRun>& runs, const Shard& shard) {
  const std::size_t nr = runs.size();
  std::vector<bool> in(inputs.size() * nr, shard.Whole());
  if (shard.Whole() || in.empty()) return in;
  std::int64_t input_cost = 0;
  std::vector<std::int64_t> run_cost;
  for (const ShardRun& r : runs) {
    run_cost.push_back(ModelRunCost(r.model));
    input_cost += run_cost.back();
  }
  // Units: whole inputs (run = nr marks "all runs") or single items.
  const bool whole_inputs = inputs.size() >= static_cast<std::size_t>(shard.count);
  struct Unit {
    std::size_t input, run;
    std::int64_t cost;
  };
  std::vector<Unit> units;
  for (std::size_t f = 0; f < inputs.size(); ++f) {
    if (whole_inputs) {
      units.push_back({f, nr, input_cost});
      continue;
    }
    for (std::size_t k = 0; k < nr; ++k) units.push_back({f, k, run_cost[k]});
  }
  // Decreasing cost; ties by the item's names, never by the order given.
  std::sort(units.begin(), units.end(), [&](const Unit& a, const Unit& b) {
    if (a.cost != b.cost) return a.cost > b.cost;
    const std::string& ma = a.run < nr ? runs[a.run].model : std::string();
    const std::string& mb = b.run < nr ? runs[b.run].model : std::string();
    const std::string& oa = a.run < nr ? runs[a.run].options : std::string();
    const std::string& ob = b.run < nr ? runs[b.run].options : std::string();
    return std::tie(inputs[a.input], ma, oa, a.input) < std::tie(inputs[b.input], mb, ob, b.input);
  });
  // Least-loaded shard first; ties: the lowest index.
  using Load = std::pair<std::int64_t, int>;
  std::priority_queue<Load, std::vector<Load>, std::greater<Load>> loads;
  for (int s = 0; s < shard.count; ++s) loads.push({0, s});
  for (const Unit& u : units) {
    auto [load, s] = loads.top();
    loads.pop();
    loads.push({load + u.cost, s});
    if (s != shard.index) continue;
    if (u.run < nr) {
      in[u.input * nr + u.run] = true;
    } else {
      for (std::size_t k = 0; k < nr; ++k) in[u.input * nr + k] = true;
    }
  }
  return in;
}

}  // namespace brdfit::pipeline
