// Camera profiles: a real camera's resolution, field of view, frame rate, NETD, FFC behaviour and
// output step, registered once with the datasheet each value comes from. A scene names one at
// /camera/profile; every value it sets stays overridable by the scene or --set.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace hoilcd {

// One value a profile sets: a scene field and where the value comes from.
struct CameraProfileValue {
  std::string pointer;   // JSON pointer into the scene: "/frame_rate_hz", "/camera/width_px"
  nlohmann::json value;  // as the scene file would hold it
  std::string source;    // the datasheet and what it says, or, where it is silent, why this value
};

struct CameraProfile {
  std::string name;                        // the value of /camera/profile
  std::string camera;                      // maker and model
  std::string documents;                   // the documents the values come from
  std::vector<CameraProfileValue> values;  // one per CameraProfileFields() entry, in that order
};

// Every profile, in the order the schema's enum lists them.
const std::vector<CameraProfile>& CameraProfiles();
std::vector<std::string> CameraProfileNames();
// The profile called `name`, or null.
const CameraProfile* FindCameraProfile(const std::string& name);
// The scene fields every profile sets (JSON pointers).
const std::vector<std::string>& CameraProfileFields();

// Writes each value of profile `name` that `doc` (a scene document) leaves out, so explicit values
// win. Does nothing for an unknown name (the schema reports it) or a document whose /camera is
// not an object.
void FillCameraProfile(nlohmann::json* doc, const std::string& name);

// For a profile `name` named by --set: one warning per field of it that the scene file (`written`,
// as read from `file`) gives and the resolved scene holds otherwise than the profile. The file's
// value wins, which a file written for another camera may not mean.
std::vector<std::string> CameraProfileOverrides(const nlohmann::json& written, const nlohmann::json& resolved,
                                                const std::string& name, const std::string& file);

// docs/models/camera_profiles.md: every profile's values with their sources
// (`hoilcd reference cameras`).
std::string CameraProfilesMarkdown();

}  // namespace hoilcd
