#include "hoilcd/sim/exr_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfCompression.h>

#include <cstring>

#include "hoilcd/core/error.h"

namespace hoilcd {
namespace {

// OpenEXR writes through an OStream; this one appends to a string so frames can be written
// atomically and checksummed before they touch the disk.
class StringOStream : public Imf::OStream {
 public:
  StringOStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    if (pos_ + n > data_.size()) data_.resize(pos_ + n);
    std::memcpy(&data_[pos_], c, n);
    pos_ += n;
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = pos; }
  std::string& data() { return data_; }

 private:
  std::string data_;
  uint64_t pos_ = 0;
};

}  // namespace

std::string EncodeExr(const ExrChannels& channels) {
  HOILCD_CHECK(!channels.empty());
  const int width = channels.front().second.cols;
  const int height = channels.front().second.rows;
  Imf::Header header(width, height);
  header.compression() = Imf::ZIP_COMPRESSION;
  Imf::FrameBuffer fb;
  for (const auto& [name, mat] : channels) {
    HOILCD_CHECK(mat.type() == CV_32F && mat.cols == width && mat.rows == height &&
                 mat.isContinuous());
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    fb.insert(name, Imf::Slice(Imf::FLOAT, const_cast<char*>(mat.ptr<char>()), sizeof(float),
                               sizeof(float) * width));
  }
  StringOStream stream;
  {
    Imf::OutputFile file(stream, header, 1);
    file.setFrameBuffer(fb);
    file.writePixels(height);
  }
  return std::move(stream.data());
}

ExrChannels ReadExr(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str(), 1);
    const Imath::Box2i dw = file.header().dataWindow();
    const int width = dw.max.x - dw.min.x + 1;
    const int height = dw.max.y - dw.min.y + 1;
    ExrChannels out;
    Imf::FrameBuffer fb;
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
      out.emplace_back(it.name(), cv::Mat(height, width, CV_32F));
    }
    for (auto& [name, mat] : out) {
      char* base = mat.ptr<char>() - (dw.min.x + static_cast<ptrdiff_t>(dw.min.y) * width) * 4;
      fb.insert(name, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * width));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return out;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, std::string("not a readable OpenEXR file (") + e.what() + ")");
  }
}

}  // namespace hoilcd
