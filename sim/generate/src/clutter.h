// The clutter of lived-in rooms (`generator.options.objects.clutter_density`): papers, mugs,
// bottles, phones and power strips on table tops; skirting boards, window sills, blinds, a heating
// pipe run, cable trunking, a thermostat, air grilles, posters, pictures, notice boards and a clock
// on the walls; bookcases with books and binders, PC towers, bins, boxes, rugs and a router on the
// floor and furniture; diffusers, smoke detectors, sprinklers and a bulkhead on the ceiling.
// docs/guide/generate.md says where each goes and what density 1 means.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "hoilcd/core/util/random.h"
#include "hoilcd/sim/assets/asset.h"
#include "hoilcd/sim/world/world.h"
#include "layouts.h"

namespace hoilcd {

// The clutter of a room of size_m (x, y, z) furnished as `layout` (its furniture standing in
// `world`), with `windows` (scene /room/windows) and `doors`, that already holds `placed` (every
// object so far), whose robot drives `route`: none at density 0. Floor objects keep
// route_clearance_m from the route and clear of every footprint, doorway and seat's access; wall
// objects take free stretches of wall; table-top objects keep off every seat's place for its
// person's props and forearms.
std::vector<PlacedObject> Clutter(const Eigen::Vector3d& size_m, const Layout& layout,
                                  const nlohmann::ordered_json& windows, const std::vector<Eigen::Vector2d>& doors,
                                  const std::vector<PlacedObject>& placed, const World& world, AssetLibrary* assets,
                                  const std::vector<Eigen::Vector2d>& route, const GeneratorOptions& options, Rng* rng);

// Whether an object stands on the floor or on something that does (what the generator leaves out
// when a room cannot keep every seat reachable with them).
bool StandsOnTheFloor(const std::string& asset);

}  // namespace hoilcd
