// SPDX-License-Identifier: Apache-2.0
// How precisely a table stores each output on disk (docs/table-format.md, "Storage precision",
// format 2.2). The creep and wear outputs, 90 % of a table's values, are stored as IEEE float32
// holding 20 significant bits: each value rounded once, to nearest (ties to even), keeping 19 of
// float32's 23 explicit significand bits (netCDF's "BitRound" quantization, recorded in the
// dataset attribute _QuantizeBitRoundNumberOfSignificantBits = 19). The relative rounding, at most
// 2^-20 = 9.5e-7, is four orders below the interpolation error of a table (~1e-2 of mu N). Half
// the bytes, and zeroed low bits that deflate packs: the default table shrinks from 4.12 MB to
// 1.63 MB (docs/table-format.md, "Storage precision"). Everything else stays float64 (why:
// storage_precision.cpp).
#pragma once

#include <string>

#include "table/table.hpp"

namespace railtab {

// Explicit significand bits a float32 output keeps (netCDF BitRound's NSB).
inline constexpr int kStoredSignificandBits = 19;
// Largest relative rounding of a float32 output: |stored - value| <= kStoredRounding * |value|.
inline constexpr double kStoredRounding = 0x1p-20;
// Attribute of every float32 output dataset, value kStoredSignificandBits (int32).
inline constexpr const char* kQuantizeAttribute = "_QuantizeBitRoundNumberOfSignificantBits";

// Whether `table`'s format stores outputs as float32: its format_version is 2.2 or newer (or it
// has none, as a table being built). A table read from an older file keeps float64 when merged.
bool table_stores_float32(const Table& table);

// Whether dataset `d` of group `group` ("left/creep", "jumps/right/wear", ...) is a float32
// output in a table whose format stores them: a non-status dataset of a creep or wear part.
bool stored_as_float32(const std::string& group, const TableDataset& d);

// `value` rounded to kStoredSignificandBits + 1 significant bits, as a float32 (exact: it has
// fewer bits than float32 holds). Non-finite values stay non-finite; a finite value beyond the
// float32 range gives an infinity (the writer refuses it). Rounding a stored value again
// returns it unchanged, so merged shards keep their bytes.
float quantize_for_storage(double value);

}  // namespace railtab
