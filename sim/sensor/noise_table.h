#pragma once
// Gaussian noise for whole images at the cost of a table lookup per sample:
// unit-sigma draws stored as int8 (x16), read from a fresh seeded offset per
// row, so noise differs per row and frame and stays byte-identical.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/rng.h"

namespace depot::sim {

// 2^20 draws of 16 x N(0, 1), clamped to int8.
const std::vector<int8_t>& unit_noise_table();

// `count` consecutive draws starting at a random offset taken from `rng`.
const int8_t* noise_row(Rng& rng, size_t count);

}  // namespace depot::sim
