// SPDX-License-Identifier: GPL-3.0-or-later
// Cooperative cancellation (see cancel.hpp).
#include "core/cancel.hpp"

namespace aq {

namespace {

std::atomic<const CancelToken*> g_token{nullptr};

}  // namespace

CancelScope::CancelScope(const CancelToken& token) noexcept
    : previous_(g_token.exchange(&token, std::memory_order_acq_rel)) {}

CancelScope::~CancelScope() { g_token.store(previous_, std::memory_order_release); }

bool cancel_requested() noexcept {
  const CancelToken* t = g_token.load(std::memory_order_acquire);
  return t != nullptr && t->requested();
}

void throw_if_cancelled() {
  if (cancel_requested()) throw Cancelled("interrupted");
}

}  // namespace aq
