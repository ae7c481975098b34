// The comparison scene of one table (`brdfit render TABLE`, demo step 40): a sphere of the
// measured table | its lambert+ggx fit | its factorization, under a key and a fill light
// (docs/scenes.md format).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace brdfit::pipeline {

// `input`: a table file or nbrdf:NAME. quick: a coarser factorization (tests).
nlohmann::json ComparisonScene(const std::string& input, bool quick);

// A table (file or nbrdf:NAME) rather than a scene file, by its name.
bool IsTableInput(const std::string& arg);

}  // namespace brdfit::pipeline
