#include "hoilcd/sim/scene/camera_profiles.h"

#include <sstream>

#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

using nlohmann::json;

// The values of one profile, in CameraProfileFields() order, each with its source.
struct Sourced {
  json value;
  const char* source;
};

CameraProfile Profile(const char* name, const char* camera, const char* documents, std::vector<Sourced> values) {
  HOILCD_CHECK_MSG(values.size() == CameraProfileFields().size(), name << ": a value for every profile field");
  CameraProfile p{name, camera, documents, {}};
  for (size_t i = 0; i < values.size(); ++i) {
    p.values.push_back({CameraProfileFields().at(i), std::move(values[i].value), values[i].source});
  }
  return p;
}

}  // namespace

const std::vector<std::string>& CameraProfileFields() {
  static const std::vector<std::string> fields = {"/camera/width_px",
                                                  "/camera/height_px",
                                                  "/camera/hfov_deg",
                                                  "/frame_rate_hz",
                                                  "/camera/netd_k",
                                                  "/camera/ffc_interval_s",
                                                  "/camera/ffc_temperature_delta_k",
                                                  "/camera/ffc_freeze_s",
                                                  "/camera/quantisation_step_k",
                                                  "/camera/f_number",
                                                  "/camera/pixel_pitch_um"};
  return fields;
}

