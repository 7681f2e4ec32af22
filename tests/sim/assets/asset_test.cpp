#include "hoilcd/sim/assets/asset.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include "hoilcd/core/util/error.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

const std::string kAssetDir = std::string(HOILCD_TEST_SOURCE_DIR) + "/assets";
const std::vector<std::string> kPeople = {"person_seated_upright", "person_seated_leaning",
                                          "person_seated_arms_on_table", "person_standing"};
const std::vector<std::string> kSeatedPeople = {"person_seated_upright", "person_seated_leaning",
                                                "person_seated_arms_on_table"};

const Asset& Shipped(const std::string& name) {
  static AssetLibrary library(kAssetDir);
  return library.Get(name);
}

// Area-weighted centroid of the triangles of one region.
Eigen::Vector3f RegionCentroid(const Asset& asset, const std::string& region) {
  const int material = asset.MaterialIndex(region);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double area_sum = 0;
  const TriangleMesh& mesh = asset.mesh;
  for (size_t t = 0; t < mesh.TriangleCount(); ++t) {
    if (static_cast<int>(mesh.triangle_material[t]) != material) continue;
    const Eigen::Vector3d a = mesh.positions_m[mesh.indices[3 * t]].cast<double>();
    const Eigen::Vector3d b = mesh.positions_m[mesh.indices[3 * t + 1]].cast<double>();
    const Eigen::Vector3d c = mesh.positions_m[mesh.indices[3 * t + 2]].cast<double>();
    const double area = (b - a).cross(c - a).norm() / 2;
    sum += area * (a + b + c) / 3;
    area_sum += area;
  }
  return (sum / area_sum).cast<float>();
}

// Highest vertex of one region.
float RegionTop(const Asset& asset, const std::string& region) {
  const int material = asset.MaterialIndex(region);
  float top = -1e9f;
  for (size_t t = 0; t < asset.mesh.TriangleCount(); ++t) {
    if (static_cast<int>(asset.mesh.triangle_material[t]) != material) continue;
    for (int k = 0; k < 3; ++k) top = std::max(top, asset.mesh.positions_m[asset.mesh.indices[3 * t + k]].z());
  }
  return top;
}

std::vector<ContactPoint> Contacts(const Asset& asset, const std::string& name) {
  std::vector<ContactPoint> found;
  for (const ContactPoint& contact : asset.contacts) {
    if (contact.name == name) found.push_back(contact);
  }
  return found;
}

TEST(ShippedAssets, EveryAssetLoadsWithItsDocumentedClassAndAConsistentMesh) {
  const std::vector<std::pair<std::string, std::string>> expected = {{"person_seated_upright", "person"},
                                                                     {"person_seated_leaning", "person"},
                                                                     {"person_seated_arms_on_table", "person"},
                                                                     {"person_standing", "person"},
                                                                     {"table", "table"},
                                                                     {"chair", "chair"},
                                                                     {"cup", "cup"},
                                                                     {"laptop", "laptop"},
                                                                     {"monitor", "monitor"},
                                                                     {"radiator", "radiator"},
                                                                     {"round_table", "table"},
                                                                     {"square_table", "table"},
                                                                     {"desk", "table"},
                                                                     {"sofa", "sofa"},
                                                                     {"low_table", "table"},
                                                                     {"partition", "partition"},
                                                                     {"lectern", "lectern"},
                                                                     {"cabinet", "cabinet"},
                                                                     {"bag", "bag"},
                                                                     {"charger", "charger"}};
  for (const auto& [name, class_name] : expected) {
    SCOPED_TRACE(name);
    const Asset& asset = Shipped(name);
    EXPECT_EQ(asset.class_name, class_name);
    EXPECT_LT(fs::file_size(kAssetDir + "/" + name + ".gltf"), 400u * 1024u);
    const TriangleMesh& mesh = asset.mesh;
    ASSERT_GT(mesh.TriangleCount(), 0u);
    ASSERT_EQ(mesh.indices.size(), 3 * mesh.TriangleCount());
    for (uint32_t index : mesh.indices) ASSERT_LT(index, mesh.positions_m.size());
    for (uint32_t material : mesh.triangle_material) ASSERT_LT(material, asset.materials.size());
    EXPECT_NEAR(asset.bounds_m.min().z(), 0.0f, 1e-4f) << "origin must be on the floor";
  }
}

TEST(ShippedAssets, PeopleHave2kTo8kTrianglesAndADocumentedPosture) {
  for (const std::string& name : kPeople) {
    SCOPED_TRACE(name);
    const Asset& person = Shipped(name);
    EXPECT_GE(person.mesh.TriangleCount(), 2000u);
    EXPECT_LE(person.mesh.TriangleCount(), 8000u);
    EXPECT_EQ("person_" + person.posture, name);
  }
}

