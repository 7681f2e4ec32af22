#include "hoilcd/core/place_recognition/shortlist_index.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

#include <gtest/gtest.h>

#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

// Unit vectors of `dimension` values, drawn from the keyed RNG (the same on every standard
// library, unlike std::normal_distribution): vector i from KeyedRng(seed, purpose, i).
std::vector<std::vector<float>> RandomUnitVectors(int count, int dimension, unsigned seed) {
  std::vector<std::vector<float>> out(count, std::vector<float>(dimension));
  for (int i = 0; i < count; ++i) {
    Rng rng = KeyedRng(seed, "test.shortlist_vectors", i);
    double norm = 0;
    for (float& x : out[static_cast<size_t>(i)]) x = static_cast<float>(rng.Normal()), norm += x * x;
    for (float& x : out[static_cast<size_t>(i)]) x = static_cast<float>(x / std::sqrt(norm));
  }
  return out;
}

float Dot(const std::vector<float>& a, const std::vector<float>& b) {
  return std::inner_product(a.begin(), a.end(), b.begin(), 0.0f);
}

ShortlistOptions Options(const std::string& index) {
  ShortlistOptions o;
  o.index = index;
  return o;
}

TEST(ShortlistIndex, FlatSearchReturnsTheMostSimilarFramesInOrderByTheirOwnIds) {
  const auto vectors = RandomUnitVectors(300, 16, 1);
  ShortlistIndex index(16, Options("flat"));
  for (int i = 0; i < 300; ++i) index.Add(1000 + i, vectors[i]);  // ids are the caller's
  EXPECT_EQ(index.size(), 300);
  const std::vector<float>& query = vectors[17];
  const std::vector<int> found = index.Search(query, 10);
  std::vector<int> expected(300);
  std::iota(expected.begin(), expected.end(), 0);
  std::sort(expected.begin(), expected.end(),
            [&](int a, int b) { return Dot(query, vectors[a]) > Dot(query, vectors[b]); });
  ASSERT_EQ(found.size(), 10u);
  EXPECT_EQ(found.front(), 1017);  // itself
  for (int i = 0; i < 10; ++i) EXPECT_EQ(found[i], 1000 + expected[i]) << i;
}

TEST(ShortlistIndex, EqualSimilaritiesComeByAscendingIdAndKZeroReturnsEveryFrame) {
  for (const std::string kind : {"flat", "hnsw"}) {
    ShortlistIndex index(4, Options(kind));
    const std::vector<float> a = {1, 0, 0, 0}, b = {0, 1, 0, 0};
    index.Add(7, b);
    index.Add(5, a);
    index.Add(3, b);
    index.Add(9, a);
    EXPECT_EQ(index.Search(a, 0), (std::vector<int>{5, 9, 3, 7})) << kind;
    EXPECT_EQ(index.Search(b, 100), (std::vector<int>{3, 7, 5, 9})) << kind;
    EXPECT_EQ(index.Search(b, 2), (std::vector<int>{3, 7})) << kind;
  }
  ShortlistIndex empty(4, Options("hnsw"));
  EXPECT_TRUE(empty.Search({1, 0, 0, 0}, 5).empty());
}

TEST(ShortlistIndex, HnswFindsNearlyAllOfTheExactNearestNeighbours) {
  const int n = 3000, dim = 32, k = 20;
  const auto vectors = RandomUnitVectors(n, dim, 2);
  ShortlistIndex exact(dim, Options("flat")), hnsw(dim, Options("hnsw"));
  for (int i = 0; i < n; ++i) exact.Add(i, vectors[i]), hnsw.Add(i, vectors[i]);
  const auto queries = RandomUnitVectors(100, dim, 3);
  int hits = 0;
  for (const auto& q : queries) {
    const std::vector<int> truth = exact.Search(q, k), found = hnsw.Search(q, k);
    EXPECT_EQ(found.size(), static_cast<size_t>(k));
    const std::set<int> truth_set(truth.begin(), truth.end());
    for (int f : found) hits += truth_set.count(f) ? 1 : 0;
  }
  EXPECT_GE(hits / (100.0 * k), 0.95);
  EXPECT_GT(hnsw.MemoryBytes(), exact.MemoryBytes());
}

TEST(ShortlistIndex, TheSameFramesInTheSameOrderGiveTheSameAnswers) {
  const auto vectors = RandomUnitVectors(2000, 24, 4);
  ShortlistIndex a(24, Options("hnsw")), b(24, Options("hnsw"));
  for (int i = 0; i < 2000; ++i) a.Add(i, vectors[i]), b.Add(i, vectors[i]);
  for (int q = 0; q < 2000; q += 97) EXPECT_EQ(a.Search(vectors[q], 50), b.Search(vectors[q], 50)) << q;
}

TEST(ShortlistIndex, OptionsNameTheFieldThatIsWrong) {
  ShortlistOptions o;
  EXPECT_EQ(o.Check(), "");
  EXPECT_EQ(o.k, 50);
  o.k = -1;
  EXPECT_NE(o.Check().find("k"), std::string::npos);
  o = ShortlistOptions();
  o.hnsw_neighbours = 1;
  EXPECT_NE(o.Check().find("hnsw_neighbours"), std::string::npos);
}

}  // namespace
}  // namespace hoilcd
