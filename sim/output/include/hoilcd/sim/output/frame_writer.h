// Encodes and writes a sequence's frames (8- and 16-bit PNGs, EXR) on worker threads, fed through
// a bounded queue: the render thread waits only while `capacity` frames are in flight, and at
// most that many frames are held in memory. Files are renamed into place without an fsync each;
// Checkpoint fsyncs those written since the last one and then writes the manifest that lists
// them (a durable resume point), in the background. Bytes never depend on the number of
// workers: each file is a function of its frame, and thermal.mp4's encoder gets the frames in
// the order they were submitted.
#pragma once

#include <condition_variable>
#include <deque>
#include <exception>
#include <future>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/exr_io.h"

namespace hoilcd {

class VideoEncoder;

// What one rendered frame's files are made from.
struct FrameImages {
  int frame = 0;
  cv::Mat temperature_c;  // CV_32F, °C after the sensor model: both PNGs and the video frame
  ExrChannels exr;        // the EXR's channels (FrameExrChannels)
};

struct FrameWriterOptions {
  std::string dir;            // dataset folder
  double display_min_c = 20;  // °C, 8-bit value 0
  double display_max_c = 30;  // °C, 8-bit value 255
  int workers = 1;            // encoder threads, at least 1
  int capacity = 0;           // frames in flight (queued or being written) at most; 0: 2 x workers
  bool thermal = true;        // write thermal/NNNNNN.png
  bool radiometric = true;    // write radiometric/NNNNNN.png
  bool exr = true;            // write exr/NNNNNN.exr (FrameImages::exr)
};

class FrameWriter {
 public:
  // Each file's checksum goes into manifest->files once the file is in place (the writer owns
  // the manifest until Finish). `video` (may be null) gets every frame's 8-bit image, in order.
  FrameWriter(FrameWriterOptions options, DatasetManifest* manifest, VideoEncoder* video);
  // Stops the workers; frames not yet written are dropped (their files were never listed).
  ~FrameWriter();
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // Queues a frame; blocks only while `capacity` frames are in flight. Rethrows a worker's error.
  void Submit(FrameImages frame);
  // A resume point: fsyncs the files written since the last one, then writes manifest.json
  // listing every file written so far, on a background thread. One checkpoint at a time: while
  // the last one is still syncing, this one is skipped (its files go to the next), so a slow disk
  // never stalls the render. Rethrows a finished checkpoint's failure.
  void Checkpoint();
  // Waits for every frame and checkpoint and fsyncs what is left; the manifest is the caller's
  // again. Rethrows the first error of a worker or checkpoint.
  void Finish();
  double video_seconds() const { return video_s_; }  // spent adding frames to the video

 private:
  void Work();
  void RetireInOrder();  // with mutex_ held
  void ThrowIfFailed();  // with mutex_ held

  const FrameWriterOptions options_;
  const size_t capacity_;
  DatasetManifest* const manifest_;
  VideoEncoder* const video_;
  double video_s_ = 0;

  std::mutex mutex_;  // guards everything below and *manifest_
  std::condition_variable work_ready_, frame_retired_;
  std::deque<FrameImages> queue_;      // submitted, not yet taken by a worker
  std::deque<int> in_flight_;          // submitted and not retired, in submission order
  std::map<int, cv::Mat> written_;     // written, not retired: its 8-bit image
  std::vector<std::string> unsynced_;  // files written since the last checkpoint took them
  std::exception_ptr error_;
  bool stop_ = false;
  std::future<void> checkpoint_;
  std::vector<std::thread> workers_;
};

}  // namespace hoilcd