const std::vector<CameraProfile>& CameraProfiles() {
  static const std::vector<CameraProfile> profiles = {
      Profile("hikmicro_pocket2", "HIKMICRO Pocket2 (handheld camera; the HOI-LCD paper's camera)",
              "HIKMICRO Pocket2 specification sheet (its document number is not recorded here; its figures are "
              "quoted from the published sheet as remembered, not re-checked against it when this profile was "
              "written); the HOI-LCD paper, section 5.1. Its values are the scene defaults, so naming it changes "
              "no frame.",
              {{256, "IR resolution 256 × 192 (Pocket2 specification); the paper's frames"},
               {192, "as width_px"},
               {50.0, "field of view 50° × 37.2° (Pocket2 specification)"},
               {25.0, "frame rate 25 Hz (Pocket2 specification); the paper's sequences"},
               {0.040, "NETD < 40 mK (Pocket2 specification); the bound taken as the 1σ noise"},
               {60.0,
                "silent: the specification gives no shutter interval; 60 s, the model's default, so the "
                "profile reproduces today's renders"},
               {0.0, "silent: no temperature trigger is published; off, as today"},
               {0.5, "silent: 0.5 s, the model's default (the frozen part of a handheld camera's shutter event)"},
               {0.01,
                "silent on the radiometric step; 0.01 K, the model's default and the step of the dataset's "
                "16-bit centikelvin PNG"},
               {1.1,
                "silent: the specification gives the lens's field of view but no f-number; f/1.1, the "
                "aperture the Lepton datasheet gives for the same 12 µm pixel class (short LWIR lenses for "
                "12 µm cores are f/1.0-1.1)"},
               {12.0, "pixel pitch 12 µm (Pocket2 specification)"}}),
      Profile("infiray_p2_pro", "InfiRay P2 Pro (USB-C module for phones)",
              "InfiRay P2 Pro specification sheet (its document number is not recorded here; its figures are "
              "quoted from the published sheet as remembered, not re-checked against it when this profile was "
              "written); the module's USB frame format as decoded by open-source readers, which InfiRay does not "
              "publish.",
              {{256, "resolution 256 × 192, 12 µm pixels (P2 Pro specification)"},
               {192, "as width_px"},
               {56.0, "field of view 56° × 42.2° (P2 Pro specification)"},
               {25.0, "frame rate 25 Hz (P2 Pro specification)"},
               {0.040, "NETD < 40 mK (P2 Pro specification); the bound taken as the 1σ noise"},
               {60.0,
                "silent: the module closes its shutter on its own but publishes no interval; 60 s, the "
                "model's default"},
               {0.0, "silent: no temperature trigger is published; off"},
               {0.5, "silent: 0.5 s, the model's default"},
               {0.015625,
                "not in a datasheet: each USB frame carries a 16-bit temperature image in units of 1/64 K "
                "(kelvin × 64) as the open-source readers of this InfiRay module family decode it, so "
                "the step is 1/64 K"},
               {1.1, "silent on the f-number; f/1.1, as the Pocket2 profile (the same 12 µm pixel class)"},
               {12.0, "12 µm pixels (P2 Pro specification)"}}),
      Profile("flir_lepton_3_5", "FLIR Lepton 3.5 (radiometric micro camera core, 57° lens)",
              "FLIR Lepton Engineering Datasheet, document 500-0659-00-09 Rev 203; FLIR Lepton Product Datasheet, "
              "document 500-0771-01-09 Rev 400; FLIR Lepton 3 Datasheet, document 500-0726-01 (for the 56° it "
              "gives the non-radiometric Lepton 3).",
              {{160, "160 × 120 active pixels (500-0659-00-09; 500-0771-01-09)"},
               {120, "as width_px"},
               {57.0,
                "57° HFOV, the 160 × 120 Lepton 3.5's lens ('configurations with 25°, 50° and 57° HFOV', "
                "500-0659-00-09; 500-0771-01-09 lists 57° too). The Lepton 3 datasheet (500-0726-01) gives "
                "56° HFOV, 71° diagonal for the Lepton 3; we follow the Lepton 3.5 documents"},
               {8.7,
                "8.7 Hz, the 160 × 120 Lepton's effective export-compliant frame rate ('export compliant frame "
                "rate (< 9 Hz)', 500-0659-00-09; its 80 × 60 table gives 8.6 Hz)"},
               {0.050,
                "thermal sensitivity < 50 mK (500-0659-00-09; 500-0771-01-09); the bound taken as the 1σ "
                "noise"},
               {180.0,
                "automatic FFC 'after a specified period of time (default of 3 minutes) has elapsed since "
                "the last FFC' (500-0659-00-09, FFC states)"},
               {1.5,
                "'or if the camera temperature has changed by more than a specified value (default of 1.5 "
                "Celsius degrees) since the last FFC' (500-0659-00-09, FFC states); modelled with the housing "
                "warming (housing_warming_k_per_min): at its default 0.5 K/min both triggers fall at 180 s"},
               {0.9,
                "'the default FFC duration is nominally 23 frames at 26Hz' (500-0659-00-09, FFC states): "
                "0.88 s, rounded to 0.9 s; 8 frames at 8.7 Hz"},
               {0.01,
                "radiometric TLinear output in kelvin × 100 at its default resolution ('T-Linear resolution "
                "(0 = 0.1, 1 = 0.01)', telemetry row C, 500-0659-00-09): 0.01 K"},
               {1.1, "effective f-number 1.1 (500-0659-00-09, optical specifications)"},
               {12.0, "pixel size 12 µm (500-0659-00-09; 500-0771-01-09)"}}),
      Profile("flir_boson_640", "FLIR Boson 640 (thermal camera core, 640 × 512, 8.7 mm lens, 50° HFOV)",
              "FLIR Boson Thermal Imaging Core datasheet, document 102-2013-40 Release 340 (March 2021); FLIR "
              "Boson Software Interface Description Document, document 102-2013-42 (FFC settings).",
              {{640, "VGA array 640 × 512, 12 µm pixels (102-2013-40)"},
               {512, "as width_px"},
               {50.0,
                "the 8.7 mm lens, 50° HFOV, one of the datasheet's eight VGA fields of view (102-2013-40); "
                "chosen because it is the paper camera's 50°, so comparing the two changes the resolution "
                "and not the view"},
               {60.0,
                "'maximum effective frame rate: fast configuration 60 Hz' (102-2013-40); 30 Hz is a setting "
                "of the same core (frame_rate_hz=30)"},
               {0.050,
                "'thermal sensitivity varies by configuration, as low as < 40 mK' (102-2013-40): < 50 mK for "
                "the professional grade used here, < 40 mK for the industrial grade (netd_k=0.04)"},
               {180.0,
                "the datasheet names an automatic FFC but gives no default period (the software IDD, "
                "102-2013-42, makes it a setting); we assume FLIR's documented Lepton default, 3 min"},
               {1.5,
                "as the period: the Boson's temperature trigger is a setting (102-2013-42); we assume FLIR's "
                "documented Lepton default, 1.5 K"},
               {0.5, "silent on the FFC's length; 0.5 s, the model's default"},
               {0.01,
                "the Boson 640 is not radiometric: it outputs 14-bit counts (or 8-bit AGC video) and the "
                "datasheet gives no kelvin per count; 0.01 K, the step of the dataset's 16-bit centikelvin "
                "PNG, so the model adds no step beyond the file's own"},
               {1.0,
                "f/1.0 for the 8.7 mm lens, as the datasheet's lens table is remembered (102-2013-40; not "
                "re-checked against it)"},
               {12.0, "12 µm pixels (102-2013-40)"}}),
  };
  return profiles;
}

