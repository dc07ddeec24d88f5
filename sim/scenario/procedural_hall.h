#pragma once
// A depot hall generated from the world seed (`scene: procedural`, the
// parameters under `hall:`): hall size, rows of back-to-back racks with
// aisles between them and a cross aisle through each row, a work area along
// the south wall with goods, pallets, a workbench and a desk (clutter), wall
// posters, ceiling lights with drawn positions and colour temperature, and
// wall and floor paint. The same parameters and seed always give the same
// layout.
//
// Along y (north = +y, as scenes/depot.yaml): a rack row against the north
// wall, then for each middle row an aisle and the row (two racks back to back,
// 1.7 m deep), then the south aisle and the work area (3 m). Every row ends an
// aisle's width from the east and west walls, so each row can be walked round.
//
// Routes (SceneLayout::routes) follow the layout, for `route:` in motion and
// actors: `aisle_1` (north) to `aisle_N` (south) along aisle centres, end to
// end; `cross` through every cross aisle, north to south; `patrol` a loop round
// the east part of row 1 through its cross aisle (round the whole row when it
// has none; along aisle_1 in a hall without middle rows); `loop_row_K` round
// the whole of row K.
#include <cstdint>
#include <string>

#include "sim/scenario/scene_layout.h"

namespace depot::sim {

// A value, or a range [low, high] drawn uniformly from the world seed.
struct HallRange {
  double low = 0.0, high = 0.0;
  std::string where;  // its key's file:line, for errors
};

struct ProceduralHallSpec {
  HallRange length{20, 20, ""};
  HallRange width{14, 14, ""};
  HallRange height{4.5, 4.5, ""};
  HallRange rack_rows{1, 2, ""};  // middle rows (integers), besides the north wall's
  HallRange aisle_width{2.6, 2.6, ""};
  HallRange rack_length{2.6, 2.6, ""};
  HallRange rack_levels{3, 4, ""};      // integers
  HallRange cross_aisle{3.0, 3.0, ""};  // m, the gap through each middle row; 0 = none
  HallRange clutter{0.6, 0.6, ""};      // share of the work area's places given goods, 0..1
  double robot_width = 0.8;             // m; an aisle must pass it with 0.4 m each side
  std::string robot_width_where;
  std::string where;  // the `hall:` map
};

// Refuses parameters no seed can lay out (one line naming the key): a range
// upside down or out of its limits, an aisle or cross aisle narrower than the
// robot and its clearance, a hall too narrow for its rows and aisles or too
// short for a row and its end aisles.
void check_procedural_hall(const ProceduralHallSpec& spec);

// The hall for one world seed (check_procedural_hall first).
SceneLayout generate_procedural_hall(const ProceduralHallSpec& spec, uint64_t world_seed);

}  // namespace depot::sim
