#include "hoilcd/sim/trajectory_io.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>

#include "hoilcd/core/error.h"

namespace hoilcd {
namespace {

constexpr int kSignificantDigits = 9;
constexpr int kPosesCsvColumns = 13;

// std::to_chars / from_chars: locale-independent, unlike printf and strtod.
void AppendNumber(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value,
                                    std::chars_format::general, kSignificantDigits);
  out.append(buffer, result.ptr);
}

bool ParseDouble(std::string_view text, double* value) {
  if (text.empty()) return false;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), *value);
  return result.ec == std::errc() && result.ptr == text.data() + text.size() &&
         std::isfinite(*value);
}

bool ParseInt(std::string_view text, int* value) {
  if (text.empty()) return false;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), *value);
  return result.ec == std::errc() && result.ptr == text.data() + text.size();
}

// Lines without their terminator (and without a trailing '\r').
std::vector<std::string_view> SplitLines(std::string_view text) {
  std::vector<std::string_view> lines;
  size_t begin = 0;
  while (begin < text.size()) {
    size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(begin, end - begin);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    begin = end + 1;
  }
  return lines;
}

std::vector<std::string_view> Split(std::string_view line, char separator) {
  std::vector<std::string_view> fields;
  size_t begin = 0;
  while (true) {
    const size_t end = line.find(separator, begin);
    fields.push_back(line.substr(begin, end == std::string_view::npos ? end : end - begin));
    if (end == std::string_view::npos) break;
    begin = end + 1;
  }
  return fields;
}

std::vector<std::string_view> SplitWhitespace(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t begin = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > begin) fields.push_back(line.substr(begin, i - begin));
  }
  return fields;
}

std::string ReadWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string Where(const std::string& file_name, size_t line_index) {
  return file_name + ":" + std::to_string(line_index + 1);
}

}  // namespace

std::vector<PoseRecord> PoseRecordsFromRun(const RobotRun& run) {
  std::vector<PoseRecord> records;
  records.reserve(run.samples.size());
  for (const RobotSample& s : run.samples) {
    records.push_back({s.frame, s.time_s, s.base, s.camera, s.odometry});
  }
  return records;
}

std::string FormatPosesCsv(const std::vector<PoseRecord>& records) {
  std::string out = kPosesCsvHeader;
  out += '\n';
  for (const PoseRecord& r : records) {
    out += std::to_string(r.frame);
    for (const double v : {r.time_s, r.base.x_m, r.base.y_m, r.base.theta_rad, r.camera.x_m,
                           r.camera.y_m, r.camera.z_m, r.camera.yaw_rad, r.camera.pitch_rad,
                           r.odometry.x_m, r.odometry.y_m, r.odometry.theta_rad}) {
      out += ',';
      AppendNumber(out, v);
    }
    out += '\n';
  }
  return out;
}

std::vector<PoseRecord> ParsePosesCsv(const std::string& text, const std::string& file_name) {
  const std::vector<std::string_view> columns = Split(kPosesCsvHeader, ',');
  ProblemCollector problems;
  std::vector<PoseRecord> records;
  const std::vector<std::string_view> lines = SplitLines(text);
  if (lines.empty() || lines[0] != kPosesCsvHeader) {
    problems.Add(Where(file_name, 0), std::string("expected the header '") + kPosesCsvHeader + "'");
    problems.ThrowIfAny();
  }
  for (size_t i = 1; i < lines.size(); ++i) {
    if (lines[i].empty()) continue;
    const std::vector<std::string_view> fields = Split(lines[i], ',');
    if (static_cast<int>(fields.size()) != kPosesCsvColumns) {
      problems.Add(Where(file_name, i), "expected " + std::to_string(kPosesCsvColumns) +
                                            " comma-separated values, found " +
                                            std::to_string(fields.size()));
      continue;
    }
    PoseRecord r;
    bool ok = true;
    if (!ParseInt(fields[0], &r.frame) || r.frame < 0) {
      problems.Add(Where(file_name, i), "column 'frame': '" + std::string(fields[0]) +
                                            "' is not a non-negative integer");
      ok = false;
    }
    double* targets[] = {&r.time_s,         &r.base.x_m,       &r.base.y_m,
                         &r.base.theta_rad, &r.camera.x_m,     &r.camera.y_m,
                         &r.camera.z_m,     &r.camera.yaw_rad, &r.camera.pitch_rad,
                         &r.odometry.x_m,   &r.odometry.y_m,   &r.odometry.theta_rad};
    for (int c = 1; c < kPosesCsvColumns; ++c) {
      if (!ParseDouble(fields[c], targets[c - 1])) {
        problems.Add(Where(file_name, i), "column '" + std::string(columns[c]) + "': '" +
                                              std::string(fields[c]) + "' is not a finite number");
        ok = false;
      }
    }
    if (!ok) continue;
    if (!records.empty() && r.frame <= records.back().frame) {
      problems.Add(Where(file_name, i), "frame " + std::to_string(r.frame) +
                                            " does not follow frame " +
                                            std::to_string(records.back().frame));
    }
    records.push_back(r);
  }
  problems.ThrowIfAny();
  return records;
}

