// SPDX-License-Identifier: Apache-2.0
// What the interpolation kernel files (interpolate_linear*.cpp, interpolate_cubic.cpp,
// interpolate_jump.cpp) share: storing one slot's results into a Contact, and how many values a
// record of each value type may hold. The kernels live in four files so that a build compiles
// them on separate cores (each instantiates dozens of kernels; one file took minutes under ASan).
#pragma once

#include <cstring>

#include "interpolate.hpp"
#include "table_data.hpp"

namespace railtab::lookup::detail {

// Copies the cell's part statuses (query layout: n_parts uint32 after the values of the cell's
// corner-0 record) into `c`.
inline void store_status(const Block& b, RecordPtr cell_record, Contact& c) noexcept {
  const unsigned char* st = cell_record + b.status_offset;
  for (int p = 0; p < b.n_parts; ++p)
    std::memcpy(&c.part_status[b.part[p]], st + p * sizeof(StatusBits), sizeof(StatusBits));
}

// Copies one slot's values (record order: parts, outputs) into `c` (Block::output_of).
inline void store_values(const Block& b, const double* values, Contact& c) noexcept {
  for (int k = 0; k < b.n_values; ++k) c.value[b.output_of[k]] = values[k];
}

// Value counts 1..kMaxSlotValues for doubles, 1..kMaxFloatValues for floats.
template <class T>
inline constexpr int kMaxValues = sizeof(T) == sizeof(float) ? kMaxFloatValues : kMaxSlotValues;
}  // namespace railtab::lookup::detail
