// "Did you mean" (core/suggest.h): the optimal string alignment distance against hand-counted
// edits, and the suggestions the CLI makes for misspelt models, materials, commands, options.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/suggest.h"

namespace brdfit {
namespace {

TEST(Suggest, EditDistanceCountsInsertionsDeletionsSubstitutionsAndSwaps) {
  EXPECT_EQ(EditDistance("", ""), 0u);
  EXPECT_EQ(EditDistance("ggx", "ggx"), 0u);
  EXPECT_EQ(EditDistance("ggxx", "ggx"), 1u);  // a deletion
  EXPECT_EQ(EditDistance("gx", "ggx"), 1u);    // an insertion
  EXPECT_EQ(EditDistance("ggy", "ggx"), 1u);   // a substitution
  EXPECT_EQ(EditDistance("fti", "fit"), 1u);   // a swap of neighbours
  EXPECT_EQ(EditDistance("--modle", "--model"), 1u);
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);  // Levenshtein's example
  EXPECT_EQ(EditDistance("ca", "abc"), 3u);          // OSA: no substring edited twice (true DL: 2)
  EXPECT_EQ(EditDistance("abc", ""), 3u);
  EXPECT_EQ(EditDistance("", "abc"), 3u);
}

TEST(Suggest, ClosestNamesAreNearForTheirLengthAndNeverTheNameItself) {
  const std::vector<std::string> models = {"ggx", "beckmann", "ward", "lambert+ggx", "lambert"};
  EXPECT_EQ(ClosestNames("ggxx", models), std::vector<std::string>{"ggx"});
  EXPECT_EQ(ClosestNames("bekmann", models), std::vector<std::string>{"beckmann"});
  EXPECT_EQ(ClosestNames("lambert+ggxx", models), std::vector<std::string>{"lambert+ggx"});
  EXPECT_TRUE(ClosestNames("phong", models).empty());  // nothing close: no guess
  EXPECT_TRUE(ClosestNames("ggx", models).empty());    // the name itself is no suggestion
  EXPECT_TRUE(ClosestNames("xyz", models).empty());    // 3 edits from ggx: far for 3 letters
  const std::vector<std::string> ties = {"ward", "word", "wart", "warm"};
  EXPECT_EQ(ClosestNames("warx", ties), (std::vector<std::string>{"ward", "wart", "warm"}));
  EXPECT_EQ(DidYouMean("ggxx", models), "did you mean ggx?");
  EXPECT_EQ(DidYouMean("warx", ties), "did you mean ward, wart or warm?");
  EXPECT_EQ(SuggestionAfter("ggxx", models), " (did you mean ggx?)");
  EXPECT_EQ(SuggestionAfter("phong", models), "");
}

}  // namespace
}  // namespace brdfit
