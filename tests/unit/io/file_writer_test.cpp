// SPDX-License-Identifier: GPL-3.0-or-later
// FileWriter (io/file_writer.hpp): chunks written by a second thread while the next one fills
// arrive whole and in order, size() counts every byte, and a failing write is reported.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/error.hpp"
#include "io/file_writer.hpp"

namespace unit_io_file_writer_test {

namespace fs = std::filesystem;
using aq::io::FileWriter;

namespace {

// Byte k of the test stream.
char byte_at(std::size_t k) { return static_cast<char>((k * 2654435761u) >> 13); }

}  // namespace

TEST(FileWriter, ManyChunksArriveWholeAndInOrder) {
  const fs::path p = fs::temp_directory_path() / "aq_file_writer_chunks.bin";
  // 5.3 chunks, appended in pieces of odd sizes so chunk boundaries fall inside pieces.
  const std::size_t total = FileWriter::kChunkBytes * 5 + FileWriter::kChunkBytes / 3;
  std::string piece;
  std::int64_t closed = 0;
  {
    FileWriter f(p);
    std::size_t k = 0;
    while (k < total) {
      piece.clear();
      for (std::size_t n = 0; n < 1237 && k < total; ++n, ++k) piece.push_back(byte_at(k));
      f.text(piece);
      EXPECT_EQ(f.size(), static_cast<std::int64_t>(k));
      f.maybe_flush();
      EXPECT_EQ(f.size(), static_cast<std::int64_t>(k));
    }
    closed = f.close();
  }
  EXPECT_EQ(closed, static_cast<std::int64_t>(total));
  ASSERT_EQ(fs::file_size(p), total);
  std::ifstream in(p, std::ios::binary);
  const std::string got((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t bad = 0;
  for (std::size_t k = 0; k < total; ++k) bad += got[k] != byte_at(k) ? 1 : 0;
  EXPECT_EQ(bad, 0u);
  fs::remove(p);
}

// /dev/full fails every write with ENOSPC: the failure of a chunk written in the background
// surfaces at the next flush or at close, naming the file.
TEST(FileWriter, BackgroundWriteFailureIsReported) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  FileWriter f("/dev/full");
  const std::string chunk(FileWriter::kChunkBytes, 'x');
  try {
    for (int k = 0; k < 3; ++k) {
      f.text(chunk);
      f.maybe_flush();
    }
    f.close();
    FAIL() << "no error reported";
  } catch (const aq::OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("write failed"), std::string::npos) << e.what();
  }
}

// A writer destroyed while a chunk is being written (an exception unwinding) waits for it.
TEST(FileWriter, DestroyedWhileWritingLeavesNoThreadBehind) {
  const fs::path p = fs::temp_directory_path() / "aq_file_writer_unwind.bin";
  {
    FileWriter f(p);
    f.text(std::string(FileWriter::kChunkBytes + 10, 'y'));
    f.maybe_flush();
  }
  EXPECT_EQ(fs::file_size(p), FileWriter::kChunkBytes + 10);
  fs::remove(p);
}

}  // namespace unit_io_file_writer_test