// The generated layouts' furniture (hoilcd generate) has the sizes assets/README.md documents:
// footprint x × y and height, m.
TEST(ShippedAssets, GeneratorFurnitureHasItsDocumentedSizes) {
  const std::vector<std::pair<std::string, Eigen::Vector3f>> expected = {
      {"round_table", {0.90f, 0.90f, 0.74f}}, {"square_table", {0.80f, 0.80f, 0.74f}},
      {"desk", {1.20f, 0.60f, 0.74f}},        {"sofa", {0.75f, 1.80f, 0.85f}},
      {"low_table", {1.00f, 0.50f, 0.42f}},   {"partition", {0.40f, 1.60f, 1.30f}},
      {"lectern", {0.50f, 0.60f, 1.17f}}};
  for (const auto& [name, size] : expected) {
    SCOPED_TRACE(name);
    const Eigen::Vector3f sizes = Shipped(name).bounds_m.sizes();
    EXPECT_NEAR(sizes.x(), size.x(), 0.01f);
    EXPECT_NEAR(sizes.y(), size.y(), 0.01f);
    EXPECT_NEAR(sizes.z(), size.z(), 0.01f);
  }
}

TEST(ShippedAssets, TableTopIsAt074MetresOver090By075Metres) {
  const Asset& table = Shipped("table");
  EXPECT_NEAR(table.bounds_m.max().z(), 0.74f, 1e-3f);
  EXPECT_NEAR(table.bounds_m.sizes().x(), 0.90f, 1e-3f);
  EXPECT_NEAR(table.bounds_m.sizes().y(), 0.75f, 1e-3f);
  EXPECT_NEAR(table.bounds_m.center().x(), 0.0f, 1e-3f);
  EXPECT_NEAR(table.bounds_m.center().y(), 0.0f, 1e-3f);
  EXPECT_NEAR(RegionTop(table, "wood"), 0.74f, 1e-3f);
  ASSERT_GE(table.MaterialIndex("metal"), 0);
  EXPECT_TRUE(table.materials[static_cast<size_t>(table.MaterialIndex("metal"))].specular);
}

TEST(ShippedAssets, ChairSeatIsAt045MetresWithTheBackrestBehind) {
  const Asset& chair = Shipped("chair");
  const int plastic = chair.MaterialIndex("plastic");
  ASSERT_GE(plastic, 0);
  float seat_top = 0;
  Eigen::Vector3d backrest = Eigen::Vector3d::Zero();
  int backrest_count = 0;
  for (size_t t = 0; t < chair.mesh.TriangleCount(); ++t) {
    if (static_cast<int>(chair.mesh.triangle_material[t]) != plastic) continue;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3f& p = chair.mesh.positions_m[chair.mesh.indices[3 * t + k]];
      if (p.z() < 0.5f) seat_top = std::max(seat_top, p.z());
      if (p.z() > 0.6f) {
        backrest += p.cast<double>();
        ++backrest_count;
      }
    }
  }
  EXPECT_NEAR(seat_top, 0.45f, 2e-3f);
  ASSERT_GT(backrest_count, 0);
  EXPECT_LT(backrest.x() / backrest_count, -0.15);
}

TEST(ShippedAssets, StandingPersonIs160To185MetresTallAndStandsBetweenItsFeet) {
  const Asset& person = Shipped("person_standing");
  EXPECT_GE(person.bounds_m.max().z(), 1.60f);
  EXPECT_LE(person.bounds_m.max().z(), 1.85f);
  const std::vector<ContactPoint> feet = Contacts(person, "floor");
  ASSERT_EQ(feet.size(), 2u);
  EXPECT_NEAR(feet[0].position_m.y() + feet[1].position_m.y(), 0.0f, 0.02f);
  EXPECT_NEAR(std::abs(feet[0].position_m.x()), 0.0f, 0.1f);
  EXPECT_TRUE(Contacts(person, "seat").empty());
}

TEST(ShippedAssets, SeatedPeopleHeadTopIsBetween120And140Metres) {
  for (const std::string& name : kSeatedPeople) {
    SCOPED_TRACE(name);
    const Asset& person = Shipped(name);
    EXPECT_GE(RegionTop(person, "hair"), 1.20f);
    EXPECT_LE(RegionTop(person, "hair"), 1.40f);
    EXPECT_NEAR(person.bounds_m.max().z(), RegionTop(person, "hair"), 0.01f);
  }
}

TEST(ShippedAssets, PeopleFacePlusXWithHairBehindTheFaceAndSymmetricInY) {
  for (const std::string& name : kPeople) {
    SCOPED_TRACE(name);
    const Asset& person = Shipped(name);
    const Eigen::Vector3f hair = RegionCentroid(person, "hair");
    // Face: skin above the hair's lowest point (so hands and neck do not count).
    const int skin = person.MaterialIndex("skin");
    const float hair_bottom = RegionTop(person, "hair") - 0.25f;
    Eigen::Vector3d face = Eigen::Vector3d::Zero();
    int face_count = 0;
    for (size_t t = 0; t < person.mesh.TriangleCount(); ++t) {
      if (static_cast<int>(person.mesh.triangle_material[t]) != skin) continue;
      const Eigen::Vector3f& p = person.mesh.positions_m[person.mesh.indices[3 * t]];
      if (p.z() > hair_bottom + 0.08f) {
        face += p.cast<double>();
        ++face_count;
      }
    }
    ASSERT_GT(face_count, 0);
    EXPECT_GT(face.x() / face_count, hair.x() + 0.03);
    EXPECT_NEAR(hair.y(), 0.0f, 0.01f);
    EXPECT_GT(hair.z(), RegionCentroid(person, "clothing_upper").z());
    EXPECT_GT(RegionCentroid(person, "shoes").x(), hair.x());
    EXPECT_LT(RegionCentroid(person, "shoes").z(), 0.1f);
  }
}

