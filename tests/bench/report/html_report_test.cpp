#include "hoilcd/bench/report/html_report.h"

#include <cstdlib>
#include <map>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/report/gallery_sample.h"
#include "hoilcd/bench/report/html.h"
#include "hoilcd/bench/runner/runner.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

TEST(EscapeHtml, EscapesTheFiveMarkupCharactersAndMakesBytesSafe) {
  EXPECT_EQ(EscapeHtml("<a href=\"x\">Tom's & Jerry's</a>"),
            "&lt;a href=&quot;x&quot;&gt;Tom&#39;s &amp; Jerry&#39;s&lt;/a&gt;");
  EXPECT_EQ(EscapeHtml("caf\xe9"), "caf\\xe9");  // not UTF-8: SafeText's escape
  EXPECT_EQ(EscapeHtml("plain text"), "plain text");
}

TEST(Base64, MatchesTheRfc4648TestVectors) {
  const std::map<std::string, std::string> vectors = {{"", ""},
                                                      {"f", "Zg=="},
                                                      {"fo", "Zm8="},
                                                      {"foo", "Zm9v"},
                                                      {"foob", "Zm9vYg=="},
                                                      {"fooba", "Zm9vYmE="},
                                                      {"foobar", "Zm9vYmFy"}};
  for (const auto& [in, out] : vectors) EXPECT_EQ(Base64(in), out) << in;
  EXPECT_EQ(Base64(std::string("\xff\x00\xfe", 3)), "/wD+");
  EXPECT_EQ(DataUri("image/png", "foo"), "data:image/png;base64,Zm9v");
}

TEST(SortableTable, EveryNumberCellCarriesItsSortKeyAndTextSortsByItself) {
  const std::string html =
      SortableTable({"a<b", "n"}, {{TextCell("x&y"), NumberCell(0.25)}, {TextCell("z"), NumberCell(NAN)}});
  EXPECT_NE(html.find("<th>a&lt;b</th>"), std::string::npos);
  EXPECT_NE(html.find("<td>x&amp;y</td><td data-sort=\"0.25\">0.250</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>-</td>"), std::string::npos);  // NaN: no key, sorted after the numbers
}

// Records of one method: query i is a hit when hits[i], every query scored.
std::vector<QueryRecord> Records(const std::vector<bool>& hits) {
  std::vector<QueryRecord> records(hits.size());
  for (size_t i = 0; i < hits.size(); ++i) {
    records[i].frame = static_cast<int>(i);
    records[i].scored = true;
    records[i].top1_is_true_match = hits[i];
  }
  return records;
}

TEST(SampleGallery, TakesAtMostPerGroupFromEachMethodOutcomeAndStratumAndAllOfSmallGroups) {
  std::vector<QueryConditions> conditions(40);
  std::vector<bool> a_hits(40), b_hits(40);
  for (int i = 0; i < 40; ++i) {
    conditions[i].frame = i;
    conditions[i].people_in_view = i < 30 ? 0 : 3;
    conditions[i].walkers_in_view = 0;
    a_hits[i] = i % 3 == 0;
    b_hits[i] = i == 7;  // one hit: its group has one member, which is taken
  }
  const std::vector<QueryRecord> a = Records(a_hits), b = Records(b_hits);
  const GallerySampling any_gap{2, 1};
  const std::vector<size_t> sample = SampleGallery({&a, &b}, conditions, {"walkers"}, any_gap);
  EXPECT_EQ(sample, SampleGallery({&a, &b}, conditions, {"walkers"}, any_gap));  // deterministic
  EXPECT_TRUE(std::is_sorted(sample.begin(), sample.end()));
  EXPECT_NE(std::find(sample.begin(), sample.end(), 7u), sample.end());
  std::map<std::string, int> per_group;
  for (size_t q : sample) {
    per_group[std::string("a:") + GalleryOutcome(a[q])]++;
    per_group[std::string("b:") + GalleryOutcome(b[q])]++;
  }
  // One stratification with one stratum ("none") and the groups of all queries, which hold the same
  // queries: two groups per method, two queries each, b's hit group one: at most 2 + 2 + 2 + 1.
  EXPECT_LE(sample.size(), 7u);
  EXPECT_GE(per_group["a:hit"], 2);
  EXPECT_GE(per_group["a:miss"], 2);
  EXPECT_GE(per_group["b:hit"], 1);
  const std::vector<QueryRecord> unscored(40);
  EXPECT_TRUE(SampleGallery({&unscored}, conditions, {"walkers"}, any_gap).empty());  // no outcome, no group
}

