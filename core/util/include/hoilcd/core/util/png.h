// Greyscale PNG frames through libdeflate: the dataset's 8-bit thermal and 16-bit radiometric
// frames are encoded and decoded here in about 2/3 of the CPU of OpenCV's libpng on zlib
// (docs/performance.md, "Rendering and the dataset"). Only non-interlaced 8- and 16-bit greyscale
// files with IHDR, IDAT and IEND chunks are handled; the caller sends anything else to OpenCV.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <opencv2/core/mat.hpp>

namespace hoilcd {

// Width and height from a PNG's signature and IHDR chunk (its first 24 bytes), without decoding
// (OpenCV offers no header-only read); false if `bytes` does not start that way.
bool PngSize(std::string_view bytes, uint32_t* width, uint32_t* height);

// A 1-channel CV_8U or CV_16U image as a PNG: 8- or 16-bit greyscale, non-interlaced, every row
// with the Sub filter, one IDAT deflated at libdeflate level 1. The same bytes for the same
// pixels (with the same libdeflate).
std::string EncodeGreyPng(const cv::Mat& image);

// Decodes `bytes` into *image if it is a non-interlaced greyscale PNG of exactly width x height
// pixels at the depth of `type` (CV_8UC1: 8-bit, CV_16UC1: 16-bit) made of IHDR, IDAT and IEND
// chunks, every CRC and the zlib checksum intact. Returns false, leaving *image alone, for any
// other file, damaged or not: the caller then decodes it with OpenCV, whose verdict stands.
bool DecodeGreyPng(std::string_view bytes, int width, int height, int type, cv::Mat* image);

}  // namespace hoilcd
