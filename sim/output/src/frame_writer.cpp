#include "hoilcd/sim/output/frame_writer.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include "hoilcd/core/dataset/frame_encoding.h"
#include "hoilcd/core/dataset/video.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/sim/sensor/sensor.h"

namespace hoilcd {

FrameWriter::FrameWriter(FrameWriterOptions options, DatasetManifest* manifest, VideoEncoder* video)
    : options_(std::move(options)),
      capacity_(static_cast<size_t>(options_.capacity > 0 ? options_.capacity : 2 * options_.workers)),
      manifest_(manifest),
      video_(video) {
  HOILCD_CHECK(manifest_ != nullptr && options_.workers >= 1);
  for (int i = 0; i < options_.workers; ++i) workers_.emplace_back([this] { Work(); });
}

FrameWriter::~FrameWriter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    queue_.clear();
  }
  work_ready_.notify_all();
  for (std::thread& worker : workers_) worker.join();
  if (checkpoint_.valid()) checkpoint_.wait();
}

void FrameWriter::ThrowIfFailed() {
  if (error_) std::rethrow_exception(error_);
}

void FrameWriter::Submit(FrameImages frame) {
  std::unique_lock<std::mutex> lock(mutex_);
  frame_retired_.wait(lock, [&] { return error_ || in_flight_.size() < capacity_; });
  ThrowIfFailed();
  in_flight_.push_back(frame.frame);
  queue_.push_back(std::move(frame));
  lock.unlock();
  work_ready_.notify_one();
}

void FrameWriter::Work() {
  for (;;) {
    FrameImages frame;
    bool skip = false;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      work_ready_.wait(lock, [&] { return stop_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping
      frame = std::move(queue_.front());
      queue_.pop_front();
      skip = error_ != nullptr;  // after a failure frames are only retired, so waiters wake up
    }
    const int f = frame.frame;
    cv::Mat display;
    std::vector<std::pair<std::string, std::string>> written;  // relative path, checksum
    std::exception_ptr error;
    if (!skip) {
      try {
        std::vector<std::pair<std::string, std::string>> files;  // relative path, bytes
        if (options_.thermal || video_ != nullptr) {
          display = ToDisplay8Bit(frame.temperature_c, options_.display_min_c, options_.display_max_c);
        }
        if (options_.thermal) files.emplace_back("thermal/" + FrameFileName(f, "png"), EncodePng(display));
        if (options_.radiometric) {
          files.emplace_back("radiometric/" + FrameFileName(f, "png"), EncodePng(ToCentikelvin16(frame.temperature_c)));
        }
        if (options_.exr) files.emplace_back("exr/" + FrameFileName(f, "exr"), EncodeExr(frame.exr));
        for (const auto& [relative, bytes] : files) {
          WriteFileAtomicUnsynced(options_.dir + "/" + relative, bytes);
          written.emplace_back(relative, ChecksumOf(bytes));
        }
      } catch (...) {
        error = std::current_exception();
      }
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (error && !error_) error_ = error;
      for (const auto& [relative, checksum] : written) {
        manifest_->files[relative] = checksum;
        unsynced_.push_back(options_.dir + "/" + relative);
      }
      written_[f] = display;
      RetireInOrder();
    }
    frame_retired_.notify_all();
  }
}

void FrameWriter::RetireInOrder() {
  while (!in_flight_.empty()) {
    const auto it = written_.find(in_flight_.front());
    if (it == written_.end()) return;
    if (video_ != nullptr && !error_) {
      try {
        const auto start = std::chrono::steady_clock::now();
        video_->Add(it->second);
        video_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      } catch (...) {
        error_ = std::current_exception();
      }
    }
    written_.erase(it);
    in_flight_.pop_front();
  }
}

void FrameWriter::Checkpoint() {
  if (checkpoint_.valid()) {
    if (checkpoint_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;  // still syncing
    checkpoint_.get();                                                                       // rethrows its failure
  }
  std::vector<std::string> to_sync;
  DatasetManifest snapshot;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ThrowIfFailed();
    to_sync.swap(unsynced_);
    snapshot = *manifest_;  // lists only files already in place
  }
  const std::string manifest_path = options_.dir + "/manifest.json";
  checkpoint_ =
      std::async(std::launch::async, [to_sync = std::move(to_sync), snapshot = std::move(snapshot), manifest_path] {
        SyncFiles(to_sync);  // durable before a manifest lists them
        WriteFileAtomic(manifest_path, snapshot.ToJson());
      });
}

void FrameWriter::Finish() {
  std::unique_lock<std::mutex> lock(mutex_);
  frame_retired_.wait(lock, [&] { return in_flight_.empty(); });
  lock.unlock();
  if (checkpoint_.valid()) checkpoint_.get();
  lock.lock();
  ThrowIfFailed();
  SyncFiles(unsynced_);
  unsynced_.clear();
}

}  // namespace hoilcd
