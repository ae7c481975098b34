// The catalog (models/catalog.h, the list ForEachModel iterates) as GoogleTest typed-test
// types: a suite instantiated with CatalogTypes runs once per registered model, named after it
// ("lambert_ggx"), so a model added to the catalog is tested without a test edit.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <tuple>

#include "models/catalog.h"

namespace brdfit::test {

template <class Tuple>
struct TypesOf;
template <class... M>
struct TypesOf<std::tuple<M...>> {
  using type = ::testing::Types<M...>;
};
using CatalogTypes = TypesOf<ModelCatalog>::type;

struct CatalogNames {
  template <class M>
  static std::string GetName(int /*index*/) {
    std::string s = ModelName<M>();
    for (char& c : s) {
      if (c == '-' || c == '+') c = '_';
    }
    return s;
  }
};

}  // namespace brdfit::test