TEST(ShippedAssets, PeopleHaveSkinHairAndClothingAtDocumentedTemperatures) {
  const std::vector<std::tuple<std::string, double, double>> regions = {{"skin", 34.0, 0.98},
                                                                        {"hair", 30.0, 0.95},
                                                                        {"clothing_upper", 28.5, 0.90},
                                                                        {"clothing_lower", 27.5, 0.90},
                                                                        {"shoes", 25.0, 0.90}};
  for (const std::string& name : kPeople) {
    SCOPED_TRACE(name);
    const Asset& person = Shipped(name);
    for (const auto& [region, temperature_c, emissivity] : regions) {
      const int index = person.MaterialIndex(region);
      ASSERT_GE(index, 0) << region;
      const ThermalMaterial& material = person.materials[static_cast<size_t>(index)];
      EXPECT_DOUBLE_EQ(material.temperature_c, temperature_c) << region;
      EXPECT_DOUBLE_EQ(material.emissivity, emissivity) << region;
      EXPECT_FALSE(material.specular) << region;
    }
  }
}

TEST(ShippedAssets, SeatedPeopleTouchTheSeatAt040To050MetresAndTheFloorWithBothFeet) {
  for (const std::string& name : kSeatedPeople) {
    SCOPED_TRACE(name);
    const Asset& person = Shipped(name);
    const std::vector<ContactPoint> seat = Contacts(person, "seat");
    ASSERT_EQ(seat.size(), 1u);
    EXPECT_GE(seat[0].position_m.z(), 0.40f);
    EXPECT_LE(seat[0].position_m.z(), 0.50f);
    EXPECT_LT(seat[0].position_m.head<2>().norm(), 0.1f) << "seat contact above the origin";
    const std::vector<ContactPoint> feet = Contacts(person, "floor");
    ASSERT_EQ(feet.size(), 2u);
    for (const ContactPoint& foot : feet) EXPECT_NEAR(foot.position_m.z(), 0.0f, 1e-4f);
  }
}

TEST(ShippedAssets, ForearmsOnTheTableTouchItsTopBeyondTheNearEdge) {
  EXPECT_TRUE(Contacts(Shipped("person_seated_upright"), "table").empty());
  for (const char* name : {"person_seated_leaning", "person_seated_arms_on_table"}) {
    SCOPED_TRACE(name);
    const std::vector<ContactPoint> table = Contacts(Shipped(name), "table");
    ASSERT_EQ(table.size(), 2u);
    for (const ContactPoint& contact : table) {
      EXPECT_NEAR(contact.position_m.z(), 0.74f, 1e-3f);
      EXPECT_GE(contact.position_m.x(), 0.30f);
    }
  }
  // The leaning person reaches further over the table than the upright one.
  EXPECT_GT(RegionCentroid(Shipped("person_seated_leaning"), "hair").x(),
            RegionCentroid(Shipped("person_seated_arms_on_table"), "hair").x() + 0.05f);
}

TEST(ShippedAssets, HotObjectsCarryTheirThermalProperties) {
  const Asset& cup = Shipped("cup");
  ASSERT_GE(cup.MaterialIndex("coffee"), 0);
  EXPECT_DOUBLE_EQ(cup.materials[static_cast<size_t>(cup.MaterialIndex("coffee"))].temperature_c, 55);
  EXPECT_DOUBLE_EQ(cup.materials[static_cast<size_t>(cup.MaterialIndex("ceramic"))].temperature_c, 45);
  EXPECT_NEAR(cup.bounds_m.max().z(), 0.085f, 5e-3f);
  const Asset& radiator = Shipped("radiator");
  EXPECT_DOUBLE_EQ(radiator.materials[static_cast<size_t>(radiator.MaterialIndex("radiator"))].temperature_c, 42);
  EXPECT_NEAR(radiator.bounds_m.sizes().y(), 1.0f, 0.01f);
  EXPECT_NEAR(radiator.bounds_m.sizes().x(), 0.1f, 0.01f);
  EXPECT_GE(Shipped("laptop").MaterialIndex("laptop_screen"), 0);
  EXPECT_GE(Shipped("monitor").MaterialIndex("monitor_back"), 0);
}

