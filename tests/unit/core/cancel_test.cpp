// SPDX-License-Identifier: GPL-3.0-or-later
// Cooperative cancellation (core/cancel.hpp): a request counts only inside the scope of its token,
// on every thread; scopes nest; no stage starts, and a running one throws when it ends, once the
// request is made (tests/unit/io/cancel_writer_test.cpp: the file writer).
#include "core/cancel.hpp"

#include <gtest/gtest.h>

#include <string>
#include <thread>

#include "core/log.hpp"
#include "core/report.hpp"

namespace aq::unit_core_cancel_test {
namespace {

TEST(Cancel, ARequestCountsOnlyInsideItsScope) {
  CancelToken token;
  token.request();
  EXPECT_TRUE(token.requested());
  EXPECT_FALSE(cancel_requested());
  EXPECT_NO_THROW(throw_if_cancelled());
  {
    const CancelScope scope(token);
    EXPECT_TRUE(cancel_requested());
    EXPECT_THROW(throw_if_cancelled(), Cancelled);
    bool seen = false;
    std::thread other([&seen] { seen = cancel_requested(); });  // an OpenMP worker, say
    other.join();
    EXPECT_TRUE(seen);
  }
  EXPECT_FALSE(cancel_requested());
}

TEST(Cancel, ScopesNestAndARequestFromAnotherThreadIsSeen) {
  CancelToken outer, inner;
  const CancelScope a(outer);
  {
    const CancelScope b(inner);
    std::thread other([&inner] { inner.request(); });
    other.join();
    EXPECT_TRUE(cancel_requested());
  }
  EXPECT_FALSE(cancel_requested());  // the outer token again
  try {
    outer.request();
    throw_if_cancelled();
    FAIL() << "no Cancelled";
  } catch (const Cancelled& e) {
    EXPECT_EQ(e.exit_code(), 130);  // SIGINT's, for a command line that maps it
    EXPECT_STREQ(e.what(), "interrupted");
  }
}

TEST(Cancel, NoStageStartsOrEndsQuietlyAfterARequest) {
  CancelToken token;
  const CancelScope scope(token);
  Report report;
  StageScope running("running", &report, Logger::null());
  token.request();
  EXPECT_THROW(StageScope("next", &report, Logger::null()), Cancelled);
  EXPECT_THROW(running.done("ends"), Cancelled);  // the stage is recorded, then the stop
  EXPECT_EQ(report.root()["stages"].size(), 1U);
}

}  // namespace
}  // namespace aq::unit_core_cancel_test
