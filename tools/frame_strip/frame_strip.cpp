// frame_strip: a README picture of a dataset's frames side by side, inferno colour map, scaled.
// Usage: frame_strip DATASET OUT.png SCALE FRAME... (frames by index, from thermal/NNNNNN.png).
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

int main(int argc, char** argv) {
  if (argc < 5) {
    std::cerr << "usage: frame_strip DATASET OUT.png SCALE FRAME...\n";
    return 2;
  }
  const std::string dataset = argv[1];
  const int scale = std::stoi(argv[3]);
  std::vector<cv::Mat> tiles;
  for (int i = 4; i < argc; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "/thermal/%06d.png", std::stoi(argv[i]));
    const cv::Mat grey = cv::imread(dataset + name, cv::IMREAD_GRAYSCALE);
    if (grey.empty()) {
      std::cerr << "frame_strip: cannot read " << dataset + name << "\n";
      return 1;
    }
    cv::Mat big, colour;
    cv::resize(grey, big, cv::Size(), scale, scale, cv::INTER_NEAREST);
    cv::applyColorMap(big, colour, cv::COLORMAP_INFERNO);
    cv::putText(colour, "frame " + std::string(argv[i]), cv::Point(6, 18), cv::FONT_HERSHEY_SIMPLEX, 0.5,
                cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
    if (!tiles.empty()) tiles.push_back(cv::Mat(colour.rows, 4, CV_8UC3, cv::Scalar(255, 255, 255)));
    tiles.push_back(colour);
  }
  cv::Mat strip;
  cv::hconcat(tiles, strip);
  if (!cv::imwrite(argv[2], strip)) {
    std::cerr << "frame_strip: cannot write " << argv[2] << "\n";
    return 1;
  }
  return 0;
}