// The room objects (docs/models/room_objects.md): class, mount, size (x out of the wall or forward,
// y along, z up), each region's temperature, emissivity and specular flag, and where the origin is.
TEST(ShippedAssets, RoomObjectsHaveTheirDocumentedClassMountSizeAndThermalRegions) {
  struct Region {
    std::string name;
    double temperature_c, emissivity;
    bool specular;
  };
  struct Expected {
    std::string name, class_name, mount;
    Eigen::Vector3f size_m;
    std::vector<Region> regions;
  };
  const std::vector<Expected> expected = {
      {"whiteboard",
       "whiteboard",
       "wall",
       {0.08f, 1.80f, 1.20f},
       {{"whiteboard", 22, 0.88, true}, {"anodized_aluminium", 22, 0.55, true}}},
      {"door_frame",
       "door",
       "wall",
       {0.063f, 1.04f, 2.12f},
       {{"painted_wood", 22, 0.93, false}, {"door_leaf", 22, 0.90, false}, {"metal", 22, 0.10, true}}},
      {"ac_unit",
       "ac_unit",
       "wall",
       {0.20f, 0.80f, 0.28f},
       {{"plastic", 22, 0.94, false}, {"ac_louvre", 15, 0.94, false}}},
      {"light_switch", "switch", "wall", {0.016f, 0.086f, 0.086f}, {{"plastic", 22, 0.94, false}}},
      {"wall_socket", "socket", "wall", {0.014f, 0.172f, 0.086f}, {{"plastic", 22, 0.94, false}}},
      {"shelf",
       "shelf",
       "wall",
       {0.25f, 0.90f, 0.50f},
       {{"wood", 22, 0.90, false}, {"books", 22, 0.93, false}, {"metal", 22, 0.10, true}}},
      {"cabinet",
       "cabinet",
       "floor",
       {0.443f, 0.80f, 1.34f},
       {{"painted_steel", 22, 0.93, false}, {"metal", 22, 0.10, true}, {"books", 22, 0.93, false}}},
      {"ceiling_light",
       "ceiling_light",
       "hanging",
       {0.60f, 0.60f, 0.041f},
       {{"light_frame", 30, 0.93, false}, {"light_diffuser", 26, 0.94, false}}},
      {"bag", "bag", "floor", {0.32f, 0.14f, 0.488f}, {{"bag_fabric", 22, 0.90, false}}},
      {"coat", "coat", "hanging", {0.102f, 0.44f, 0.492f}, {{"coat", 25, 0.90, false}}},
      {"charger", "charger", "floor", {0.11f, 0.05f, 0.03f}, {{"charger", 40, 0.94, false}}},
      // The clutter of lived-in rooms.
      {"pc_tower",
       "pc",
       "floor",
       {0.457f, 0.20f, 0.45f},
       {{"pc_case", 24, 0.93, false}, {"pc_exhaust", 34, 0.93, false}}},
      {"desk_phone", "phone", "floor", {0.20f, 0.22f, 0.084f}, {{"phone", 26, 0.94, false}}},
      {"router", "router", "floor", {0.14f, 0.20f, 0.18f}, {{"router", 33, 0.94, false}}},
      {"power_strip", "power_strip", "floor", {0.056f, 0.30f, 0.048f}, {{"plastic", 22, 0.94, false}}},
      {"mug", "mug", "floor", {0.082f, 0.1075f, 0.095f}, {{"mug", 22, 0.92, false}}},
      {"bottle", "bottle", "floor", {0.066f, 0.066f, 0.225f}, {{"bottle", 22, 0.94, false}}},
      {"papers", "papers", "floor", {0.237f, 0.305f, 0.021f}, {{"paper", 22, 0.93, false}}},
      {"binder_row", "binders", "floor", {0.29f, 0.388f, 0.32f}, {{"binder", 22, 0.94, false}}},
      {"book_row", "books", "floor", {0.20f, 0.338f, 0.28f}, {{"books", 22, 0.93, false}}},
      {"bookcase", "bookcase", "floor", {0.32f, 0.80f, 1.80f}, {{"wood", 22, 0.90, false}}},
      {"poster", "poster", "wall", {0.002f, 0.594f, 0.841f}, {{"poster", 22, 0.89, false}}},
      {"framed_picture",
       "picture",
       "wall",
       {0.027f, 0.50f, 0.40f},
       {{"painted_wood", 22, 0.93, false}, {"glass", 22, 0.94, true}}},
      {"wall_clock", "clock", "wall", {0.04f, 0.30f, 0.30f}, {{"plastic", 22, 0.94, false}, {"glass", 22, 0.94, true}}},
      {"notice_board",
       "notice_board",
       "wall",
       {0.0235f, 0.90f, 0.60f},
       {{"wood", 22, 0.90, false}, {"pinboard", 22, 0.90, false}, {"paper", 22, 0.93, false}}},
      {"thermostat", "thermostat", "wall", {0.025f, 0.08f, 0.08f}, {{"plastic", 22, 0.94, false}}},
      {"supply_grille",
       "grille",
       "wall",
       {0.025f, 0.40f, 0.15f},
       {{"painted_steel", 22, 0.93, false}, {"supply_air", 30, 0.93, false}}},
      {"return_grille", "grille", "wall", {0.03f, 0.40f, 0.30f}, {{"painted_steel", 22, 0.93, false}}},
      {"heating_pipe",
       "pipe",
       "wall",
       {0.056f, 1.0f, 0.13f},
       {{"heating_flow", 45, 0.93, false}, {"heating_return", 37, 0.93, false}, {"plastic", 22, 0.94, false}}},
      {"cable_trunking", "trunking", "wall", {0.04f, 1.0f, 0.06f}, {{"plastic", 22, 0.94, false}}},
      {"skirting_board", "skirting", "wall", {0.015f, 1.0f, 0.08f}, {{"painted_wood", 22, 0.93, false}}},
      {"skirting_board_short", "skirting", "wall", {0.015f, 0.20f, 0.08f}, {{"painted_wood", 22, 0.93, false}}},
      {"window_sill", "sill", "wall", {0.16f, 0.20f, 0.03f}, {{"painted_wood", 22, 0.93, false}}},
      {"blind",
       "blind",
       "wall",
       {0.07f, 0.20f, 0.67f},
       {{"painted_steel", 22, 0.93, false}, {"blind_fabric", 22, 0.90, false}}},
      {"bin", "bin", "floor", {0.30f, 0.30f, 0.35f}, {{"plastic", 22, 0.94, false}}},
      {"cardboard_box", "box", "floor", {0.40f, 0.30f, 0.301f}, {{"cardboard", 22, 0.93, false}}},
      {"rug", "rug", "floor", {1.60f, 1.20f, 0.01f}, {{"rug", 22, 0.90, false}}},
      {"ceiling_diffuser",
       "diffuser",
       "hanging",
       {0.60f, 0.60f, 0.06f},
       {{"painted_steel", 22, 0.93, false}, {"supply_air", 30, 0.93, false}}},
      {"smoke_detector", "detector", "hanging", {0.11f, 0.11f, 0.05f}, {{"plastic", 22, 0.94, false}}},
      {"sprinkler", "sprinkler", "hanging", {0.07f, 0.07f, 0.06f}, {{"metal", 22, 0.10, true}}},
      {"bulkhead", "bulkhead", "hanging", {0.40f, 1.0f, 0.25f}, {{"painted_plaster", 22, 0.93, false}}}};
  for (const Expected& e : expected) {
    SCOPED_TRACE(e.name);
    const Asset& asset = Shipped(e.name);
    EXPECT_EQ(asset.class_name, e.class_name);
    EXPECT_EQ(asset.mount, e.mount);
    EXPECT_LE(asset.mesh.TriangleCount(), 400u) << "room objects stay small";
    const Eigen::Vector3f size = asset.bounds_m.sizes();
    for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(size[axis], e.size_m[axis], 0.005f) << "axis " << axis;
    for (const Region& r : e.regions) {
      const int m = asset.MaterialIndex(r.name);
      ASSERT_GE(m, 0) << r.name;
      const ThermalMaterial& material = asset.materials[static_cast<size_t>(m)];
      EXPECT_DOUBLE_EQ(material.temperature_c, r.temperature_c) << r.name;
      EXPECT_DOUBLE_EQ(material.emissivity, r.emissivity) << r.name;
      EXPECT_EQ(material.specular, r.specular) << r.name;
    }
    EXPECT_EQ(asset.materials.size(), e.regions.size());
    if (e.mount == "wall") {
      EXPECT_NEAR(asset.bounds_m.min().x(), 0.0f, 1e-4f) << "the back face is on the wall";
      EXPECT_NEAR(asset.bounds_m.center().y(), 0.0f, 1e-3f) << "centred along the wall";
      EXPECT_NEAR(asset.bounds_m.min().z(), 0.0f, 1e-4f) << "the origin is at the bottom";
    }
  }
  EXPECT_NEAR(Shipped("ceiling_light").bounds_m.max().z(), 0.0f, 1e-4f) << "hangs from its top face";
  for (const char* ceiling : {"ceiling_diffuser", "smoke_detector", "sprinkler", "bulkhead"}) {
    EXPECT_NEAR(Shipped(ceiling).bounds_m.max().z(), 0.0f, 1e-4f) << ceiling << " hangs from its top face";
  }
  // The exhaust grille is on the PC's back (-x), the monitor's and PC's heat where it leaves.
  EXPECT_LT(RegionCentroid(Shipped("pc_tower"), "pc_exhaust").x(), -0.2f);
  // A rug is low enough to be driven over (it is no footprint, world.cpp).
  EXPECT_LE(Shipped("rug").bounds_m.max().z(), 0.02f);
  EXPECT_NEAR(Shipped("coat").bounds_m.max().z(), 0.04f, 2e-3f) << "folded over the backrest's top edge";
  // The louvre is the unit's underside, facing the floor in front of the casing.
  EXPECT_LT(RegionCentroid(Shipped("ac_unit"), "ac_louvre").z(), 0.03f);
  EXPECT_GT(RegionCentroid(Shipped("whiteboard"), "whiteboard").x(), 0.0f);
}

