// SPDX-License-Identifier: Apache-2.0
// Checkpoint file of an interrupted sweep: writes finished y blocks, reads them back on --resume.
#include "engine/checkpoint.hpp"

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "core/check.hpp"

namespace railtab {
namespace {

constexpr char kMagic[16] = {'R', 'A', 'I', 'L', 'T', 'A', 'B', '-', 'C', 'K', 'P', 'T', '-', 'v', '1', '\n'};

struct Header {
  char magic[16];
  std::uint64_t key;
  std::uint64_t record_bytes;
};

std::uint64_t record_checksum(std::uint64_t block, const std::vector<char>& bytes) {
  std::uint64_t h = fnv1a(std::string_view(reinterpret_cast<const char*>(&block), sizeof block));
  return fnv1a(std::string_view(bytes.data(), bytes.size()), h);
}

// Every dataset in table order: (pointer to its bytes, bytes per block, the dataset, its group).
template <class Fn>
void for_each_slice(Table& table, std::size_t blocks, std::size_t block, Fn fn) {
  for (auto& group : table.groups) {
    for (auto& d : group.datasets) {
      std::size_t element = d.is_status ? sizeof(StatusBits) : sizeof(double);
      std::size_t count = d.size();
      RAILTAB_CHECK(count % blocks == 0, "checkpoint: dataset {}/{} does not split into {} blocks", group.path,
                    d.name, blocks);
      std::size_t per_block = count / blocks * element;
      char* base = d.is_status ? reinterpret_cast<char*>(d.status.data()) : reinterpret_cast<char*>(d.values.data());
      fn(base + block * per_block, per_block, d, group);
    }
  }
}

}  // namespace

std::uint64_t fnv1a(std::string_view bytes, std::uint64_t seed) {
  std::uint64_t h = seed;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::vector<char> pack_block(const Table& table, std::size_t blocks, std::size_t block) {
  std::vector<char> out;
  Table& mutable_table = const_cast<Table&>(table);  // read only below; shares the slice walker
  for_each_slice(mutable_table, blocks, block, [&](char* data, std::size_t n, const TableDataset&, const TableGroup&) {
    out.insert(out.end(), data, data + n);
  });
  return out;
}

void unpack_block(Table& table, std::size_t blocks, std::size_t block, const std::vector<char>& bytes) {
  std::size_t at = 0;
  for_each_slice(table, blocks, block, [&](char* data, std::size_t n, const TableDataset&, const TableGroup&) {
    RAILTAB_CHECK(at + n <= bytes.size(), "checkpoint: block {} is too short", block);
    std::memcpy(data, bytes.data() + at, n);
    at += n;
  });
  RAILTAB_CHECK(at == bytes.size(), "checkpoint: block {} has {} bytes, expected {}", block, bytes.size(), at);
}

std::string first_non_finite(const Table& table, std::size_t blocks, std::size_t block) {
  std::string where;
  Table& mutable_table = const_cast<Table&>(table);  // read only below; shares the slice walker
  for_each_slice(mutable_table, blocks, block, [&](char* data, std::size_t n, const TableDataset& d, const TableGroup& g) {
    // /equilibrium_roll holds NaN where the roll search failed, by design (docs/table-format.md).
    if (!where.empty() || d.is_status || d.name == "equilibrium_roll") return;
    for (std::size_t i = 0; i < n / sizeof(double); ++i) {
      double v = 0.0;
      std::memcpy(&v, data + i * sizeof(double), sizeof v);
      if (!std::isfinite(v)) {
        where = "/" + (g.path.empty() ? d.name : g.path + "/" + d.name);
        return;
      }
    }
  });
  return where;
}

Checkpoint::Checkpoint(std::filesystem::path path, std::uint64_t key, std::size_t record_bytes)
    : path_(std::move(path)), key_(key), record_bytes_(record_bytes) {
  std::uintmax_t good_end = 0;
  if (std::filesystem::exists(path_)) {
    std::ifstream in(path_, std::ios::binary);
    Header h{};
    in.read(reinterpret_cast<char*>(&h), sizeof h);
    bool same = in && std::memcmp(h.magic, kMagic, sizeof kMagic) == 0 && h.key == key_ &&
                h.record_bytes == record_bytes_;
    if (same) {
      good_end = sizeof h;
      while (true) {
        Record r{0, std::vector<char>(record_bytes_)};
        std::uint64_t sum = 0;
        in.read(reinterpret_cast<char*>(&r.block), sizeof r.block);
        in.read(r.bytes.data(), static_cast<std::streamsize>(r.bytes.size()));
        in.read(reinterpret_cast<char*>(&sum), sizeof sum);
        if (!in || sum != record_checksum(r.block, r.bytes)) break;  // end, or a torn last record
        records_.push_back(std::move(r));
        good_end += sizeof r.block + record_bytes_ + sizeof sum;
      }
    } else {
      discarded_ = true;
    }
  }
  if (good_end > 0) {
    std::filesystem::resize_file(path_, good_end);  // drop a torn tail so appends line up
    file_ = std::fopen(path_.c_str(), "ab");
  } else {
    file_ = std::fopen(path_.c_str(), "wb");
    if (file_) {
      Header h{};
      std::memcpy(h.magic, kMagic, sizeof kMagic);
      h.key = key_;
      h.record_bytes = record_bytes_;
      if (std::fwrite(&h, sizeof h, 1, file_) != 1 || std::fflush(file_) != 0) {
        std::fclose(file_);
        file_ = nullptr;
      }
    }
  }
  RAILTAB_CHECK(file_, "{}: cannot write the checkpoint file", path_.string());
}

Checkpoint::~Checkpoint() {
  if (file_) std::fclose(file_);
}

void Checkpoint::append(std::uint64_t block, const std::vector<char>& bytes) {
  RAILTAB_CHECK(file_ && bytes.size() == record_bytes_, "{}: bad checkpoint record", path_.string());
  std::uint64_t sum = record_checksum(block, bytes);
  bool ok = std::fwrite(&block, sizeof block, 1, file_) == 1 &&
            std::fwrite(bytes.data(), 1, bytes.size(), file_) == bytes.size() &&
            std::fwrite(&sum, sizeof sum, 1, file_) == 1 && std::fflush(file_) == 0;
  RAILTAB_CHECK(ok, "{}: cannot append to the checkpoint file", path_.string());
  ::fdatasync(::fileno(file_));  // a finished block survives a crash of the machine, too
}

void Checkpoint::remove() {
  if (file_) std::fclose(file_);
  file_ = nullptr;
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

}  // namespace railtab