// Frames from `first` on, one query each; conditions[i].walkers_in_view cycles 0, 1, 2 every 40.
std::vector<QueryConditions> ConsecutiveQueries(int count, int first) {
  std::vector<QueryConditions> conditions(count);
  for (int i = 0; i < count; ++i) {
    conditions[i].frame = first + i;
    conditions[i].people_in_view = 2;
    conditions[i].walkers_in_view = (i / 40) % 3;
  }
  return conditions;
}

TEST(SampleGallery, NoTwoEntriesAreWithinTheGapAndAGroupComesOutShortOnlyWhenTheGapCrowdsItOut) {
  // Three methods whose hits interleave frame by frame: each group's evenly spaced picks land on
  // neighbouring frames of the other methods' picks, the near-duplicate rows the gap prevents.
  const int n = 300;
  const std::vector<QueryConditions> conditions = ConsecutiveQueries(n, 1000);
  std::vector<std::vector<QueryRecord>> records;
  for (int m = 0; m < 3; ++m) {
    std::vector<bool> hits(n);
    for (int i = 0; i < n; ++i) hits[i] = i % 3 == m;
    records.push_back(Records(hits));
  }
  // A fourth method with one hit, next to where the first method's hit group would pick: the
  // smallest group picks first, so this rare hit is shown.
  std::vector<bool> rare(n);
  rare[76] = true;
  records.push_back(Records(rare));
  std::vector<const std::vector<QueryRecord>*> pointers;
  for (const auto& r : records) pointers.push_back(&r);
  const std::vector<std::string> stratifications = {"walkers"};
  for (const GallerySampling sampling : {GallerySampling(), GallerySampling{3, 25}}) {
    const std::vector<size_t> sample = SampleGallery(pointers, conditions, stratifications, sampling);
    EXPECT_EQ(sample, SampleGallery(pointers, conditions, stratifications, sampling));  // deterministic
    ASSERT_FALSE(sample.empty());
    EXPECT_TRUE(std::is_sorted(sample.begin(), sample.end()));
    for (size_t k = 1; k < sample.size(); ++k) {
      EXPECT_GE(conditions[sample[k]].frame - conditions[sample[k - 1]].frame, sampling.min_gap_frames)
          << "queries " << sample[k - 1] << " and " << sample[k];
    }
    EXPECT_TRUE(std::binary_search(sample.begin(), sample.end(), 76u)) << "the rare hit is not sampled";
    // Each group (method, outcome, and all queries or one stratum) holds min(per_group, its size)
    // sampled queries, or each of its other queries is within the gap of a sampled one.
    std::map<std::string, std::vector<size_t>> groups;
    for (size_t m = 0; m < records.size(); ++m) {
      for (size_t i = 0; i < conditions.size(); ++i) {
        const std::string key = std::to_string(m) + GalleryOutcome(records[m][i]);
        groups[key].push_back(i);
        groups[key + StratumOf("walkers", conditions[i])].push_back(i);
      }
    }
    const auto near_sample = [&](size_t i) {
      for (size_t s : sample)
        if (std::abs(conditions[s].frame - conditions[i].frame) < sampling.min_gap_frames) return true;
      return false;
    };
    int full = 0;
    for (const auto& [key, members] : groups) {
      size_t held = 0;
      for (size_t i : members) held += std::binary_search(sample.begin(), sample.end(), i) ? 1 : 0;
      if (held >= std::min(members.size(), static_cast<size_t>(sampling.per_group))) {
        ++full;
        continue;
      }
      for (size_t i : members) EXPECT_TRUE(near_sample(i)) << "group " << key << ": query " << i << " could be sampled";
    }
    EXPECT_GT(full, static_cast<int>(groups.size()) / 2);
  }
}

