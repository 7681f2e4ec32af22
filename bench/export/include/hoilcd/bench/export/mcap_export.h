// hoilcd export-mcap: a dataset folder as a ROS 2 bag in one MCAP file (profile ros2, CDR messages,
// ros2msg schemas): the thermal frames, camera info, wheel odometry, tf, ground truth and person
// boxes on the topics docs/guide/ros2.md lists, stamped with the dataset's clock (poses.csv's t).
// Reads only the dataset folder; the bag is written atomically, and the same dataset gives the
// same bytes.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hoilcd/bench/export/mcap_writer.h"

namespace hoilcd {

struct McapExportOptions {
  McapCompression compression = McapCompression::kZstd;  // of the chunks
  int threads = 0;     // frames decoded and serialised on this many threads (0: every core); same bytes at any count
  bool quiet = false;  // no progress line
};

struct McapExportResult {
  std::string path;                                      // the bag written
  int frames = 0;                                        // dataset frames exported
  std::vector<std::pair<std::string, uint64_t>> topics;  // each topic and its message count, in channel order
  uint64_t messages = 0;                                 // all topics
  uint64_t bytes = 0;                                    // file size
  uint64_t start_time_ns = 0, end_time_ns = 0;           // ns, first and last log time (the dataset's clock)
  double seconds = 0;                                    // s, wall time of the export
};

// Exports dataset_dir (opened with Verify::kOnRead: each file read is checked against the
// manifest) to out_path. InputError for a folder that is not a complete dataset, a file that cannot
// be read or does not match its checksum (naming it), or an out_path that is a folder.
McapExportResult ExportMcap(const std::string& dataset_dir, const std::string& out_path,
                            const McapExportOptions& options = {});

}  // namespace hoilcd
