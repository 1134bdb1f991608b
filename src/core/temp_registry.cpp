// SPDX-License-Identifier: GPL-3.0-or-later
// TempRegistry: fixed-size slots in chunks published through atomic pointers (see the header for
// the state diagram). Adding takes a mutex only to allocate a chunk; the signal-handler side
// reads atomics and char buffers only.
#include "core/temp_registry.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

#include <array>
#include <atomic>
#include <cstring>
#include <mutex>

#include "core/error.hpp"

namespace aq {
namespace {

enum State : int { kFree = 0, kFilling = 1, kTemp = 2, kRenaming = 3, kRenamed = 4 };

struct Slot {
  std::atomic<int> state{kFree};
  std::atomic<int> backup{0};  // 0 none, 1 a hard link, 2 the old file moved to bak
  char tmp[TempRegistry::kPathMax];
  char fin[TempRegistry::kPathMax];
  char bak[TempRegistry::kPathMax];
};

struct Chunk {
  std::array<Slot, TempRegistry::kSlotsPerChunk> slots;
};

static_assert(std::atomic<int>::is_always_lock_free);
static_assert(std::atomic<Chunk*>::is_always_lock_free);

std::array<std::atomic<Chunk*>, TempRegistry::kMaxChunks> g_chunks{};
std::mutex g_grow;

Slot& slot_of(int id) {
  return g_chunks[static_cast<std::size_t>(id / TempRegistry::kSlotsPerChunk)]
      .load(std::memory_order_acquire)
      ->slots[static_cast<std::size_t>(id % TempRegistry::kSlotsPerChunk)];
}

// Claims a free slot (kFree -> kFilling), allocating a chunk when all are taken; -1 when full.
int claim() {
  for (int c = 0; c < TempRegistry::kMaxChunks; ++c) {
    Chunk* chunk = g_chunks[static_cast<std::size_t>(c)].load(std::memory_order_acquire);
    if (chunk == nullptr) {
      const std::lock_guard<std::mutex> lock(g_grow);
      chunk = g_chunks[static_cast<std::size_t>(c)].load(std::memory_order_acquire);
      if (chunk == nullptr) {
        chunk = new Chunk;  // never freed: the handler may read it at any time
        g_chunks[static_cast<std::size_t>(c)].store(chunk, std::memory_order_release);
      }
    }
    for (int k = 0; k < TempRegistry::kSlotsPerChunk; ++k) {
      int expected = kFree;
      if (chunk->slots[static_cast<std::size_t>(k)].state.compare_exchange_strong(expected, kFilling))
        return c * TempRegistry::kSlotsPerChunk + k;
    }
  }
  return -1;
}

void copy_path(char* dst, const std::filesystem::path& p) {
  const std::string& s = p.native();
  std::memcpy(dst, s.c_str(), s.size() + 1);
}

}  // namespace

int TempRegistry::add(const std::filesystem::path& tmp, const std::filesystem::path& fin,
                      const std::filesystem::path& bak) {
  for (const auto* p : {&tmp, &fin, &bak})
    if (p->native().size() >= kPathMax)
      throw OutputError(fmt::format("{}: path longer than {} bytes", p->string(), kPathMax - 1));
  const int id = claim();
  if (id < 0) throw OutputError(fmt::format("{}: more than {} output files at once", fin.string(), kMaxSlots));
  Slot& s = slot_of(id);
  copy_path(s.tmp, tmp);
  copy_path(s.fin, fin);
  copy_path(s.bak, bak);
  s.backup.store(0, std::memory_order_relaxed);
  s.state.store(kTemp, std::memory_order_release);
  return id;
}

void TempRegistry::backed_up(int slot, bool moved) noexcept {
  slot_of(slot).backup.store(moved ? 2 : 1, std::memory_order_seq_cst);
}
void TempRegistry::renaming(int slot) noexcept { slot_of(slot).state.store(kRenaming, std::memory_order_seq_cst); }
void TempRegistry::renamed(int slot) noexcept { slot_of(slot).state.store(kRenamed, std::memory_order_seq_cst); }
void TempRegistry::release(int slot) noexcept { slot_of(slot).state.store(kFree, std::memory_order_release); }

int TempRegistry::remove_registered_temporaries() noexcept {
  int removed = 0;
  for (auto& c : g_chunks) {
    Chunk* chunk = c.load(std::memory_order_acquire);
    if (chunk == nullptr) break;  // chunks are allocated in order
    for (Slot& s : chunk->slots) {
      const int st = s.state.load(std::memory_order_acquire);
      if (st == kFree || st == kFilling) continue;
      const int backup = s.backup.load(std::memory_order_acquire);
      if ((st == kTemp || st == kRenaming) && ::unlink(s.tmp) == 0) ++removed;
      if (st == kRenaming || st == kRenamed || backup == 2) {
        // The old file back under its name (the new one goes), or no file where none was.
        if (backup != 0 ? ::rename(s.bak, s.fin) == 0 : ::unlink(s.fin) == 0) ++removed;
      } else if (backup == 1 && ::unlink(s.bak) == 0) {
        ++removed;
      }
    }
  }
  return removed;
}

int TempRegistry::in_use() noexcept {
  int n = 0;
  for (auto& c : g_chunks) {
    Chunk* chunk = c.load(std::memory_order_acquire);
    if (chunk == nullptr) break;
    for (Slot& s : chunk->slots) n += s.state.load(std::memory_order_relaxed) != kFree ? 1 : 0;
  }
  return n;
}

}  // namespace aq
