// SPDX-License-Identifier: Apache-2.0
// The query layout of a block (table_data.hpp): per node its values and the status of the cell it
// starts, so a query reads one status word per part instead of folding the 2^D corners; and the
// float records of blocks whose values are all exactly floats (records.hpp).
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <utility>
#include <vector>

#include "interpolate.hpp"
#include "low_confidence.hpp"
#include "table_data.hpp"

namespace railtab::lookup::detail {
namespace {

// Status of a cell: trouble bits from ANY corner, kEveryCorner's (converged, full_slip) only if ALL
// corners have them.
StatusBits fold_cell(const StatusBits* node_status, std::size_t n_parts, std::size_t node,
                     const std::size_t* node_stride, int n_dims) {
  StatusBits any = 0, all = ~0u;
  for (int c = 0; c < (1 << n_dims); ++c) {
    std::size_t k = node;
    for (int d = 0; d < n_dims; ++d)
      if (c & (1 << d)) k += node_stride[d];
    any |= node_status[k * n_parts];
    all &= node_status[k * n_parts];
  }
  return (any & ~kEveryCorner) | (all & kEveryCorner);
}

// Whether the slot holds a contact at some corners of the cell and none at others: the cell spans
// an onset, a lift-off or a hand-over between slots that its nodes do not locate
// (low_confidence.hpp).
bool cell_presence_mixed(const StatusBits* node_status, std::size_t n_parts, std::size_t node,
                         const std::size_t* node_stride, int n_dims) {
  std::size_t corner[1 << kMaxDims];
  for (int c = 0; c < (1 << n_dims); ++c) {
    std::size_t k = node;
    for (int d = 0; d < n_dims; ++d)
      if (c & (1 << d)) k += node_stride[d];
    corner[c] = k;
  }
  auto status = [&](std::size_t k, int p) { return node_status[k * n_parts + static_cast<std::size_t>(p)]; };
  return mixed_presence(status, static_cast<int>(n_parts), corner, 1 << n_dims);
}

// The kernels of the block's shape and value type (interpolate.hpp).
void choose_kernels(Block& b) {
  b.linear = linear_kernel_for(b.n_dims, b.n_values, b.value_bytes);
  b.cubic = cubic_kernel_for(b.n_values, b.value_bytes);
  b.monotone = monotone_kernel_for(b.value_bytes);
}

// Whether value k of every record in `data` (records of `record` bytes, doubles) is a float.
bool exact_floats(const RecordBytes& data, int n_values, int record) {
  const std::size_t n = data.size() / static_cast<std::size_t>(record);
  for (std::size_t r = 0; r < n; ++r)
    for (int k = 0; k < n_values; ++k) {
      const double v = record_value<double>(data.data() + r * static_cast<std::size_t>(record), k);
      if (static_cast<double>(static_cast<float>(v)) != v) return false;
    }
  return true;
}

// The records of `data` (doubles, `record` bytes each) with float values, `narrow` bytes each:
// the same values (exact), the same statuses, zero padding.
RecordBytes narrow_records(const RecordBytes& data, int n_values, int n_parts, int record, int narrow) {
  const std::size_t n = data.size() / static_cast<std::size_t>(record);
  RecordBytes out(n * static_cast<std::size_t>(narrow), 0);
  for (std::size_t r = 0; r < n; ++r) {
    const unsigned char* in = data.data() + r * static_cast<std::size_t>(record);
    unsigned char* to = out.data() + r * static_cast<std::size_t>(narrow);
    for (int k = 0; k < n_values; ++k) {
      const float v = static_cast<float>(record_value<double>(in, k));
      std::memcpy(to + static_cast<std::size_t>(k) * sizeof v, &v, sizeof v);
    }
    std::memcpy(to + static_cast<std::size_t>(n_values) * sizeof(float),
                in + static_cast<std::size_t>(n_values) * sizeof(double),
                static_cast<std::size_t>(n_parts) * sizeof(StatusBits));
  }
  return out;
}

// A stride of whole records, from records of `record` bytes to records of `narrow` bytes.
std::size_t rescale(std::size_t stride, int record, int narrow) {
  return stride / static_cast<std::size_t>(record) * static_cast<std::size_t>(narrow);
}

}  // namespace

void prepare_query_layout(Block& b, const std::vector<double>& values, const std::vector<StatusBits>& status,
                          int n_slots) {
  b.value_bytes = sizeof(double);
  b.status_offset = b.n_values * b.value_bytes;
  b.record = record_bytes(b.n_values, b.value_bytes, b.n_parts);
  std::size_t node_stride[kMaxDims];  // nodes between neighbours along each dimension
  std::size_t nodes = 1;
  for (int d = b.n_dims - 1; d >= 0; --d) {
    node_stride[d] = nodes;
    b.stride[d] = nodes * static_cast<std::size_t>(b.record);
    nodes *= static_cast<std::size_t>(b.size[d]);
  }
  b.slot_size = nodes * static_cast<std::size_t>(b.record);
  b.data.assign(static_cast<std::size_t>(n_slots) * b.slot_size, 0);
  const std::size_t nv = static_cast<std::size_t>(b.n_values), np = static_cast<std::size_t>(b.n_parts);
  for (std::size_t s = 0; s < static_cast<std::size_t>(n_slots); ++s) {
    const StatusBits* node_status = status.data() + s * nodes * np;
    for (std::size_t n = 0; n < nodes; ++n) {
      unsigned char* out = b.data.data() + s * b.slot_size + n * static_cast<std::size_t>(b.record);
      std::memcpy(out, values.data() + (s * nodes + n) * nv, nv * sizeof(double));
      // A node starts a cell unless it is the last node along some dimension.
      bool starts_cell = true;
      std::size_t rest = n;
      for (int d = 0; d < b.n_dims; ++d) {
        const std::size_t i = rest / node_stride[d];
        rest %= node_stride[d];
        starts_cell = starts_cell && i + 1 < static_cast<std::size_t>(b.size[d]);
      }
      const bool mixed = starts_cell && cell_presence_mixed(node_status, np, n, node_stride, b.n_dims);
      for (std::size_t p = 0; p < np; ++p) {
        StatusBits cell = starts_cell ? fold_cell(node_status + p, np, n, node_stride, b.n_dims)
                                      : node_status[n * np + p];
        if (mixed) cell |= status::kLowConfidence;
        std::memcpy(out + b.status_offset + p * sizeof(StatusBits), &cell, sizeof cell);
      }
    }
  }
  choose_kernels(b);
}

void narrow_exact_blocks(TableData& d) {
  if (const char* env = std::getenv("RAILTAB_LOOKUP_NO_FLOAT_RECORDS"); env && *env && *env != '0') return;
  for (int bi = 0; bi < d.n_blocks; ++bi) {
    // Only the creep and wear block (what format 2.2 stores as float32): float records are summed
    // in float (weighted_sum.hpp), which is within the stored rounding there but would cost
    // digits in a geometry or normal block whose values merely happen to be floats.
    bool exact = bi == d.creep_block && d.block[0][bi].n_values <= kMaxFloatValues;  // interpolate.hpp
    for (int w = 0; w < 2 && exact; ++w) {
      const Block& b = d.block[w][bi];
      exact = b.value_bytes == sizeof(double) && exact_floats(b.data, b.n_values, b.record) &&
              (!d.has_jumps || exact_floats(d.jumps[w].samples[bi].data, b.n_values, b.record));
    }
    if (!exact) continue;
    for (int w = 0; w < 2; ++w) {
      Block& b = d.block[w][bi];
      const int narrow = record_bytes(b.n_values, sizeof(float), b.n_parts);
      b.data = narrow_records(b.data, b.n_values, b.n_parts, b.record, narrow);
      for (int k = 0; k < b.n_dims; ++k) b.stride[k] = rescale(b.stride[k], b.record, narrow);
      b.slot_size = rescale(b.slot_size, b.record, narrow);
      if (d.has_jumps) {
        JumpSamples& js = d.jumps[w].samples[bi];
        js.data = narrow_records(js.data, b.n_values, b.n_parts, b.record, narrow);
        for (std::size_t* s : {&js.slot_stride, &js.load_stride, &js.jump_stride, &js.side_stride})
          *s = rescale(*s, b.record, narrow);
        js.sum = jump_kernel_for(js.n_inner, b.n_values, sizeof(float));
      }
      b.value_bytes = sizeof(float);
      b.status_offset = b.n_values * b.value_bytes;
      b.record = narrow;
      choose_kernels(b);
    }
  }
}

}  // namespace railtab::lookup::detail
