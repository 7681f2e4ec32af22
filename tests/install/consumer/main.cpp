// Links hoilcd::core from an installed prefix: fuses two rankings and checksums a string.
#include <cstdio>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/place_recognition/rank_fusion.h"

int main() {
  const std::vector<double> fused = hoilcd::ReciprocalRankFusion({{0, 1}, {1, 0}}, 2);
  std::printf("hoilcd %s fused %.2f %.2f %s\n", HOILCD_VERSION, fused[0], fused[1],
              hoilcd::ChecksumOf("hoilcd").c_str());
  return 0;
}
