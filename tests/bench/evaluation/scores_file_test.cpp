#include "hoilcd/bench/evaluation/scores_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

// The error text of reading `text` as CSV over `frames` frames ("" when it reads).
std::string CsvError(const std::string& text, int frames = 4) {
  try {
    ScoresFromCsv(text, "s.csv", frames);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A .npy file of `values` with the given header fields.
std::string Npy(const std::vector<double>& values, const std::string& shape, const std::string& descr = "<f8",
                const std::string& fortran = "False", int version = 1) {
  std::string header = "{'descr': '" + descr + "', 'fortran_order': " + fortran + ", 'shape': " + shape + ", }";
  const size_t prefix = version == 1 ? 10 : 12;
  header.append(64 - (prefix + header.size() + 1) % 64, ' ');
  header += '\n';
  std::string out("\x93NUMPY", 6);
  out += static_cast<char>(version);
  out += '\0';
  const size_t len = header.size();
  out += static_cast<char>(len & 0xff);
  out += static_cast<char>(len >> 8 & 0xff);
  if (version != 1) out += std::string(2, '\0');
  out += header;
  for (double v : values) {
    if (descr == "<f4") {
      const float f = static_cast<float>(v);
      out.append(reinterpret_cast<const char*>(&f), 4);
    } else {
      out.append(reinterpret_cast<const char*>(&v), 8);
    }
  }
  return out;
}

std::string NpyError(const std::string& bytes, int frames = 2) {
  try {
    ScoresFromNpy(bytes, "s.npy", frames);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ScoresFile, CsvPairsLeftOutAreUnscoredAndWrittenScoresReadBackBitExactly) {
  Query q;
  q.frame = 3;
  q.database = {0, 1};
  q.is_true_match = {1, 0};
  const double third = 1.0 / 3.0;
  const std::string csv = ScoresToCsv({q}, {{third, -2.5e-12}});
  const ScoreMatrix m = ScoresFromCsv(csv, "s.csv", 4);
  EXPECT_EQ(m.At(3, 0), third);
  EXPECT_EQ(m.At(3, 1), -2.5e-12);
  EXPECT_TRUE(std::isnan(m.At(3, 2)));
  EXPECT_TRUE(std::isnan(m.At(0, 3)));
  EXPECT_EQ(ScoresFromCsv("query,reference,score\r\n1,2,5\r\n\n", "s.csv", 4).At(1, 2), 5.0);
}

TEST(ScoresFile, CsvErrorsNameTheFileTheLineAndWhatWasExpected) {
  EXPECT_NE(CsvError("q,r,s\n0,1,2\n").find("s.csv:1: expected the header 'query,reference,score', got 'q,r,s'"),
            std::string::npos);
  EXPECT_NE(CsvError("").find("s.csv:1: expected the header"), std::string::npos);
  EXPECT_NE(CsvError("query,reference,score\n0,1,2\n0,4,1\n").find("s.csv:3: reference '4': expected a frame index in 0..3"),
            std::string::npos);
  EXPECT_NE(CsvError("query,reference,score\n-1,1,2\n").find("s.csv:2: query '-1': expected a frame index in 0..3"),
            std::string::npos);
  EXPECT_NE(CsvError("query,reference,score\n0,1,nan\n").find("s.csv:2: score is NaN: leave the pair out"),
            std::string::npos);
  EXPECT_NE(CsvError("query,reference,score\n0,1,inf\n").find("s.csv:2: score 'inf': expected a finite number"),
            std::string::npos);
  EXPECT_NE(CsvError("query,reference,score\n0,1,x\n").find("s.csv:2: score 'x': expected a number"),
            std::string::npos);
  EXPECT_NE(CsvError("query,reference,score\n0,1,2\n1,1,1\n0,1,3\n").find("s.csv:4: duplicate pair query 0, reference 1"),
            std::string::npos);
  EXPECT_NE(CsvError("query,reference,score\n0,1\n").find("s.csv:2: expected 3 fields (query,reference,score), got 2"),
            std::string::npos);
  EXPECT_NE(CsvError("query,reference,score\n0,1,2,3\n").find("got 4"), std::string::npos);
}

TEST(ScoresFile, ABrokenCsvNamesItsFirstProblemsAndCountsTheRest) {
  std::string text = "query,reference,score\n";
  for (int i = 0; i < 25; ++i) text += "9,0,1\n";
  const std::string error = CsvError(text);
  EXPECT_NE(error.find("s.csv:11: query '9'"), std::string::npos) << error;
  EXPECT_EQ(error.find("s.csv:12:"), std::string::npos) << error;
  EXPECT_NE(error.find("further problems not listed"), std::string::npos) << error;
}

TEST(ScoresFile, NpyFloat64AndFloat32ReadWithNanAsUnscored) {
  const double nan = std::nan("");
  for (const char* descr : {"<f8", "<f4"}) {
    for (int version : {1, 2}) {
      const ScoreMatrix m = ScoresFromNpy(Npy({0.5, nan, -1, 2}, "(2, 2)", descr, "False", version), "s.npy", 2);
      EXPECT_EQ(m.At(0, 0), 0.5) << descr;
      EXPECT_TRUE(std::isnan(m.At(0, 1))) << descr;
      EXPECT_EQ(m.At(1, 0), -1.0) << descr;
      EXPECT_EQ(m.At(1, 1), 2.0) << descr;
    }
  }
}

TEST(ScoresFile, NpyErrorsNameTheFileAndWhatWasExpected) {
  EXPECT_NE(NpyError("not numpy at all").find("s.npy: expected a NumPy .npy file"), std::string::npos);
  EXPECT_NE(NpyError(Npy({1, 2, 3}, "(3,)")).find("matrix shape (3,): expected (2, 2) (the dataset's frames x frames)"),
            std::string::npos);
  EXPECT_NE(NpyError(Npy(std::vector<double>(9, 0), "(3, 3)")).find("matrix shape (3, 3): expected (2, 2)"),
            std::string::npos);
  EXPECT_NE(NpyError(Npy({1, 2, 3, 4}, "(2, 2)", "<i8")).find("dtype '<i8': expected float64"), std::string::npos);
  EXPECT_NE(NpyError(Npy({1, 2, 3, 4}, "(2, 2)", "<f8", "True")).find("fortran_order True"), std::string::npos);
  EXPECT_NE(NpyError(Npy({1, 2, 3}, "(2, 2)")).find("holds 24 data bytes: expected 32"), std::string::npos);
  EXPECT_NE(NpyError(Npy({1, 2, 3, INFINITY}, "(2, 2)")).find("element [1, 1] = inf: expected a finite score"),
            std::string::npos);
  std::string v9 = Npy({1, 2, 3, 4}, "(2, 2)");
  v9[6] = 9;
  EXPECT_NE(NpyError(v9).find(".npy format version 9: expected 1, 2 or 3"), std::string::npos);
  EXPECT_NE(NpyError(Npy({1, 2, 3, 4}, "(2, 2)").substr(0, 30)).find("truncated .npy header"), std::string::npos);
}

}  // namespace
}  // namespace hoilcd
