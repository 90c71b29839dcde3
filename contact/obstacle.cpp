// SPDX-License-Identifier: BSD-3-Clause
// The registry of obstacle types: one line per type (each type is one file
// under contact/obstacles/), and the translated obstacle of a moving one.
#include "contact/obstacle.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace igac {

namespace {
const ObstacleType* const kObstacleTypes[] = {
    &plane_obstacle(),
    &sphere_obstacle(),
    &cylinder_obstacle(),
    &edge_obstacle(),
};
}  // namespace

std::span<const ObstacleType* const> obstacle_types() { return kObstacleTypes; }

const ObstacleType* find_obstacle_type(std::string_view name) {
  for (const ObstacleType* t : kObstacleTypes)
    if (t->name == name) return t;
  return nullptr;
}

std::string TranslatedObstacle::describe() const {
  return fmt::format("{}, moved by ({})", base_->describe(),
                     fmt::join(std::vector<double>(shift_.data(), shift_.data() + shift_.size()), ", "));
}

}  // namespace igac