// The powered parts' heat (docs/models/room_objects.md): with the room's thermal solution their
// temperature comes from it; every other part of the shipped assets states none.
TEST(ShippedAssets, PoweredPartsStateTheirDocumentedPowerAndNoOtherPartStatesOne) {
  const std::map<std::pair<std::string, std::string>, double> powered = {{{"monitor", "monitor_back"}, 13.0},
                                                                         {{"monitor", "monitor_screen"}, 4.0},
                                                                         {{"pc_tower", "pc_case"}, 10.0},
                                                                         {{"desk_phone", "phone"}, 6.0},
                                                                         {{"router", "router"}, 8.0}};
  for (const fs::directory_entry& e : fs::directory_iterator(kAssetDir)) {
    if (e.path().extension() != ".gltf") continue;
    const std::string name = e.path().stem().string();
    const Asset& asset = Shipped(name);
    for (const ThermalMaterial& m : asset.materials) {
      const auto it = powered.find({name, m.region});
      EXPECT_DOUBLE_EQ(m.power_w, it == powered.end() ? 0.0 : it->second) << name << " " << m.region;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Hand-written glTF files: one triangle (0,0,0), (1,0,0), (0,1,0) in tri.bin.

class GltfFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    temp_ = std::make_unique<test::TestDir>();
    dir_ = temp_->path() / "assets";
    fs::create_directories(dir_);
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::ofstream(dir_ / "tri.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(positions), sizeof(positions));
    gltf_ = {{"asset", {{"version", "2.0"}}},
             {"buffers", {{{"uri", "tri.bin"}, {"byteLength", 36}}}},
             {"bufferViews", {{{"buffer", 0}, {"byteLength", 36}}}},
             {"accessors",
              {{{"bufferView", 0},
                {"componentType", 5126},
                {"count", 3},
                {"type", "VEC3"},
                {"min", {0, 0, 0}},
                {"max", {1, 1, 0}}}}},
             {"materials",
              {{{"name", "warm"},
                {"extras", {{"temperature_c", 30}, {"emissivity", 0.5}, {"specular", true}, {"region", "r"}}}}}},
             {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"material", 0}}}}}}},
             {"nodes", {{{"mesh", 0}}}},
             {"scenes", {{{"nodes", {0}}, {"extras", {{"class", "thing"}}}}}},
             {"scene", 0}};
  }
  void TearDown() override { temp_.reset(); }

  std::string Write(const std::string& text, const std::string& name = "test.gltf") {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }
  std::string Write() { return Write(gltf_.dump()); }

  // The message of the InputError LoadAsset(path) throws, or "" if it does not throw.
  static std::string LoadError(const std::string& path) {
    try {
      LoadAsset(path);
    } catch (const InputError& error) {
      return error.what();
    }
    return "";
  }

  std::unique_ptr<test::TestDir> temp_;
  fs::path dir_;  // the glTF files' folder, inside temp_
  nlohmann::json gltf_;
};