std::vector<std::string> CameraProfileNames() {
  std::vector<std::string> names;
  for (const CameraProfile& p : CameraProfiles()) names.push_back(p.name);
  return names;
}

const CameraProfile* FindCameraProfile(const std::string& name) {
  for (const CameraProfile& p : CameraProfiles()) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

void FillCameraProfile(json* doc, const std::string& name) {
  const CameraProfile* profile = FindCameraProfile(name);
  if (profile == nullptr || !doc->is_object()) return;
  if (doc->contains("camera") && !(*doc)["camera"].is_object()) return;
  for (const CameraProfileValue& v : profile->values) {
    const json::json_pointer pointer(v.pointer);
    if (!doc->contains(pointer)) (*doc)[pointer] = v.value;
  }
}

std::vector<std::string> CameraProfileOverrides(const json& written, const json& resolved, const std::string& name,
                                                const std::string& file) {
  std::vector<std::string> warnings;
  const CameraProfile* profile = FindCameraProfile(name);
  if (profile == nullptr) return warnings;
  for (const CameraProfileValue& v : profile->values) {
    const json::json_pointer pointer(v.pointer);
    if (!written.contains(pointer) || !resolved.contains(pointer) || !resolved[pointer].is_number() ||
        resolved[pointer].get<double>() == v.value.get<double>()) {
      continue;
    }
    warnings.push_back(file + ": " + v.pointer + " is " + resolved[pointer].dump() + ", not the " + name +
                       " profile's " + v.value.dump() + ": the scene file's value wins over the profile --set names");
  }
  return warnings;
}

std::string CameraProfilesMarkdown() {
  std::ostringstream out;
  out << "# Camera profiles\n\n"
      << "<!-- Generated by `hoilcd reference cameras > docs/models/camera_profiles.md` from "
         "sim/scene/src/camera_profiles.cpp; do not edit by hand (tests/docs checks it is current). -->\n\n"
      << "`camera.profile` names a real camera; the profile sets the scene fields below from the camera's "
         "datasheet. A value the scene gives itself, or one set with `--set`, wins over the profile's "
         "(`--set camera.width_px=320`). The dataset's `scene.json` holds the values used. A scene that names no "
         "profile takes the schema's defaults, which are the `hikmicro_pocket2` profile's: naming it changes no "
         "frame (only `scene.json`, which then names it).\n\n"
      << "The frame rate is the top-level `frame_rate_hz`. A scene that gives a value keeps it: the shipped "
         "scenes give 25 Hz, and `paper_room.json` also gives the paper camera's 256 × 192 px and 50°, so "
         "`--set camera.profile=flir_lepton_3_5` on it changes only what it leaves out (NETD, FFC, output "
         "step). `scenes/lepton_room.json` is the paper room with the Lepton profile and nothing it sets. "
         "A profile does not change `frames`: "
         "the robot drives at the same speed, so 1996 frames last 229 s at 8.7 Hz and 33 s (under a lap) at "
         "60 Hz; set `frames` to the length you need.\n\n"
      << "A camera's FFC on its own temperature change (`camera.ffc_temperature_delta_k`) is modelled with the "
         "housing warming that drives the lens shading (`camera.housing_warming_k_per_min`, K/min since the last "
         "FFC): the next FFC comes when the interval has passed or the housing has warmed by the threshold, "
         "whichever is first ([the sensor model](sensor_and_thermal.md)). Where a datasheet is silent the table "
         "says so and why the value was chosen.\n\n";
  out << "| field |";
  for (const CameraProfile& p : CameraProfiles()) out << " `" << p.name << "` |";
  out << "\n|---|";
  for (size_t i = 0; i < CameraProfiles().size(); ++i) out << "---|";
  out << "\n";
  for (size_t f = 0; f < CameraProfileFields().size(); ++f) {
    out << "| `" << CameraProfileFields()[f].substr(1) << "` |";
    for (const CameraProfile& p : CameraProfiles()) out << " " << p.values[f].value.dump() << " |";
    out << "\n";
  }
  for (const CameraProfile& p : CameraProfiles()) {
    out << "\n## `" << p.name << "`\n\n"
        << p.camera << ". Sources: " << p.documents << "\n\n"
        << "| field | value | source |\n|---|---|---|\n";
    for (const CameraProfileValue& v : p.values) {
      out << "| `" << v.pointer.substr(1) << "` | " << v.value.dump() << " | " << v.source << " |\n";
    }
  }
  return out.str();
}

}  // namespace hoilcd
