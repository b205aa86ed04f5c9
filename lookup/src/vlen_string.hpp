// SPDX-License-Identifier: Apache-2.0
// Variable-length string attributes (legacy tables, h5py's default) read WITHOUT libhdf5's
// variable-length read: a one-byte corruption of the heap reference or of the global heap makes
// that read allocate gigabytes or read out of bounds (issue #19). Instead the attribute's raw
// heap reference (length, collection address, object index) is taken from the attribute as
// stored, and the string is copied out of the file's bytes after every offset and size in the
// global heap collection has been checked against the collection and the file.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace railtab::lookup::detail {

// Where the file's addresses start and how big it is (from its creation properties).
struct RawFileLayout {
  std::string path;               // file to read the heap from
  std::uintmax_t size = 0;        // bytes
  std::uint64_t base = 0;         // address 0 = this byte offset (the user block size)
  std::size_t sizeof_addr = 8;    // bytes of a file address
  std::size_t sizeof_size = 8;    // bytes of a length
};

// The layout of the file that holds `object` (any open object or attribute of it), or "" and
// the problem. Also used by the generator's table reader (generator/CMakeLists.txt compiles this
// file into railtab::table too: neither library may link the other).
std::string raw_file_layout(hid_t object, RawFileLayout& out);

// Reads the scalar variable-length string attribute `attr` into `out`. Returns "" on success,
// else the problem (e.g. "its global heap at 4096 is corrupt: object 3 runs past the
// collection"). Never reads more than `max_bytes` of string.
std::string read_vlen_string_attribute(hid_t attr, const RawFileLayout& file,
                                       std::size_t max_bytes, std::string& out);

// The same for a scalar or 1-D attribute of `count` variable-length strings (`count` = the
// attribute's number of elements, at most 4096); `max_bytes` bounds each string.
std::string read_vlen_string_attribute(hid_t attr, const RawFileLayout& file,
                                       std::size_t max_bytes, std::size_t count,
                                       std::vector<std::string>& out);

}  // namespace railtab::lookup::detail
