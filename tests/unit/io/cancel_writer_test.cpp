// SPDX-License-Identifier: GPL-3.0-or-later
// A stop request (core/cancel.hpp) while a file is written: FileWriter does not hand another block
// to the kernel, and the OutputSet the file belongs to leaves nothing behind (no temporary).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/cancel.hpp"
#include "core/output_files.hpp"
#include "io/file_writer.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_io_cancel_writer_test {
namespace {

TEST(CancelWriter, NoBlockIsWrittenAfterARequestAndNothingIsLeft) {
  aq::testing::TempDir dir;
  CancelToken token;
  const CancelScope scope(token);
  {
    OutputSet out(dir.path());
    FileWriter f(out.temp_path("big.txt"));
    f.text(std::string(FileWriter::kChunkBytes + 1, 'x'));
    f.maybe_flush();  // the first block goes out
    EXPECT_FALSE(std::filesystem::is_empty(dir.path()));
    token.request();
    f.text(std::string(FileWriter::kChunkBytes + 1, 'y'));
    EXPECT_THROW(f.maybe_flush(), Cancelled);
    EXPECT_LT(std::filesystem::file_size(out.pending_path("big.txt")), 2 * FileWriter::kChunkBytes);
  }  // neither committed nor kept: the OutputSet removes its temporary
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace aq::io::unit_io_cancel_writer_test
