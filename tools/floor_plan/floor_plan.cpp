// floor_plan: a docs picture of a scene from above: rooms and corridors, walls, every footprint
// (furniture, objects, standing people), the seated people at t = 0 and the robot's route.
// Usage: floor_plan SCENE OUT.png [PIXELS_PER_M] (HOILCD_DATA_DIR as for hoilcd).
#include <iostream>
#include <string>

#include <Eigen/Geometry>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/world/world.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: floor_plan SCENE OUT.png [PIXELS_PER_M]\n";
    return 2;
  }
  try {
    const hoilcd::Scene scene = hoilcd::LoadScene(argv[1]);
    const double scale = argc > 3 ? std::stod(argv[3]) : 40.0;
    const hoilcd::BandRadianceTable table;
    const hoilcd::World world(scene, table);
    constexpr int kMarginPx = 10;
    const int width = static_cast<int>(scene.room.size_m.x() * scale) + 2 * kMarginPx;
    const int height = static_cast<int>(scene.room.size_m.y() * scale) + 2 * kMarginPx;
    cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
    // Floor frame (y north, up in the picture) to pixels.
    auto px = [&](const Eigen::Vector2d& p) {
      return cv::Point(static_cast<int>(kMarginPx + p.x() * scale),
                       static_cast<int>(height - kMarginPx - p.y() * scale));
    };
    for (const hoilcd::FloorRoom& room : scene.floor.rooms) {
      cv::rectangle(image, px(room.box_m.min()), px(room.box_m.max()),
                    room.corridor ? cv::Scalar(225, 235, 240) : cv::Scalar(240, 245, 235), cv::FILLED);
      if (!room.corridor) {
        cv::putText(image, room.layout.empty() ? room.name : room.layout,
                    px({room.box_m.min().x() + 0.2, room.box_m.max().y() - 0.5}), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                    cv::Scalar(90, 90, 90), 1, cv::LINE_AA);
      }
    }
    for (const hoilcd::Obstacle2D& o : world.obstacles()) {
      const bool wall = o.name.find("wall") != std::string::npos;
      const cv::Scalar colour = wall ? cv::Scalar(40, 40, 40) : cv::Scalar(150, 150, 150);
      if (o.shape == hoilcd::Obstacle2D::Shape::kCircle) {
        cv::circle(image, px(o.center_m), static_cast<int>(o.radius_m * scale), colour, cv::FILLED, cv::LINE_AA);
        continue;
      }
      const Eigen::Rotation2Dd rotation(o.yaw_rad);
      std::vector<cv::Point> corners;
      for (const Eigen::Vector2d& c :
           {Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, -1), Eigen::Vector2d(1, 1), Eigen::Vector2d(-1, 1)}) {
        corners.push_back(px(o.center_m + rotation * Eigen::Vector2d(c.cwiseProduct(o.half_size_m))));
      }
      cv::fillConvexPoly(image, corners, colour, cv::LINE_AA);
    }
    for (const hoilcd::Person& person : world.people()) {
      if (!person.present) continue;
      const Eigen::Vector2d at = person.world_from_seat.topRightCorner<2, 1>().cast<double>();
      cv::circle(image, px(at), static_cast<int>(0.2 * scale), cv::Scalar(40, 120, 240), cv::FILLED, cv::LINE_AA);
    }
    std::vector<cv::Point> route;
    for (const Eigen::Vector2d& p : scene.route.waypoints_m) route.push_back(px(p));
    cv::polylines(image, route, true, cv::Scalar(40, 40, 220), 2, cv::LINE_AA);
    if (!route.empty()) cv::circle(image, route.front(), 5, cv::Scalar(40, 40, 220), cv::FILLED, cv::LINE_AA);
    if (!cv::imwrite(argv[2], image)) {
      std::cerr << "floor_plan: cannot write " << argv[2] << "\n";
      return 1;
    }
  } catch (const std::exception& e) {
    std::cerr << "floor_plan: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