TEST(BenchReportHtml, IsTheSameBytesTwiceAndItsGalleryDrawsEveryPointMethodsInliersOrSaysItHasNone) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomDataset(temp / "data");
  BenchOptions options;
  options.methods = ParseMethodList("all", &options.optional_methods);
  const BenchResult result = RunBench(dataset, options);
  const HtmlReportInput input{temp.str(), {}, GallerySampling()};
  const HtmlReport a = BenchReportHtml(result, dataset, options, input),
                   b = BenchReportHtml(result, dataset, options, input);
  EXPECT_EQ(a.html, b.html);
  ASSERT_FALSE(a.gallery.empty());
  size_t entries = 0;
  for (size_t at = a.html.find("<div class=\"entry\""); at != std::string::npos;
       at = a.html.find("<div class=\"entry\"", at + 1))
    ++entries;
  EXPECT_EQ(entries, a.gallery.size());
  EXPECT_EQ(a.html.find("http://"), std::string::npos);  // nothing from the network
  EXPECT_EQ(a.html.find("https://"), std::string::npos);
  // Every method that matches points (the point-set methods, their oracles, dlcd-track): the matches
  // re-run for a sampled pair give the top-1's score as their inlier count, and the page draws them.
  // The others' tiles say that they match no points.
  std::map<std::string, int> drawn, matched;
  for (const MethodRun& run : result.runs) {
    const LoopClosureMethod& method = FindMethod(run.name);
    const ShownFeatures shown = method.Features();
    const std::unique_ptr<MethodOptions> own = method.Options();
    const std::string tile = "<figure class=\"tile pair\" data-method=\"" + run.name + "\">";
    size_t tiles = 0, with_inliers = 0, saying_none = 0;
    for (size_t at = a.html.find(tile); at != std::string::npos; at = a.html.find(tile, at + 1)) {
      const std::string caption = a.html.substr(at, a.html.find("</figure>", at) - at);
      ++tiles;
      with_inliers += caption.find("RANSAC inliers") != std::string::npos ? 1 : 0;
      saying_none += caption.find("class=\"no-matches\"") != std::string::npos ? 1 : 0;
    }
    EXPECT_EQ(tiles, a.gallery.size()) << run.name;
    if (shown == ShownFeatures::kNone) {
      EXPECT_EQ(saying_none, tiles) << run.name << ": a tile without matches says why";
      continue;
    }
    EXPECT_EQ(with_inliers, tiles) << run.name;
    for (size_t q : a.gallery) {
      const QueryRecord& rec = run.metrics.queries[q];
      if (!rec.scored || rec.top1_frame < 0) continue;
      const FrameFeatures &qf = result.features[rec.frame], &rf = result.features[rec.top1_frame];
      const std::vector<Point2> qp = qf.Points(shown), rp = rf.Points(shown);
      const std::optional<PairMatches> m =
          method.MatchPair({own.get(), qp, rp, qf.Hoi(shown), rf.Hoi(shown), rec.frame, rec.top1_frame,
                            dataset.manifest().intrinsics.height, dataset.manifest().seed});
      ASSERT_TRUE(m.has_value()) << run.name;
      EXPECT_EQ(m->inliers, rec.top1_score) << run.name << " query " << rec.frame;
      ++drawn[run.name];
      matched[run.name] += m->matches.empty() ? 0 : 1;
    }
  }
  for (const std::string name : {"slcd", "dlcd", "dlcd-track", "dlcd-oracle", "slcd-ideal"}) {
    EXPECT_GT(drawn[name], 0) << name;
    EXPECT_GT(matched[name], 0) << name << " matched no points in any sampled pair";
  }
  EXPECT_NE(a.html.find("The tiles of fusion, fusion-tc, thumb, thumb-seq show the two frames alone"),
            std::string::npos);
}

TEST(SuiteReportHtml, HoldsOneRowPerRunLinkingToItsReport) {
  const SuiteSummary summary = SummariseSuite("rooms<1>", "two rooms", {"slcd"},
                                              {{"a-seed1", "", {{"slcd", 0.5}}, {{"slcd", 0.4}}, "a"},
                                               {"b-seed1", "", {{"slcd", 0.25}}, {{"slcd", 0.2}}, "b"},
                                               {"c-seed1", "no frames", {}, {}, "c"}});
  const std::string html =
      SuiteReportHtml(summary, {{"a-seed1", "runs/a-seed1"}, {"b-seed1", "../shard/runs/b-seed1"}});
  EXPECT_NE(html.find("<a href=\"runs/a-seed1/report.html\">"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"../shard/runs/b-seed1/report.html\">"), std::string::npos);
  EXPECT_NE(html.find("rooms&lt;1&gt;"), std::string::npos);
  EXPECT_NE(html.find("c-seed1: no frames"), std::string::npos);
}

}  // namespace
}  // namespace hoilcd
