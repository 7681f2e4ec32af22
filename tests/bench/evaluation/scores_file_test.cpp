#include "hoilcd/bench/evaluation/scores_file.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cpu_seconds.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "input_error_of.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

using namespace std::string_literals;
using test::InputErrorOf;

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

// A .npy file with exactly `header` as its header dict (padded as numpy pads it) and `body`.
std::string NpyWithHeader(const std::string& dict, const std::string& body) {
  std::string header = dict;
  header.append(64 - (10 + header.size() + 1) % 64, ' ');
  header += '\n';
  std::string out("\x93NUMPY\x01\x00", 8);
  out += static_cast<char>(header.size() & 0xff);
  out += static_cast<char>(header.size() >> 8);
  return out + header + body;
}

// The error of reading `bytes` as the file `name` through ReadScoresFile ("" when it reads).
std::string FileError(const test::TestDir& dir, const std::string& name, const std::string& bytes, int frames = 2) {
  WriteFileAtomic(dir / name, bytes);
  return InputErrorOf([&] { ReadScoresFile(dir / name, frames); });
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
  EXPECT_NE(
      CsvError("query,reference,score\n0,1,2\n0,4,1\n").find("s.csv:3: reference '4': expected a frame index in 0..3"),
      std::string::npos);
  EXPECT_NE(CsvError("query,reference,score\n-1,1,2\n").find("s.csv:2: query '-1': expected a frame index in 0..3"),
            std::string::npos);
  EXPECT_NE(CsvError("query,reference,score\n0,1,nan\n").find("s.csv:2: score is NaN: leave the pair out"),
            std::string::npos);
  EXPECT_NE(CsvError("query,reference,score\n0,1,inf\n").find("s.csv:2: score 'inf': expected a finite number"),
            std::string::npos);
  EXPECT_NE(CsvError("query,reference,score\n0,1,x\n").find("s.csv:2: score 'x': expected a number"),
            std::string::npos);
  EXPECT_NE(
      CsvError("query,reference,score\n0,1,2\n1,1,1\n0,1,3\n").find("s.csv:4: duplicate pair query 0, reference 1"),
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
  EXPECT_NE(NpyError(Npy({1, 2, 3, 4}, "(2, 2)", "<f8", "True")).find("fortran_order True: expected a C-order"),
            std::string::npos);
  EXPECT_NE(NpyError(Npy({1, 2, 3}, "(2, 2)")).find("holds 24 data bytes: expected 32"), std::string::npos);
  EXPECT_NE(NpyError(Npy({1, 2, 3, INFINITY}, "(2, 2)")).find("element [1, 1] = inf: expected a finite score"),
            std::string::npos);
  std::string v9 = Npy({1, 2, 3, 4}, "(2, 2)");
  v9[6] = 9;
  EXPECT_NE(NpyError(v9).find(".npy format version 9: expected 1, 2 or 3"), std::string::npos);
  EXPECT_NE(NpyError(Npy({1, 2, 3, 4}, "(2, 2)").substr(0, 30))
                .find("s.npy: truncated .npy header: expected 128 bytes up to the header's end, the file holds 30"),
            std::string::npos);
  EXPECT_NE(NpyError(Npy({1, 2, 3, 4}, "(2, 2)", "<f8", "False", 2).substr(0, 11))
                .find("s.npy: truncated .npy header: expected 12 bytes up to the header's end, the file holds 11"),
            std::string::npos);
}

TEST(ScoresFile, FilesReadThroughReadScoresFileGiveWhatTheirBytesGive) {
  const test::TestDir dir;
  const double nan = std::nan("");
  WriteFileAtomic(dir / "s.npy", Npy({0.5, nan, -1, 2}, "(2, 2)"));
  const ScoreMatrix npy = ReadScoresFile(dir / "s.npy", 2);
  EXPECT_EQ(npy.At(0, 0), 0.5);
  EXPECT_TRUE(std::isnan(npy.At(0, 1)));
  EXPECT_EQ(npy.At(1, 1), 2.0);
  EXPECT_EQ(npy.source, dir / "s.npy");
  // A CSV longer than one read block, read line by line.
  std::string csv = "query,reference,score\n";
  for (int q = 0; q < 300; ++q) {
    for (int r = 0; r < 300; ++r)
      csv += std::to_string(q) + "," + std::to_string(r) + "," + std::to_string(q - r) + "\r\n";
  }
  csv.pop_back();  // a last line without its '\n'
  WriteFileAtomic(dir / "s.csv", csv);
  const ScoreMatrix from_file = ReadScoresFile(dir / "s.csv", 300);
  EXPECT_EQ(from_file.values, ScoresFromCsv(csv, "s.csv", 300).values);
  EXPECT_EQ(from_file.At(299, 0), 299.0);
}

TEST(ScoresFile, ATruncatedNpyFileNamesWhereItEndsReadFromAFileAsFromBytes) {
  const test::TestDir dir;
  const std::string npy = Npy({1, 2, 3, 4}, "(2, 2)");
  for (size_t size : {size_t{11}, size_t{100}, size_t{140}}) {
    EXPECT_EQ(FileError(dir, "s.npy", npy.substr(0, size)),
              InputErrorOf([&] { ScoresFromNpy(npy.substr(0, size), dir / "s.npy", 2); }))
        << size;
  }
}

TEST(ScoresFile, RefusesAFifoWithoutBlocking) {
  const test::TestDir dir;
  for (const char* name : {"pipe.csv", "pipe.npy"}) {
    ASSERT_EQ(::mkfifo((dir / name).c_str(), 0600), 0);
    // No writer ever opens the FIFO: a reader that opened it blocking would wait forever.
    const std::string error = InputErrorOf([&] { ReadScoresFile(dir / name, 4); });
    EXPECT_NE(error.find(dir / name + ": is a FIFO: expected a regular file"), std::string::npos) << error;
  }
}

TEST(ScoresFile, RefusesADeviceSuchAsDevZeroInsteadOfReadingItForever) {
  const std::string error = InputErrorOf([&] { ReadScoresFile("/dev/zero", 4); });
  EXPECT_NE(error.find("/dev/zero: is a character device: expected a regular file"), std::string::npos) << error;
}

TEST(ScoresFile, AHugeSparseNpyIsRefusedByItsSizeAgainstItsHeaderBeforeItsBodyIsRead) {
  const test::TestDir dir;
  const std::string path = dir / "huge.npy";
  WriteFileAtomic(path, Npy({1, 2, 3, 4}, "(2, 2)"));
  ASSERT_EQ(::truncate(path.c_str(), off_t{1} << 36), 0);  // 64 GiB of holes
  const double start = test::ProcessCpuSeconds();          // CPU time: a loaded machine stretches wall time
  const std::string error = InputErrorOf([&] { ReadScoresFile(path, 2); });
  EXPECT_NE(error.find(path + ": holds 68719476608 data bytes: expected 32 for a (2, 2) matrix of 64-bit floats"),
            std::string::npos)
      << error;
  EXPECT_LT(test::ProcessCpuSeconds() - start, 2.0) << "the body was read";
}

TEST(ScoresFile, AHugeSparseCsvIsRefusedByItsSizeAgainstTheDatasetBeforeItIsRead) {
  const test::TestDir dir;
  const std::string path = dir / "huge.csv";
  WriteFileAtomic(path, "query,reference,score\n");
  ASSERT_EQ(::truncate(path.c_str(), off_t{1} << 36), 0);
  const std::string error = InputErrorOf([&] { ReadScoresFile(path, 4); });
  EXPECT_NE(error.find(path + ": is 68719476736 bytes: a scores CSV of this dataset's 4 frames holds at most 4 x 4 "
                              "lines of at most 128 bytes"),
            std::string::npos)
      << error;
}

TEST(ScoresFile, AnNpyHeaderLongerThanNumpyWritesIsRefusedBeforeItIsRead) {
  std::string v2 = Npy({1, 2, 3, 4}, "(2, 2)", "<f8", "False", 2);
  for (size_t i = 8; i < 12; ++i) v2[i] = '\xff';  // a header length of 4 GiB
  const std::string error = NpyError(v2);
  EXPECT_NE(error.find("s.npy: .npy header of 4294967295 bytes: expected at most 65536"), std::string::npos) << error;
}

TEST(ScoresFile, AHeaderOnlyCsvIsRefusedAsHoldingNoScore) {
  EXPECT_NE(CsvError("query,reference,score\n")
                .find("s.csv: holds the header and no pair: expected at least one "
                      "line query,reference,score"),
            std::string::npos);
  EXPECT_NE(CsvError("query,reference,score\r\n\n\n").find("holds the header and no pair"), std::string::npos);
}

TEST(ScoresFile, AnAllNanNpyIsRefusedAsHoldingNoScore) {
  const double nan = std::nan("");
  for (const char* descr : {"<f8", "<f4"}) {
    EXPECT_NE(NpyError(Npy({nan, nan, nan, nan}, "(2, 2)", descr))
                  .find("s.npy: every element is NaN (unscored): "
                        "expected at least one score"),
              std::string::npos);
  }
}

TEST(ScoresFile, AnNpyObjectArrayIsRefusedByItsDtype) {
  const std::string error = NpyError(Npy({}, "(2, 2)", "|O"));
  EXPECT_NE(error.find("s.npy: dtype '|O': expected float64 ('<f8') or float32 ('<f4') (an object array holds Python "
                       "objects"),
            std::string::npos)
      << error;
}

TEST(ScoresFile, NpyShapesThatAreNotTuplesOfNonNegativeIntegersAreRefused) {
  for (const char* shape : {"(-2, 2)", "(a2, b2)", "(2, 2a)", "(2 2)", "(2,, 2)", "(, 2)", "2, 2", "(2, 2", "(+2, 2)",
                            "(2.0, 2)", "(99999999999999999999, 2)"}) {
    const std::string error = NpyError(Npy({1, 2, 3, 4}, shape));
    EXPECT_NE(error.find("s.npy: "), std::string::npos) << shape << ": " << error;
    EXPECT_TRUE(error.find("expected a tuple of non-negative integers, (2, 2) for this dataset") != std::string::npos ||
                error.find(".npy header") != std::string::npos)
        << shape << ": " << error;
  }
  EXPECT_NE(NpyError(Npy({1, 2, 3, 4}, "(-2, 2)")).find("shape '(-2, 2)': expected a tuple of non-negative integers"),
            std::string::npos);
  EXPECT_NE(NpyError(Npy({1, 2, 3, 4}, "(a2, b2)")).find("shape '(a2, b2)': expected a tuple"), std::string::npos);
  // What numpy writes, spaced as numpy spaces it or not.
  EXPECT_EQ(NpyError(Npy({1, 2, 3, 4}, "(2,2)")), "");
  EXPECT_EQ(NpyError(Npy({1, 2, 3, 4}, "(2, 2,)")), "");
  EXPECT_NE(NpyError(Npy({1, 2}, "(2,)")).find("matrix shape (2,): expected (2, 2)"), std::string::npos);
}

TEST(ScoresFile, NpyFortranOrderIsReportedAsWritten) {
  const std::string error = NpyError(Npy({1, 2, 3, 4}, "(2, 2)", "<f8", "Maybe"));
  EXPECT_NE(error.find("s.npy: fortran_order 'Maybe': expected False (a C-order matrix)"), std::string::npos) << error;
  EXPECT_EQ(error.find("True"), std::string::npos) << error;
}

TEST(ScoresFile, NpyHeadersOtherThanNumpysDictAreRefusedNamingWhatIsWrong) {
  const std::string body(32, '\0');
  const auto error = [&](const std::string& dict) { return NpyError(NpyWithHeader(dict, body)); };
  EXPECT_EQ(error("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 2)}"), "");
  EXPECT_EQ(error("{\"shape\": (2, 2), \"descr\": \"<f8\", \"fortran_order\": False, }"), "");
  EXPECT_NE(error("{'descr': '<f8', 'fortran_order': False}").find(".npy header has no 'shape'"), std::string::npos);
  EXPECT_NE(
      error("{'descr': '<f8', 'descr': '<f8', 'fortran_order': False, 'shape': (2, 2)}").find("'descr' is given twice"),
      std::string::npos);
  EXPECT_NE(error("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 2), 'extra': 1}")
                .find("key 'extra': expected only 'descr', 'fortran_order' and 'shape'"),
            std::string::npos);
  EXPECT_NE(error("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 2)} trailing").find("text after the dict"),
            std::string::npos);
  EXPECT_NE(error("['descr']").find("expected a Python dict"), std::string::npos);
  EXPECT_NE(error("{'descr': '<f8, 'fortran_order': False, 'shape': (2, 2)}").find(".npy header"), std::string::npos);
  EXPECT_NE(error("{'descr': [('a', '<f8')], 'fortran_order': False, 'shape': (2, 2)}").find("dtype [('a', '<f8')]"),
            std::string::npos);
  EXPECT_NE(error("{'descr': '<f8', 'fortran_order': False, 'shape': ((2, 2)}").find("its brackets do not match"),
            std::string::npos);
}

TEST(ScoresFile, ANulByteInACsvIsShownEscapedAndDoesNotCutTheMessageShort) {
  const std::string error = CsvError("query,reference,score\n0\0,1,2\n1,2,\xe9\n"s);
  EXPECT_EQ(error.find('\0'), std::string::npos) << "a NUL would end the message where it is printed";
  EXPECT_NE(error.find("s.csv:2: query '0\\x00': expected a frame index in 0..3"), std::string::npos) << error;
  EXPECT_NE(error.find("s.csv:3: score '\\xe9': expected a number"), std::string::npos) << error;
  EXPECT_NE(CsvError("\0query,reference,score\n"s)
                .find("expected the header 'query,reference,score', got "
                      "'\\x00query,reference,score'"),
            std::string::npos);
}

TEST(ScoresFile, CsvLinesLongerThanAnyPairAreRefusedInTextAndInFilesAlike) {
  const test::TestDir dir;
  const std::string long_line = "query,reference,score\n0,1," + std::string(2 << 20, '7') + "\n1,1,x\n";
  const std::string from_text = CsvError(long_line, 300);
  EXPECT_NE(from_text.find("s.csv:2: line '0,1,777"), std::string::npos) << from_text;
  EXPECT_NE(from_text.find("...' is longer than 128 bytes: expected query,reference,score"), std::string::npos)
      << from_text;
  EXPECT_NE(from_text.find("s.csv:3: score 'x'"), std::string::npos) << from_text;
  EXPECT_EQ(FileError(dir, "s.csv", long_line, 300),
            InputErrorOf([&] { ScoresFromCsv(long_line, dir / "s.csv", 300); }));
}

TEST(ScoresFile, CsvScoresBeyondTheRangeOfADoubleAreNamedAsSuch) {
  EXPECT_NE(CsvError("query,reference,score\n0,1,1e400\n").find("score '1e400': beyond the range of a double"),
            std::string::npos);
  EXPECT_NE(CsvError("query,reference,score\n0,1,-inf\n").find("score '-inf': expected a finite number"),
            std::string::npos);
  // The smallest double, as ScoresToCsv writes it, reads back.
  EXPECT_EQ(ScoresFromCsv("query,reference,score\n0,1,4.9406564584124654e-324\n", "s.csv", 4).At(0, 1),
            std::numeric_limits<double>::denorm_min());
}

}  // namespace
}  // namespace hoilcd
