// SPDX-License-Identifier: Apache-2.0
// Variable-length string attributes read with bounds checks instead of libhdf5's own read (vlen_string.hpp).
#include "vlen_string.hpp"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <vector>

namespace railtab::lookup::detail {
namespace {

// Tag of the opaque memory type that receives a variable-length string's stored heap reference.
constexpr const char* kHeapIdTag = "railtab_lookup:vlen heap reference";

// A soft conversion "variable-length string -> opaque tagged kHeapIdTag" that leaves the bytes
// as stored: H5Aread hands the attribute's raw data (the heap reference) to the conversion, so
// with this path registered H5Aread copies out the reference and never touches the heap. It
// declines every other pair of types, so no other conversion in the process changes.
herr_t keep_heap_reference(hid_t src, hid_t dst, H5T_cdata_t* cdata, std::size_t, std::size_t,
                           std::size_t, void*, void*, hid_t) {
  switch (cdata->command) {
    case H5T_CONV_INIT: {
      cdata->need_bkg = H5T_BKG_NO;
      if (H5Tget_class(src) != H5T_STRING || H5Tis_variable_str(src) <= 0) return -1;
      if (H5Tget_class(dst) != H5T_OPAQUE) return -1;
      char* tag = H5Tget_tag(dst);
      const bool ours = tag && std::strcmp(tag, kHeapIdTag) == 0;
      H5free_memory(tag);
      return ours ? 0 : -1;
    }
    case H5T_CONV_CONV:
      return H5Tget_size(src) == H5Tget_size(dst) ? 0 : -1;  // in place: the bytes stay
    case H5T_CONV_FREE:
      return 0;
  }
  return -1;
}

hid_t heap_reference_type(std::size_t bytes) {
  const hid_t t = H5Tcreate(H5T_OPAQUE, bytes);
  if (t >= 0) H5Tset_tag(t, kHeapIdTag);
  return t;
}

bool register_conversion() {
  static bool ok = [] {
    const hid_t src = H5Tcopy(H5T_C_S1);
    H5Tset_size(src, H5T_VARIABLE);
    const hid_t dst = heap_reference_type(16);
    const bool done = src >= 0 && dst >= 0 &&
                      H5Tregister(H5T_PERS_SOFT, "railtab_lookup_vlen_reference", src, dst,
                                  keep_heap_reference) >= 0;
    H5Tclose(src);
    H5Tclose(dst);
    return done;
  }();
  return ok;
}

std::uint64_t little_endian(const unsigned char* p, std::size_t n) {
  std::uint64_t v = 0;
  for (std::size_t k = n; k-- > 0;) v = (v << 8) | p[k];
  return v;
}

std::string at(std::uint64_t offset) { return "global heap collection at " + std::to_string(offset); }

// One string from its stored heap reference (length 4, collection address 8, object index 4),
// every offset and size checked against the collection and the file.
std::string string_from_heap(const unsigned char* ref, const RawFileLayout& file,
                             std::size_t max_bytes, std::string& out) {
  const std::uint64_t length = little_endian(ref, 4);
  const std::uint64_t address = little_endian(ref + 4, 8);
  const std::uint64_t index = little_endian(ref + 12, 4);
  if (length == 0) {
    out.clear();
    return "";
  }
  if (length > max_bytes)
    return "declares a string of " + std::to_string(length) + " bytes (limit " +
           std::to_string(max_bytes) + ")";
  if (index == 0) return "refers to object 0 of its global heap (free space)";

  // Collection header: "GCOL", version 1, 3 reserved, collection size (8).
  constexpr std::uint64_t kHeader = 16, kObjectHeader = 16;
  const std::uint64_t start = file.base + address;
  if (address > file.size || start > file.size || file.size - start < kHeader)
    return "refers to a global heap at " + std::to_string(address) + ", outside the file";
  std::ifstream in(file.path, std::ios::binary);
  unsigned char head[kHeader];
  if (!in.seekg(static_cast<std::streamoff>(start)) ||
      !in.read(reinterpret_cast<char*>(head), kHeader))
    return "cannot read the " + at(address);
  if (std::memcmp(head, "GCOL", 4) != 0 || head[4] != 1)
    return "refers to " + std::to_string(address) + ", which is not a global heap collection";
  const std::uint64_t size = little_endian(head + 8, 8);
  if (size < kHeader || size > file.size - start)
    return "the " + at(address) + " declares " + std::to_string(size) + " bytes, past the file end";
  // Walk the objects (index 2, references 2, reserved 4, size 8, data padded to 8) up to the
  // one referred to; every object must lie inside the collection.
  std::vector<unsigned char> obj(kObjectHeader);
  std::uint64_t p = kHeader;
  while (size - p >= kObjectHeader) {
    if (!in.seekg(static_cast<std::streamoff>(start + p)) ||
        !in.read(reinterpret_cast<char*>(obj.data()), kObjectHeader))
      return "cannot read the " + at(address);
    const std::uint64_t id = little_endian(obj.data(), 2);
    const std::uint64_t bytes = little_endian(obj.data() + 8, 8);
    if (id == 0) break;  // free space: the rest of the collection
    if (bytes > size - p - kObjectHeader)
      return "the " + at(address) + " is corrupt: object " + std::to_string(id) +
             " runs past the collection";
    if (id == index) {
      if (bytes < length)
        return "declares " + std::to_string(length) + " bytes but its heap object holds " +
               std::to_string(bytes);
      out.assign(static_cast<std::size_t>(length), '\0');
      if (!in.read(out.data(), static_cast<std::streamsize>(length)))
        return "cannot read its string from the " + at(address);
      out.resize(std::strlen(out.c_str()));  // a NUL inside ends the string, as in C
      return "";
    }
    const std::uint64_t padded = (bytes + 7) / 8 * 8;
    if (padded > size - p - kObjectHeader)
      return "the " + at(address) + " is corrupt: object " + std::to_string(id) +
             " runs past the collection";
    p += kObjectHeader + padded;
  }
  return "object " + std::to_string(index) + " is not in the " + at(address);
}

}  // namespace

std::string unchecksummed_metadata_problem(const std::string& path) {
  static constexpr unsigned char kSignature[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";  // the caller's own open reports the problem
  for (std::uint64_t offset = 0;; offset = offset == 0 ? 512 : 2 * offset) {
    unsigned char head[9] = {};
    in.clear();
    in.seekg(static_cast<std::streamoff>(offset));
    if (!in.read(reinterpret_cast<char*>(head), sizeof head)) return "";
    if (std::memcmp(head, kSignature, sizeof kSignature) != 0) continue;
    const unsigned version = head[8];
    if (version >= 2) return "";
    return "HDF5 superblock version " + std::to_string(version) +
           " (metadata without checksums): written by an old railtab (table format 1.0, no "
           "checksums) or another tool, which this reader refuses: regenerate it with "
           "`railtab generate <scene.toml>`";
  }
}

std::string raw_file_layout(hid_t object, RawFileLayout& out) {
  const hid_t file = H5Iget_file_id(object);
  if (file < 0) return "cannot find the file of the object";
  std::string problem;
  const ssize_t name_length = H5Fget_name(file, nullptr, 0);
  const hid_t fcpl = H5Fget_create_plist(file);
  hsize_t user_block = 0;
  if (name_length <= 0 || fcpl < 0 || H5Pget_userblock(fcpl, &user_block) < 0 ||
      H5Pget_sizes(fcpl, &out.sizeof_addr, &out.sizeof_size) < 0) {
    problem = "cannot read the file creation properties";
  } else {
    out.path.assign(static_cast<std::size_t>(name_length) + 1, '\0');
    H5Fget_name(file, out.path.data(), out.path.size());
    out.path.resize(static_cast<std::size_t>(name_length));
    std::error_code ec;
    out.size = std::filesystem::file_size(out.path, ec);
    if (ec) problem = "cannot read the size of " + out.path;
    out.base = user_block;
  }
  if (fcpl >= 0) H5Pclose(fcpl);
  H5Fclose(file);
  return problem;
}

std::string read_vlen_string_attribute(hid_t attr, const RawFileLayout& file,
                                       std::size_t max_bytes, std::string& out) {
  std::vector<std::string> one;
  const std::string problem = read_vlen_string_attribute(attr, file, max_bytes, 1, one);
  if (problem.empty()) out = std::move(one.at(0));
  return problem;
}

std::string read_vlen_string_attribute(hid_t attr, const RawFileLayout& file,
                                       std::size_t max_bytes, std::size_t count,
                                       std::vector<std::string>& out) {
  static std::mutex registering;  // H5Tregister is process-wide; the first loads may race
  {
    std::lock_guard lock(registering);
    if (!register_conversion()) return "cannot register the heap-reference conversion";
  }
  if (file.sizeof_addr != 8 || file.sizeof_size != 8)
    return "variable-length strings are read only from files with 8-byte addresses";
  constexpr std::size_t kMaxCount = 4096;  // a table's longest list (axis or output names) is ~50
  if (count == 0 || count > kMaxCount)
    return "holds " + std::to_string(count) + " strings (1 to " + std::to_string(kMaxCount) + " expected)";
  // The attribute's element count must be what the caller sized the buffer for.
  const hid_t space = H5Aget_space(attr);
  const hssize_t points = space >= 0 ? H5Sget_simple_extent_npoints(space) : -1;
  if (space >= 0) H5Sclose(space);
  if (points < 0 || static_cast<std::size_t>(points) != count)
    return "holds " + std::to_string(points) + " strings, not " + std::to_string(count);
  // Stored form of a variable-length string: length (4), collection address (8), index (4).
  constexpr std::size_t kRefBytes = 16;
  const hid_t mem = heap_reference_type(kRefBytes);
  if (mem < 0) return "cannot create a memory type";
  std::vector<unsigned char> refs(kRefBytes * count, 0);
  const herr_t rc = H5Aread(attr, mem, refs.data());
  H5Tclose(mem);
  if (rc < 0) return "cannot read its heap reference";
  out.assign(count, std::string());
  for (std::size_t i = 0; i < count; ++i) {
    const std::string problem = string_from_heap(refs.data() + i * kRefBytes, file, max_bytes, out[i]);
    if (!problem.empty()) return count == 1 ? problem : "string " + std::to_string(i) + ": " + problem;
  }
  return "";
}

}  // namespace railtab::lookup::detail
