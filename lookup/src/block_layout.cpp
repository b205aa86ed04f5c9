// SPDX-License-Identifier: Apache-2.0
// The query layout of a block (table_data.hpp): records without status padding, and per node
// the status of the cell it starts, so a query reads one status word per part instead of
// folding the 2^D corners.
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "interpolate.hpp"
#include "table_data.hpp"

namespace railtab::lookup::detail {
namespace {

// Status of a cell: trouble bits from ANY corner, kConverged only if ALL corners converged.
StatusBits fold_cell(const std::vector<StatusBits>& node_status, std::size_t node,
                     const std::size_t* node_stride, int n_dims) {
  StatusBits any = 0, all = ~0u;
  for (int c = 0; c < (1 << n_dims); ++c) {
    std::size_t k = node;
    for (int d = 0; d < n_dims; ++d)
      if (c & (1 << d)) k += node_stride[d];
    any |= node_status[k];
    all &= node_status[k];
  }
  return (any & ~status::kConverged) | (all & status::kConverged);
}

}  // namespace

void prepare_query_layout(Block& b, int n_slots) {
  const int node_record = b.record;           // node layout, as make_block wrote it
  const std::size_t nodes = b.slot_size / static_cast<std::size_t>(node_record);
  for (int d = 0; d < b.n_dims; ++d) {
    const std::size_t outer = d == 0 ? b.slot_size : b.stride[d - 1];
    b.size[d] = static_cast<int>(outer / b.stride[d]);
  }
  const int status_doubles = (b.n_parts + 1) / 2;
  b.status_offset = b.n_values;
  b.record = (b.n_values + status_doubles + 1) / 2 * 2;

  std::size_t node_stride[kMaxDims];  // nodes between neighbours along each dimension
  std::size_t stride = 1;
  for (int d = b.n_dims - 1; d >= 0; --d) {
    node_stride[d] = stride;
    b.stride[d] = stride * static_cast<std::size_t>(b.record);
    stride *= static_cast<std::size_t>(b.size[d]);
  }
  const std::size_t slot_size = nodes * static_cast<std::size_t>(b.record);

  std::vector<double, CacheAligned<double>> data(static_cast<std::size_t>(n_slots) * slot_size,
                                                 0.0);
  std::vector<StatusBits> node_status(nodes);
  for (int s = 0; s < n_slots; ++s) {
    const double* in = b.data.data() + static_cast<std::size_t>(s) * b.slot_size;
    double* out = data.data() + static_cast<std::size_t>(s) * slot_size;
    for (int p = 0; p < b.n_parts; ++p) {
      for (std::size_t n = 0; n < nodes; ++n) {
        const auto* st = reinterpret_cast<const unsigned char*>(
            in + n * static_cast<std::size_t>(node_record) + b.values_padded);
        std::memcpy(&node_status[n], st + static_cast<std::size_t>(p) * sizeof(StatusBits),
                    sizeof(StatusBits));
      }
      for (std::size_t n = 0; n < nodes; ++n) {
        // A node starts a cell unless it is the last node along some dimension.
        bool starts_cell = true;
        std::size_t rest = n;
        for (int d = 0; d < b.n_dims; ++d) {
          const std::size_t i = rest / node_stride[d];
          rest %= node_stride[d];
          starts_cell = starts_cell && i + 1 < static_cast<std::size_t>(b.size[d]);
        }
        const StatusBits cell =
            starts_cell ? fold_cell(node_status, n, node_stride, b.n_dims) : node_status[n];
        auto* st = reinterpret_cast<unsigned char*>(out + n * static_cast<std::size_t>(b.record) +
                                                    b.status_offset);
        std::memcpy(st + static_cast<std::size_t>(p) * sizeof(StatusBits), &cell,
                    sizeof(StatusBits));
      }
    }
    for (std::size_t n = 0; n < nodes; ++n)
      std::memcpy(out + n * static_cast<std::size_t>(b.record),
                  in + n * static_cast<std::size_t>(node_record),
                  static_cast<std::size_t>(b.n_values) * sizeof(double));
  }
  b.data = std::move(data);
  b.slot_size = slot_size;
  b.linear = linear_kernel_for(b.n_dims, b.n_values);
  b.cubic = cubic_kernel_for(b.n_values);
}

}  // namespace railtab::lookup::detail
