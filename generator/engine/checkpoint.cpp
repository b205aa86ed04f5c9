// SPDX-License-Identifier: Apache-2.0
// Checkpoint file of an interrupted sweep: writes finished y blocks, reads them back on --resume.
// Created and reopened only through table/output_file.hpp (never through a link, a FIFO or an
// input of the run).
#include "engine/checkpoint.hpp"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

#include "core/check.hpp"
#include "table/output_file.hpp"

namespace railtab {
namespace {

constexpr char kMagic[16] = {'R', 'A', 'I', 'L', 'T', 'A', 'B', '-', 'C', 'K', 'P', 'T', '-', 'v', '1', '\n'};

struct Header {
  char magic[16];
  std::uint64_t key;
  std::uint64_t record_bytes;
};

// Reads exactly `n` bytes; false at the end of the file (a torn record) or on an error.
bool read_exact(int fd, void* buffer, std::size_t n) {
  auto* at = static_cast<char*>(buffer);
  while (n > 0) {
    const ssize_t got = ::read(fd, at, n);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    at += got;
    n -= static_cast<std::size_t>(got);
  }
  return true;
}

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
  // An existing checkpoint: a regular file of one name, not an input, not held by another run.
  fd_ = open_output_to_continue(path_);
  off_t good_end = 0;
  if (fd_ >= 0) {
    Header h{};
    const bool same = read_exact(fd_, &h, sizeof h) && std::memcmp(h.magic, kMagic, sizeof kMagic) == 0 &&
                      h.key == key_ && h.record_bytes == record_bytes_;
    if (same) {
      good_end = sizeof h;
      while (true) {
        Record r{0, std::vector<char>(record_bytes_)};
        std::uint64_t sum = 0;
        if (!read_exact(fd_, &r.block, sizeof r.block) || !read_exact(fd_, r.bytes.data(), r.bytes.size()) ||
            !read_exact(fd_, &sum, sizeof sum) || sum != record_checksum(r.block, r.bytes)) {
          break;  // end, or a torn last record
        }
        records_.push_back(std::move(r));
        good_end += static_cast<off_t>(sizeof r.block + record_bytes_ + sizeof sum);
      }
      // Drop a torn tail so appends line up.
      RAILTAB_CHECK(::ftruncate(fd_, good_end) == 0 && ::lseek(fd_, good_end, SEEK_SET) == good_end,
                    "{}: cannot cut the checkpoint file after its last whole record: {}", path_.string(),
                    std::strerror(errno));
    } else {
      discarded_ = true;
      ::close(fd_);
      fd_ = -1;
    }
  }
  if (fd_ < 0) {  // a new checkpoint: the header through a temporary renamed into place
    Header h{};
    std::memcpy(h.magic, kMagic, sizeof kMagic);
    h.key = key_;
    h.record_bytes = record_bytes_;
    OutputFile file(path_);
    write_all(file.descriptor(), std::string_view(reinterpret_cast<const char*>(&h), sizeof h), path_);
    fd_ = file.commit_and_keep_open();
  }
}

Checkpoint::~Checkpoint() {
  if (fd_ >= 0) ::close(fd_);
}

void Checkpoint::append(std::uint64_t block, const std::vector<char>& bytes) {
  RAILTAB_CHECK(fd_ >= 0 && bytes.size() == record_bytes_, "{}: bad checkpoint record", path_.string());
  const std::uint64_t sum = record_checksum(block, bytes);
  std::string record(reinterpret_cast<const char*>(&block), sizeof block);
  record.append(bytes.data(), bytes.size());
  record.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  write_all(fd_, record, path_);  // one write per record: a crash tears at most the last one
  ::fdatasync(fd_);               // a finished block survives a crash of the machine, too
}

void Checkpoint::remove() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

}  // namespace railtab