TEST_F(GltfFileTest, ConvertsGltfAxesToTheAssetFrameAndReadsMaterialExtras) {
  const Asset asset = LoadAsset(Write());
  EXPECT_EQ(asset.class_name, "thing");
  ASSERT_EQ(asset.mesh.positions_m.size(), 3u);
  // (x, y, z)_hoilcd = (Z, X, Y)_gltf.
  EXPECT_TRUE(asset.mesh.positions_m[1].isApprox(Eigen::Vector3f(0, 1, 0)));
  EXPECT_TRUE(asset.mesh.positions_m[2].isApprox(Eigen::Vector3f(0, 0, 1)));
  ASSERT_EQ(asset.materials.size(), 1u);
  EXPECT_EQ(asset.materials[0].name, "warm");
  EXPECT_EQ(asset.materials[0].region, "r");
  EXPECT_DOUBLE_EQ(asset.materials[0].temperature_c, 30);
  EXPECT_DOUBLE_EQ(asset.materials[0].emissivity, 0.5);
  EXPECT_TRUE(asset.materials[0].specular);
  EXPECT_EQ(asset.MaterialIndex("r"), 0);
  EXPECT_EQ(asset.MaterialIndex("skin"), -1);
}

TEST_F(GltfFileTest, AppliesTranslationRotationScaleAndMatrixThroughTheHierarchy) {
  // Root: translate +1 along glTF X. Child: rotate 90° about glTF Y, scale 2. Grandchild: a
  // matrix translating +1 along glTF Y, holding the mesh.
  const double s = std::sqrt(0.5);
  gltf_["nodes"] = {{{"translation", {1, 0, 0}}, {"children", {1}}},
                    {{"rotation", {0, s, 0, s}}, {"scale", {2, 2, 2}}, {"children", {2}}},
                    {{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 1}}, {"mesh", 0}}};
  const Asset asset = LoadAsset(Write());
  ASSERT_EQ(asset.mesh.positions_m.size(), 3u);
  // glTF vertex (1,0,0): +Y 1 -> (1,1,0); rotate about Y by 90° -> (0,1,-1); scale 2 -> (0,2,-2);
  // translate -> (1,2,-2); hoilcd (Z, X, Y) = (-2, 1, 2).
  EXPECT_TRUE(asset.mesh.positions_m[1].isApprox(Eigen::Vector3f(-2, 1, 2), 1e-5f))
      << asset.mesh.positions_m[1].transpose();
  EXPECT_TRUE(asset.bounds_m.min().isApprox(Eigen::Vector3f(-2, 1, 2), 1e-5f));
}

TEST_F(GltfFileTest, MaterialWithoutExtrasAndPrimitiveWithoutMaterialGetDefaults) {
  gltf_["materials"][0].erase("extras");
  gltf_["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}}});
  const Asset asset = LoadAsset(Write());
  ASSERT_EQ(asset.materials.size(), 2u);
  EXPECT_EQ(asset.materials[0].region, "warm");
  EXPECT_DOUBLE_EQ(asset.materials[0].temperature_c, 22);
  EXPECT_DOUBLE_EQ(asset.materials[0].emissivity, 0.9);
  EXPECT_FALSE(asset.materials[0].specular);
  EXPECT_EQ(asset.materials[1].region, "default");
  ASSERT_EQ(asset.mesh.triangle_material.size(), 2u);
  EXPECT_EQ(asset.mesh.triangle_material[0], 0u);
  EXPECT_EQ(asset.mesh.triangle_material[1], 1u);
}

TEST_F(GltfFileTest, ContactPositionsAreConvertedToTheAssetFrame) {
  gltf_["scenes"][0]["extras"]["contacts"] = {{{"name", "seat"}, {"position", {0.1, 0.45, -0.05}}}};
  gltf_["scenes"][0]["extras"]["posture"] = "seated_upright";
  const Asset asset = LoadAsset(Write());
  EXPECT_EQ(asset.posture, "seated_upright");
  ASSERT_EQ(asset.contacts.size(), 1u);
  EXPECT_EQ(asset.contacts[0].name, "seat");
  EXPECT_TRUE(asset.contacts[0].position_m.isApprox(Eigen::Vector3f(-0.05f, 0.1f, 0.45f)));
}

TEST_F(GltfFileTest, MissingFileIsAnInputErrorNamingIt) {
  const std::string path = (dir_ / "nowhere.gltf").string();
  const std::string message = LoadError(path);
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("not found"), std::string::npos) << message;
}

