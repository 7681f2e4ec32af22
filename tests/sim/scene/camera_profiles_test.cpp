#include "hoilcd/sim/scene/camera_profiles.h"

#include <sstream>

#include <gtest/gtest.h>

#include "hoilcd/sim/scene/scene.h"

namespace hoilcd {
namespace {

using nlohmann::json;

Scene WithProfile(const std::string& name, json doc = json::object(), const std::vector<std::string>& overrides = {}) {
  doc["camera"]["profile"] = name;
  return SceneFromJson(doc, "test.json", overrides);
}

// The schema node of a scene field: "/camera/width_px" -> "/properties/camera/properties/width_px".
json::json_pointer SchemaPointer(const std::string& pointer) {
  std::string out;
  std::stringstream keys(pointer.substr(1));
  for (std::string key; std::getline(keys, key, '/');) out += "/properties/" + key;
  return json::json_pointer(out);
}

// What each camera's datasheet gives (docs/models/camera_profiles.md), written out again here
// so that an edit of the registry that drifts from the datasheets fails.
struct Expected {
  std::string name;
  int width_px, height_px;
  double hfov_deg, frame_rate_hz, netd_k, ffc_interval_s, ffc_temperature_delta_k, ffc_freeze_s, quantisation_step_k,
      f_number, pixel_pitch_um;
};

const std::vector<Expected>& Datasheets() {
  static const std::vector<Expected> expected = {
      {"hikmicro_pocket2", 256, 192, 50, 25, 0.040, 60, 0, 0.5, 0.01, 1.1, 12},
      {"infiray_p2_pro", 256, 192, 56, 25, 0.040, 60, 0, 0.5, 1.0 / 64, 1.1, 12},
      {"flir_lepton_3_5", 160, 120, 57, 8.7, 0.050, 180, 1.5, 0.9, 0.01, 1.1, 12},
      {"flir_boson_640", 640, 512, 50, 60, 0.050, 180, 1.5, 0.5, 0.01, 1.0, 12},
  };
  return expected;
}

TEST(CameraProfiles, EveryProfileResolvesToItsDatasheetValues) {
  ASSERT_EQ(CameraProfileNames().size(), Datasheets().size());
  for (const Expected& e : Datasheets()) {
    SCOPED_TRACE(e.name);
    const Scene s = WithProfile(e.name);
    EXPECT_EQ(s.camera.width_px, e.width_px);
    EXPECT_EQ(s.camera.height_px, e.height_px);
    EXPECT_EQ(s.camera.hfov_deg, e.hfov_deg);
    EXPECT_EQ(s.frame_rate_hz, e.frame_rate_hz);
    EXPECT_EQ(s.camera.sensor.netd_k, e.netd_k);
    EXPECT_EQ(s.camera.sensor.ffc_interval_s, e.ffc_interval_s);
    EXPECT_EQ(s.camera.sensor.ffc_temperature_delta_k, e.ffc_temperature_delta_k);
    EXPECT_EQ(s.camera.sensor.ffc_freeze_s, e.ffc_freeze_s);
    EXPECT_EQ(s.camera.sensor.quantisation_step_k, e.quantisation_step_k);
    EXPECT_EQ(s.camera.sensor.f_number, e.f_number);
    EXPECT_EQ(s.camera.sensor.pixel_pitch_um, e.pixel_pitch_um);
    // The resolved scene (the dataset's scene.json) names the profile and holds its values.
    EXPECT_EQ(s.resolved["camera"]["profile"], e.name);
    EXPECT_EQ(s.resolved["camera"]["width_px"], e.width_px);
    EXPECT_EQ(s.resolved["frame_rate_hz"].get<double>(), e.frame_rate_hz);
    EXPECT_EQ(s.resolved["camera"]["ffc_temperature_delta_k"].get<double>(), e.ffc_temperature_delta_k);
  }
}

TEST(CameraProfiles, EveryProfileSetsEveryProfileFieldWithASource) {
  for (const CameraProfile& p : CameraProfiles()) {
    ASSERT_EQ(p.values.size(), CameraProfileFields().size()) << p.name;
    for (size_t i = 0; i < p.values.size(); ++i) {
      EXPECT_EQ(p.values[i].pointer, CameraProfileFields()[i]) << p.name;
      EXPECT_FALSE(p.values[i].source.empty()) << p.name << " " << p.values[i].pointer;
      EXPECT_TRUE(SceneSchema().contains(SchemaPointer(p.values[i].pointer))) << p.values[i].pointer;
    }
  }
}

// The paper's camera is today's defaults: naming it changes no typed value, and its resolved
// scene differs from a scene naming no profile only by the profile's own keys.
TEST(CameraProfiles, ThePaperCameraIsTheDefaults) {
  const Scene none = SceneFromJson(json::object(), "test.json");
  const Scene pocket2 = WithProfile("hikmicro_pocket2");
  EXPECT_EQ(CameraOptions::Table().ToJson(none.camera), CameraOptions::Table().ToJson(pocket2.camera));
  EXPECT_EQ(none.frame_rate_hz, pocket2.frame_rate_hz);
  json stripped = pocket2.resolved;
  stripped["camera"].erase("profile");
  stripped["camera"].erase("ffc_temperature_delta_k");
  EXPECT_EQ(stripped, none.resolved);
  EXPECT_FALSE(none.resolved["camera"].contains("profile"));
  EXPECT_FALSE(none.resolved["camera"].contains("ffc_temperature_delta_k"));
}

TEST(CameraProfiles, AValueTheSceneOrAnOverrideGivesWinsOverTheProfile) {
  json doc;
  doc["frame_rate_hz"] = 25;
  doc["camera"]["width_px"] = 320;
  const Scene s = WithProfile("flir_lepton_3_5", doc, {"camera.netd_k=0.035"});
  EXPECT_EQ(s.camera.width_px, 320);
  EXPECT_EQ(s.camera.height_px, 120);
  EXPECT_EQ(s.frame_rate_hz, 25.0);
  EXPECT_EQ(s.camera.sensor.netd_k, 0.035);
  EXPECT_EQ(s.camera.sensor.ffc_interval_s, 180.0);
  EXPECT_TRUE(s.warnings.empty()) << "the file names its profile: its own values are meant";
  // The profile itself may come from an override, as may a value it sets.
  const Scene set = SceneFromJson(json::object(), "test.json", {"camera.profile=flir_boson_640", "camera.hfov_deg=24"});
  EXPECT_EQ(set.camera.width_px, 640);
  EXPECT_EQ(set.camera.hfov_deg, 24.0);
  EXPECT_EQ(set.frame_rate_hz, 60.0);
  // A file written for another camera, given a profile by --set, keeps its own values, each a warning.
  json paper;
  paper["frame_rate_hz"] = 25;
  paper["camera"]["width_px"] = 256;
  paper["camera"]["netd_k"] = 0.05;
  const Scene lepton = SceneFromJson(paper, "test.json", {"camera.profile=flir_lepton_3_5", "frame_rate_hz=8.7"});
  EXPECT_EQ(lepton.camera.width_px, 256);
  EXPECT_EQ(lepton.frame_rate_hz, 8.7);
  ASSERT_EQ(lepton.warnings.size(), 1u);
  EXPECT_EQ(lepton.warnings[0],
            "test.json: /camera/width_px is 256, not the flir_lepton_3_5 profile's 160: the scene "
            "file's value wins over the profile --set names");
  EXPECT_TRUE(SceneFromJson(paper, "test.json").warnings.empty());
  // An override of the whole camera object keeps the profile's values for what it leaves out.
  const Scene whole =
      SceneFromJson(json::object(), "test.json", {R"(camera={"profile": "flir_lepton_3_5", "netd_k": 0.03})"});
  EXPECT_EQ(whole.camera.width_px, 160);
  EXPECT_EQ(whole.camera.sensor.netd_k, 0.03);
}

TEST(CameraProfiles, AnUnknownProfileIsAnErrorAtItsPathListingTheProfiles) {
  try {
    WithProfile("flir_lepton_9");
    FAIL() << "no error";
  } catch (const InputError& e) {
    ASSERT_EQ(e.problems().size(), 1u) << e.what();
    EXPECT_EQ(e.problems()[0].where, "test.json: /camera/profile");
    EXPECT_EQ(e.problems()[0].message.rfind(
                  "expected one of: hikmicro_pocket2, infiray_p2_pro, flir_lepton_3_5, flir_boson_640", 0),
              0u)
        << e.problems()[0].message;
  }
}

TEST(CameraProfiles, TheReferencePageListsEveryProfileAndSource) {
  const std::string page = CameraProfilesMarkdown();
  for (const CameraProfile& p : CameraProfiles()) {
    EXPECT_NE(page.find("## `" + p.name + "`"), std::string::npos) << p.name;
    for (const CameraProfileValue& v : p.values) EXPECT_NE(page.find(v.source), std::string::npos) << v.source;
  }
}

}  // namespace
}  // namespace hoilcd