std::vector<PoseRecord> ReadPosesCsv(const std::string& path) {
  return ParsePosesCsv(ReadWholeFile(path), path);
}

std::vector<TumPose> TumPosesFromRun(const RobotRun& run) {
  std::vector<TumPose> poses;
  poses.reserve(run.samples.size());
  for (const RobotSample& s : run.samples) poses.push_back({s.time_s, s.camera.WorldFromCam()});
  return poses;
}

std::string FormatTumPoses(const std::vector<TumPose>& poses) {
  std::string out =
      "# hoilcd camera poses world_from_cam: world x along the room, z up (REP 103); camera x "
      "right, y down, z forward (OpenCV)\n# t tx ty tz qx qy qz qw\n";
  for (const TumPose& p : poses) {
    Eigen::Quaterniond q = p.world_from_cam.rotation.normalized();
    if (q.w() < 0) q.coeffs() *= -1.0;
    const Eigen::Vector3d& t = p.world_from_cam.translation;
    bool first = true;
    for (const double v : {p.time_s, t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()}) {
      if (!first) out += ' ';
      first = false;
      AppendNumber(out, v);
    }
    out += '\n';
  }
  return out;
}

std::vector<TumPose> ParseTumPoses(const std::string& text, const std::string& file_name) {
  static const char* const kNames[] = {"t", "tx", "ty", "tz", "qx", "qy", "qz", "qw"};
  ProblemCollector problems;
  std::vector<TumPose> poses;
  const std::vector<std::string_view> lines = SplitLines(text);
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::vector<std::string_view> fields = SplitWhitespace(lines[i]);
    if (fields.empty() || fields[0].front() == '#') continue;
    if (fields.size() != 8) {
      problems.Add(Where(file_name, i), "expected 8 values 't tx ty tz qx qy qz qw', found " +
                                            std::to_string(fields.size()));
      continue;
    }
    double v[8];
    bool ok = true;
    for (int c = 0; c < 8; ++c) {
      if (!ParseDouble(fields[c], &v[c])) {
        problems.Add(Where(file_name, i), std::string("column '") + kNames[c] + "': '" +
                                              std::string(fields[c]) + "' is not a finite number");
        ok = false;
      }
    }
    if (!ok) continue;
    const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-3) {
      problems.Add(Where(file_name, i), "quaternion is not unit length");
      continue;
    }
    if (!poses.empty() && !(v[0] > poses.back().time_s)) {
      problems.Add(Where(file_name, i), "timestamps must increase");
    }
    TumPose pose;
    pose.time_s = v[0];
    pose.world_from_cam.translation = Eigen::Vector3d(v[1], v[2], v[3]);
    pose.world_from_cam.rotation = q.normalized();
    poses.push_back(pose);
  }
  problems.ThrowIfAny();
  return poses;
}

std::vector<TumPose> ReadTumPoses(const std::string& path) {
  return ParseTumPoses(ReadWholeFile(path), path);
}

}  // namespace hoilcd