TEST_F(GltfFileTest, MalformedJsonIsAnInputErrorNamingTheFile) {
  const std::string path = Write("{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [");
  const std::string message = LoadError(path);
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("cannot parse"), std::string::npos) << message;
}

TEST_F(GltfFileTest, EmissivityAboveOneIsAnInputErrorNamingFileAndJsonPath) {
  gltf_["materials"][0]["extras"]["emissivity"] = 1.5;
  const std::string path = Write();
  const std::string message = LoadError(path);
  EXPECT_NE(message.find(path + ": /materials/0/extras/emissivity"), std::string::npos) << message;
}

TEST_F(GltfFileTest, BadExtrasValuesAreAllReportedWithTheirPaths) {
  gltf_["materials"][0]["extras"] = {{"temperature_c", 300}, {"emissivity", 0}, {"specular", "yes"}, {"colour", 1}};
  gltf_["scenes"][0]["extras"]["contacts"] = {{{"name", "seat"}, {"position", {1, 2}}}};
  const std::string message = LoadError(Write());
  for (const char* pointer :
       {"/materials/0/extras/temperature_c", "/materials/0/extras/emissivity", "/materials/0/extras/specular",
        "/materials/0/extras/colour", "/scenes/0/extras/contacts/0/position"}) {
    EXPECT_NE(message.find(pointer), std::string::npos) << pointer << " in: " << message;
  }
}

TEST_F(GltfFileTest, MountIsReadAndABadMountIsReportedWithItsPath) {
  EXPECT_EQ(LoadAsset(Write()).mount, "floor");
  gltf_["scenes"][0]["extras"]["mount"] = "wall";
  EXPECT_EQ(LoadAsset(Write()).mount, "wall");
  gltf_["scenes"][0]["extras"]["mount"] = "ceiling";
  const std::string error = LoadError(Write());
  EXPECT_NE(error.find("test.gltf"), std::string::npos) << error;
  EXPECT_NE(error.find("/scenes/0/extras/mount: must be \"floor\", \"wall\" or \"hanging\""), std::string::npos)
      << error;
}

TEST_F(GltfFileTest, BadPartParentJointAndKeypointExtrasAreReportedWithTheirPaths) {
  gltf_["scenes"][0]["extras"]["part"] = "";
  gltf_["scenes"][0]["extras"]["parent"] = 3;
  gltf_["scenes"][0]["extras"]["joint"] = {0, 1};
  gltf_["scenes"][0]["extras"]["keypoints"] = {{{"name", "nose"}}, {{"name", ""}, {"position", {0, 0, 0}}}, 7};
  gltf_["scenes"][0]["extras"]["bone"] = "x";
  const std::string message = LoadError(Write());
  for (const char* expected :
       {"/scenes/0/extras/part: must be a non-empty string", "/scenes/0/extras/parent: must be a non-empty string",
        "/scenes/0/extras/joint: must be an array of 3 numbers",
        "/scenes/0/extras/keypoints/0: needs both name and position",
        "/scenes/0/extras/keypoints/1/name: must be a non-empty string",
        "/scenes/0/extras/keypoints/2: must be an object",
        "/scenes/0/extras/bone: unknown key (expected class, posture, mount, contacts, part, parent, joint, "
        "keypoints)"}) {
    EXPECT_NE(message.find(expected), std::string::npos) << expected << " in: " << message;
  }
  gltf_["scenes"][0]["extras"] = {{"class", "person"}, {"keypoints", "nose"}};
  const std::string not_array = LoadError(Write());
  EXPECT_NE(not_array.find("/scenes/0/extras/keypoints: must be an array of {name, position}"), std::string::npos)
      << not_array;
}

TEST_F(GltfFileTest, PartParentJointAndKeypointsAreReadInTheAssetFrame) {
  gltf_["scenes"][0]["extras"]["part"] = "head";
  gltf_["scenes"][0]["extras"]["parent"] = "neck";
  gltf_["scenes"][0]["extras"]["joint"] = {0.1, 1.5, 0.0};
  gltf_["scenes"][0]["extras"]["keypoints"] = {{{"name", "nose"}, {"position", {0.0, 1.6, 0.1}}}};
  const Asset asset = LoadAsset(Write());
  EXPECT_EQ(asset.part, "head");
  EXPECT_EQ(asset.parent, "neck");
  EXPECT_TRUE(asset.joint_m.isApprox(Eigen::Vector3f(0.0f, 0.1f, 1.5f))) << asset.joint_m.transpose();
  ASSERT_EQ(asset.keypoints.size(), 1u);
  EXPECT_EQ(asset.keypoints[0].name, "nose");
  EXPECT_TRUE(asset.keypoints[0].position_m.isApprox(Eigen::Vector3f(0.1f, 0.0f, 1.6f)));
}

TEST_F(GltfFileTest, NonTrianglePrimitiveIsAnInputError) {
  gltf_["meshes"][0]["primitives"][0]["mode"] = 1;  // LINES
  const std::string message = LoadError(Write());
  EXPECT_NE(message.find("/meshes/0/primitives/0/mode"), std::string::npos) << message;
}

