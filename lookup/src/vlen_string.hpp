// SPDX-License-Identifier: Apache-2.0
// Variable-length string attributes (legacy tables, h5py's default) read WITHOUT libhdf5's
// variable-length read: a one-byte corruption of the heap reference or of the global heap makes
// that read allocate gigabytes or read out of bounds (docs/reliability.md). Instead the attribute's raw
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

// Tables whose HDF5 metadata carry no checksums (superblock version 0 or 1: railtab format 1.0,
// or other writers' defaults) are refused BEFORE libhdf5 opens them: libhdf5 parses object
// headers and attribute messages without bounds checks, so one corrupt byte in such a file can
// make it read freed or out-of-bounds memory (found by fuzz_table_load). From
// superblock 2 on, every metadata block is checksummed and verified before it is parsed.
// Reads the superblock signature ("\211HDF\r\n\032\n" at byte 0, 512, 1024, 2048, ...) and the
// version byte after it from the raw file. Returns "" if the version is >= 2 or no signature
// is found (the caller's HDF5 check then reports "not an HDF5 file"), else the problem.
std::string unchecksummed_metadata_problem(const std::string& path);

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