TEST_F(GltfFileTest, PrimitiveWithoutPositionsIsAnInputError) {
  gltf_["meshes"][0]["primitives"][0]["attributes"] = {{"NORMAL", 0}};
  const std::string message = LoadError(Write());
  EXPECT_NE(message.find("/meshes/0/primitives/0/attributes"), std::string::npos) << message;
  EXPECT_NE(message.find("POSITION"), std::string::npos) << message;
}

TEST_F(GltfFileTest, AccessorPastTheEndOfItsBufferIsAnInputError) {
  gltf_["accessors"][0]["count"] = 4;
  const std::string message = LoadError(Write());
  EXPECT_NE(message.find("/accessors/0"), std::string::npos) << message;
}

TEST_F(GltfFileTest, LibraryLoadsEachFileOnceAndResolvesNamesInItsSearchDir) {
  Write(gltf_.dump(), "thing.gltf");
  AssetLibrary library(dir_.string());
  EXPECT_EQ(library.Resolve("thing"), (dir_ / "thing.gltf").string());
  EXPECT_EQ(library.Resolve("other/x.glb"), "other/x.glb");
  const Asset& first = library.Get("thing");
  const Asset& again = library.Get((dir_ / "thing.gltf").string());
  EXPECT_EQ(&first, &again);
  EXPECT_EQ(first.class_name, "thing");
  EXPECT_THROW(library.Get("missing"), InputError);
}

TEST(AssetLibrary, ShippedAssetDirHoldsTheShippedAssets) {
  EXPECT_TRUE(fs::exists(fs::path(ShippedAssetDir()) / "person_seated_upright.gltf"));
}

}  // namespace
}  // namespace hoilcd

namespace hoilcd {
namespace {

TEST_F(GltfFileTest, AccessorCountThatWrapsTheBoundsArithmeticIsAnInputError) {
  gltf_["accessors"][0]["count"] = (uint64_t{1} << 62) + 1;  // 12 * (count - 1) wraps to 0
  const std::string message = LoadError(Write());
  EXPECT_NE(message.find("/accessors/0"), std::string::npos) << message;
  EXPECT_NE(message.find("reads past the end"), std::string::npos) << message;
}

TEST_F(GltfFileTest, BufferViewOffsetThatWrapsTheBoundsArithmeticIsAnInputError) {
  gltf_["bufferViews"][0]["byteOffset"] = UINT64_MAX - 7;  // 2^64 - 8: offset + length wraps
  const std::string message = LoadError(Write());
  EXPECT_NE(message.find("reads past the end"), std::string::npos) << message;
}

TEST_F(GltfFileTest, BufferUriOutsideTheGltfFolderIsRefused) {
  fs::copy_file(dir_ / "tri.bin", temp_->path() / "outside.bin");
  gltf_["buffers"][0]["uri"] = "../outside.bin";
  const std::string message = LoadError(Write());
  EXPECT_NE(message.find("inside the glTF file's folder"), std::string::npos) << message;
}

TEST_F(GltfFileTest, BufferUriNamingAFifoIsRefusedWithoutWaiting) {
  ASSERT_EQ(::mkfifo((dir_ / "pipe.bin").c_str(), 0600), 0);
  gltf_["buffers"][0]["uri"] = "pipe.bin";
  const std::string message = LoadError(Write());  // before the fix: blocked here forever
  EXPECT_NE(message.find("not a regular file"), std::string::npos) << message;
}

}  // namespace
}  // namespace hoilcd

namespace hoilcd {
namespace {

// A glTF (or a .glb's JSON chunk) nested 10^5 deep in its extras, or repeating a key, is refused
// naming the file and pointer before tinygltf reads it (issue 45).
TEST(GltfJson, DeepNestingAndRepeatedKeysAreRefusedAtTheirPointers) {
  const test::TestDir dir;
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const std::string gltf = dir / "deep.gltf";
  std::ofstream(gltf) << R"({"asset": {"version": "2.0", "extras": )" << deep << "}}";
  std::string error;
  try {
    LoadAsset(gltf);
  } catch (const InputError& e) {
    error = e.what();
  }
  EXPECT_NE(error.find(gltf + ": /asset/extras/0/"), std::string::npos) << error.substr(0, 200);
  EXPECT_NE(error.find("nests deeper than 64 levels"), std::string::npos) << error.substr(0, 200);

  const std::string json = R"({"asset": {"version": "2.0", "version": "1.0"}})";
  std::string glb = std::string("glTF") + std::string("\x02\x00\x00\x00", 4) + std::string(4, '\0');
  const auto le32 = [](size_t n) {
    std::string out;
    for (int k = 0; k < 4; ++k) out += static_cast<char>((n >> (8 * k)) & 0xff);
    return out;
  };
  glb += le32(json.size()) + "JSON" + json;
  glb.replace(8, 4, le32(glb.size()));
  const std::string glb_path = dir / "twice.glb";
  std::ofstream(glb_path, std::ios::binary) << glb;
  error.clear();
  try {
    LoadAsset(glb_path);
  } catch (const InputError& e) {
    error = e.what();
  }
  EXPECT_NE(error.find(glb_path + ": /asset/version: the key \"version\" is repeated"), std::string::npos) << error;
}

}  // namespace
}  // namespace hoilcd
